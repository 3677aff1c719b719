# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Antennas of a visibility file whose feed rotation cannot be computed as the file
describes them.

A file can hold antennas that no `~astropy_feedrot.Antenna` describes: an
orbiting antenna (space VLBI: ``MNTSTA`` 2, ``MOUNT`` ``'SPACE-HALCA'``),
whose feed turns with its spacecraft; a mount label with no model (phased,
``'BIZARRE'``, an empty or unknown ``MOUNT``, a ``MNTSTA`` code whose writer
the file does not reveal); receptors that are not a pair (linear receptors
at one angle, as LWA and PAPER Measurement Sets give ``RECEPTOR_ANGLE`` [0,
0]). The readers keep such an antenna as an `UnusableAntenna` (with
``unusable='keep'``), so that the other antennas can still be listed
(``feedrot antennas``) and corrected:

* an orbiting antenna's baselines are left as they are, named in one
  warning (`UncorrectedBaselinesWarning`);
* an antenna whose mount has no model takes the station catalogue's with
  ``mounts='catalogue'`` (`~astropy_feedrot.visibilities.catalogue_mounts`),
  and is otherwise refused, named with the reason;
* an antenna whose receptors are not a pair is refused, named with the
  reason, unless receptors are given for it (``feeds=``, ``--feeds X,Y``).
"""

from ..core.exceptions import UncorrectedBaselinesWarning, warn_caller
from ..engine.antenna import Antenna

__all__ = ["UnusableAntenna", "UNUSABLE", "PROBLEMS", "check_unusable", "given_feeds",
           "usable_antennas", "warn_skipped", "orbiting_reason"]

#: What a reader does with an antenna it cannot describe: ``'raise'`` (a
#: ValueError naming it) or ``'keep'`` (an `UnusableAntenna` in its place).
UNUSABLE = ("raise", "keep")

#: The kinds of problem of an `UnusableAntenna`: an orbiting antenna, a mount
#: label with no model, receptors that cannot be used, or an element of an
#: aperture array (`~astropy_feedrot.stations.aperture_arrays`).
PROBLEMS = ("orbiting", "mount", "receptors", "aperture array")


class UnusableAntenna:
    """An antenna of a file that cannot be corrected as the file describes it.

    Parameters
    ----------
    location : `~astropy.coordinates.EarthLocation`
        Its position as the file gives it (for an orbiting antenna, the
        position the file holds, often its tracking station's).
    name : str
        Its name in the file.
    problem : {'orbiting', 'mount', 'receptors', 'aperture array'}
        What is wrong: an orbiting antenna, a mount label with no model,
        receptors that cannot be used, or an element of an aperture array.
    reason : str
        Why, with the label or the values the file holds, and what to do.
    label : object, optional
        The file's mount label (``MNTSTA`` code, ``MOUNT`` string).
    mount, focus : optional
        The mount and focus, known when the problem is the receptors.
    vertical : {'geodetic', 'geocentric'}, optional
        As `~astropy_feedrot.Antenna`.
    rotator : optional
        As `~astropy_feedrot.Antenna`.
    receptors : `~astropy_feedrot.Receptors`, optional
        Its receptors, where the problem is its mount and the file gives
        usable ones.
    receptors_problem : str, optional
        Why its receptors cannot be used, where they cannot (with any
        problem).

    Attributes
    ----------
    location, name, problem, reason, label, mount, focus, vertical, rotator
        As given.
    receptors, receptors_problem
        As given.

    Examples
    --------
    >>> from astropy_feedrot import get_antenna
    >>> from astropy_feedrot.visibilities import UnusableAntenna
    >>> halca = UnusableAntenna(get_antenna("DSS65").location, "RZ", "orbiting",
    ...                         "MNTSTA 2: an orbiting antenna", label=2)
    >>> halca
    UnusableAntenna('RZ', 'orbiting': MNTSTA 2: an orbiting antenna)
    """

    def __init__(self, location, name, problem, reason, *, label=None, mount=None,
                 focus=None, vertical="geodetic", rotator=None, receptors=None,
                 receptors_problem=None):
        if problem not in PROBLEMS:
            raise ValueError(f"problem must be one of {PROBLEMS}, got {problem!r}")
        self.location = location
        self.name = name
        self.problem = problem
        self.reason = reason
        self.label = label
        self.mount = mount
        self.focus = focus
        self.vertical = vertical
        self.rotator = rotator
        self.receptors = receptors
        self.receptors_problem = receptors_problem

    def __repr__(self):
        return f"UnusableAntenna({self.name!r}, {self.problem!r}: {self.reason})"

    def with_receptors(self, receptors):
        """The `~astropy_feedrot.Antenna` it is with these receptors (problem
        ``'receptors'`` only: the others have no mount to give it).

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy_feedrot import AltAzMount, get_antenna
        >>> from astropy_feedrot.antennas.receptors import Receptors
        >>> from astropy_feedrot.visibilities import UnusableAntenna
        >>> lwa = UnusableAntenna(get_antenna("VLA_W9").location, "LWA001", "receptors",
        ...                       "parallel receptors", mount=AltAzMount())
        >>> lwa.with_receptors(Receptors("XY", [90, 0] * u.deg)).receptors
        Receptors('XY', [90.0, 0.0] * u.deg)
        """
        if self.problem != "receptors":
            raise ValueError(f"antenna {self.name}: {self.reason}")
        return Antenna(self.location, self.mount, self.focus, name=self.name,
                       vertical=self.vertical, receptors=receptors, rotator=self.rotator)

    def with_mount(self, mount, focus):
        """What it is with this mount and focus (problem ``'mount'`` only): an
        `~astropy_feedrot.Antenna`, or an `UnusableAntenna` of problem
        ``'receptors'`` when its receptors cannot be used.

        Examples
        --------
        >>> from astropy_feedrot import AltAzMount, get_antenna
        >>> from astropy_feedrot.visibilities import UnusableAntenna
        >>> fd = get_antenna("FD-VLBA")
        >>> bare = UnusableAntenna(fd.location, "FD", "mount", "MOUNT is empty",
        ...                        receptors=fd.receptors)
        >>> bare.with_mount(AltAzMount(), None).mount
        AltAzMount()
        """
        if self.problem != "mount":
            raise ValueError(f"antenna {self.name}: {self.reason}")
        if self.receptors_problem is not None:
            return UnusableAntenna(self.location, self.name, "receptors",
                                   self.receptors_problem, label=self.label, mount=mount,
                                   focus=focus, vertical=self.vertical, rotator=self.rotator)
        return Antenna(self.location, mount, focus, name=self.name, vertical=self.vertical,
                       receptors=self.receptors, rotator=self.rotator)


def orbiting_reason(label):
    """The reason of an orbiting antenna, its file's label ``label`` (``'MNTSTA 2'``).

    Examples
    --------
    >>> from astropy_feedrot.visibilities.unusable import orbiting_reason
    >>> orbiting_reason("MNTSTA 2")[:32]
    'MNTSTA 2: an orbiting antenna (s'
    """
    return (f"{label}: an orbiting antenna (space VLBI), whose feed turns with its "
            "spacecraft, whose attitude the file does not give; a correction leaves its "
            "baselines as they are")


def check_unusable(unusable):
    """``unusable`` checked (one of `UNUSABLE`).

    Examples
    --------
    >>> from astropy_feedrot.visibilities.unusable import check_unusable
    >>> check_unusable("keep")
    'keep'
    """
    if unusable not in UNUSABLE:
        raise ValueError(f"unusable must be one of {UNUSABLE}, got {unusable!r}")
    return unusable


def given_feeds(antennas, feeds):
    """The antennas with ``feeds`` given to those whose receptors could not be used.

    Parameters
    ----------
    antennas : mapping
        ``{antenna number: Antenna or UnusableAntenna}``.
    feeds : `~astropy_feedrot.Receptors`, mapping or None
        As `~astropy_feedrot.visibilities.with_receptors`: the receptors of
        every antenna, or ``{antenna number or name: Receptors}``.

    Returns
    -------
    dict
        A new mapping, the antennas of problem ``'receptors'`` that
        ``feeds`` names replaced by `~astropy_feedrot.Antenna` objects.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot import AltAzMount, get_antenna
    >>> from astropy_feedrot.antennas.receptors import Receptors
    >>> from astropy_feedrot.visibilities.unusable import UnusableAntenna, given_feeds
    >>> lwa = UnusableAntenna(get_antenna("VLA_W9").location, "LWA001", "receptors",
    ...                       "parallel receptors", mount=AltAzMount())
    >>> given_feeds({1: lwa}, Receptors("XY", [90, 0] * u.deg))[1].receptors.types
    'XY'
    """
    if feeds is None:
        return dict(antennas)
    out = {}
    for number, antenna in antennas.items():
        if isinstance(antenna, UnusableAntenna) and antenna.problem == "receptors":
            given = feeds if not hasattr(feeds, "get") else \
                feeds.get(number, feeds.get(antenna.name))
            if given is not None:
                antenna = antenna.with_receptors(given)
        out[number] = antenna
    return out


def _label(number, antenna):
    return f"{number} ({antenna.name})" if antenna.name else f"{number}"


def usable_antennas(antennas, numbers, where):
    """The antennas the rows can use, and the orbiting ones whose rows are left alone.

    Parameters
    ----------
    antennas : mapping
        ``{antenna number: Antenna or UnusableAntenna}``.
    numbers : iterable of int
        The antennas the rows use.
    where : str
        The data, for the messages.

    Returns
    -------
    usable : dict
        The antennas that are `~astropy_feedrot.Antenna` objects.
    skipped : list of int
        The orbiting antennas among ``numbers``: their rows are to be left
        as they are (`warn_skipped`).

    Raises
    ------
    ValueError
        If an antenna of ``numbers`` has a mount without a model or
        receptors that cannot be used: one message naming every such
        antenna with its reason.

    Examples
    --------
    >>> from astropy_feedrot import get_antenna
    >>> from astropy_feedrot.visibilities.unusable import UnusableAntenna, usable_antennas
    >>> halca = UnusableAntenna(get_antenna("DSS65").location, "RZ", "orbiting",
    ...                         "MNTSTA 2: an orbiting antenna")
    >>> usable, skipped = usable_antennas({1: get_antenna("FD-VLBA"), 5: halca}, [1, 5],
    ...                                   "x.idifits")
    >>> sorted(usable), skipped
    ([1], [5])
    """
    used = sorted({int(n) for n in numbers})
    refused = [n for n in used if isinstance(antennas.get(n), UnusableAntenna)
               and antennas[n].problem != "orbiting"]
    if refused:
        reasons = {}  # antennas of one reason together
        for n in refused:
            reasons.setdefault(antennas[n].reason, []).append(n)
        listed = "; ".join(
            (f"antenna {_label(ns[0], antennas[ns[0]])}" if len(ns) == 1 else
             f"antennas {', '.join(_label(n, antennas[n]) for n in ns[:10])}"
             + (f" and {len(ns) - 10} more" if len(ns) > 10 else "")) + f": {reason}"
            for reason, ns in list(reasons.items())[:10])
        more = f"; and {len(reasons) - 10} more reasons" if len(reasons) > 10 else ""
        raise ValueError(f"{where}: {len(refused)} antenna{'s' if len(refused) > 1 else ''} "
                         f"cannot be corrected: {listed}{more}")
    skipped = [n for n in used if isinstance(antennas.get(n), UnusableAntenna)]
    usable = {n: a for n, a in antennas.items() if not isinstance(a, UnusableAntenna)}
    return usable, skipped


def warn_skipped(antennas, skipped, rows, total, where):
    """Warn once that the baselines of the orbiting antennas ``skipped`` were left alone.

    Parameters
    ----------
    antennas : mapping
        ``{antenna number: Antenna or UnusableAntenna}``.
    skipped : list of int
        The orbiting antennas (`usable_antennas`).
    rows, total : int
        The rows left as they were, and all rows.
    where : str
        The data, for the message.

    Examples
    --------
    >>> import warnings
    >>> from astropy_feedrot import get_antenna
    >>> from astropy_feedrot.visibilities.unusable import UnusableAntenna, warn_skipped
    >>> halca = UnusableAntenna(get_antenna("DSS65").location, "RZ", "orbiting",
    ...                         "MNTSTA 2: an orbiting antenna")
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn_skipped({5: halca}, [5], 10, 100, "x.idifits")
    >>> print(str(caught[0].message)[:78])
    x.idifits: the 10 of 100 rows on baselines to the orbiting antenna 5 (RZ) are
    """
    if not skipped:
        return
    names = ", ".join(_label(n, antennas[n]) for n in skipped)
    plural = "s" if len(skipped) > 1 else ""
    warn_caller(f"{where}: the {rows} of {total} rows on baselines to the orbiting "
                f"antenna{plural} {names} are left as they were (an orbiting antenna's feed "
                "turns with its spacecraft, whose attitude the file does not give); the "
                "ground baselines are corrected", UncorrectedBaselinesWarning)
