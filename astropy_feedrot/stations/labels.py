# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Mount labels of other software, to and from this package's mounts and foci.

Visibility files, correlator inputs and station catalogues name an antenna's
mount and focus with labels of their own: an integer ``MNTSTA`` code in the
antenna table of FITS-IDI and UVFITS files, a ``MOUNT`` string in a
Measurement Set, a DiFX mount name, a VEX ``axis_type``, a pyuvdata
``mount_type``, a geodetic station-catalogue code. `mount_from_label` turns
such a label into a ``(mount, focus)`` pair for `~astropy_feedrot.Antenna`;
`label_from_mount` writes one back, and refuses what a convention cannot
express. The ``MNTSTA`` codes 6 and 7 mean different things to casacore,
DiFX and pyuvdata, so a code is always read with the software that wrote it.

The tables of each convention, with the sources they were checked against
and the traps of each program, are in `astropy_feedrot.stations.label_tables`.
"""

import numpy as np

from ..antennas.focus import (
    BeamWaveguideFocus,
    CassegrainFocus,
    GregorianFocus,
    MirrorTrain,
    NasmythFocus,
    PrimeFocus,
    as_focus,
)
from ..antennas.mounts import FixedAxisMount, StationaryMount, as_mount
from .label_tables import (
    DESCRIPTIONS,
    KNOWN_LABELS,
    LOOKUP,
    MAKERS,
    NO_MODEL,
    NOTES,
    OLD_ERAS,
    RICHMOND_AXIS,
    SOFTWARE,
    TABLES,
    VEX_NASMYTH,
    check_software,
    label_key,
    one_scalar,
)

__all__ = ["SOFTWARE", "KNOWN_LABELS", "known_labels", "mount_from_label", "label_from_mount",
           "is_orbiting"]


def known_labels(software):
    """The labels of a software's convention that `mount_from_label` accepts.

    Parameters
    ----------
    software : str
        One of `SOFTWARE`.

    Returns
    -------
    list
        Integers for the ``fits-idi:*`` conventions, strings otherwise (the
        VEX ones are ``axis_type`` values). Strings are matched
        case-insensitively, so each is listed once, in the case the software
        writes it. Labels with no feed-rotation model (orbiting, phased,
        other) are included: they are known, and rejected with a reason.

    Raises
    ------
    ValueError
        For an unknown ``software``.

    Examples
    --------
    >>> from astropy_feedrot.stations.labels import known_labels
    >>> known_labels("geodetic")
    ['AZEL', 'EQUA', 'X-YN', 'X-YE', 'RICH', 'NASR', 'NASP', 'NASL', 'NASM', 'BWG', 'GNSS']
    """
    return list(KNOWN_LABELS[check_software(software)])


def is_orbiting(label, software):
    """Whether a mount label names an orbiting antenna (space VLBI).

    Parameters
    ----------
    label : int or str
        One label, as `mount_from_label` takes it.
    software : str
        Whose convention: one of `SOFTWARE`.

    Returns
    -------
    bool
        True for the labels of orbiting antennas (``MNTSTA`` 2; casacore
        ``ORBITING`` and ``SPACE-HALCA``; DiFX ``SPACE``; pyuvdata
        ``orbiting``); False for every other label, known or not.

    Raises
    ------
    ValueError
        For an unknown ``software``.

    Examples
    --------
    >>> from astropy_feedrot.stations.labels import is_orbiting
    >>> is_orbiting(2, "fits-idi:difx"), is_orbiting("SPACE-HALCA", "casacore")
    (True, True)
    >>> is_orbiting(0, "fits-idi:difx")
    False
    """
    software = check_software(software)
    try:
        key = label_key(software, one_scalar(label))
    except (TypeError, ValueError):
        return False
    entry = LOOKUP[software].get(key)
    return entry is not None and entry[1] == "orbiting"


def _join(words, conjunction="and"):
    words = list(words)
    if len(words) == 1:
        return words[0]
    return ", ".join(words[:-1]) + f" {conjunction} " + words[-1]


def _shown(software, label):
    """A label as the text of a message."""
    if software == "vex":
        axis_type, nasmyth = label
        return f"axis_type {axis_type!r}" + (f", nasmyth {nasmyth!r}" if nasmyth else "")
    return repr(label)


def _elsewhere(label, software):
    """A hint naming the other conventions that know ``label``, or ''."""
    others = []
    for other in SOFTWARE:
        if other == software or other in OLD_ERAS:
            continue
        try:
            key = label_key(other, label)
        except (TypeError, ValueError):
            continue
        if key in LOOKUP[other]:
            others.append(other)
    if not others:
        return ""
    hint = (f"{label!r} is a {_join(others)} label; use "
            + " or ".join(f"software={other!r}" for other in others))
    codes = [other for other in others if other.startswith("fits-idi:")]
    if len(codes) > 1 and label_key(codes[0], label) in (6, 7):
        hint += " (codes 6 and 7 mean different mounts to each)"
    return hint


def _listing(software):
    return ", ".join(repr(label) for label in KNOWN_LABELS[software])


def _lookup(software, label):
    """The kind of ``label`` in ``software``'s table; ValueError if unknown."""
    try:
        key = label_key(software, label)
    except (TypeError, ValueError):
        hint = _elsewhere(label, software)
        if hint:
            raise ValueError(f"{label!r} is not a {software} mount label: {hint}") from None
        raise
    entry = LOOKUP[software].get(key)
    if entry is None:
        hint = _elsewhere(label, software)
        hint = f"; {hint}" if hint else ""
        what = "axis_type" if software == "vex" else "mount label"
        raise ValueError(
            f"unknown {software} {what} {label!r}{hint}. The {software} labels are "
            f"{_listing(software)}"
        )
    return entry


def _vex_focus(nasmyth, axis_type, kind):
    """The focus of a VEX 2 per-band ``nasmyth`` value."""
    if nasmyth is None:
        return None
    if isinstance(nasmyth, bytes):
        nasmyth = nasmyth.decode("ascii", "replace")
    if not isinstance(nasmyth, str):
        raise TypeError(f"VEX nasmyth must be a string ('right', 'left' or 'none') or None, "
                        f"got {type(nasmyth).__name__}")
    value = nasmyth.strip().lower()
    if value not in VEX_NASMYTH:
        raise ValueError(f"VEX nasmyth must be one of {tuple(VEX_NASMYTH)} or None, got "
                         f"{nasmyth!r}")
    handedness = VEX_NASMYTH[value]
    if handedness is None:
        return None
    if kind != "alt-az":
        raise ValueError(
            f"VEX nasmyth = {value} needs axis_type az:el (a Nasmyth focus is defined for an "
            f"alt-az mount), got {axis_type!r}; describe other optics with a MirrorTrain"
        )
    return NasmythFocus(handedness)


def mount_from_label(label, software, *, nasmyth=None):
    """The mount and focus named by another software's mount label.

    Parameters
    ----------
    label : int, str, or a 1-d sequence or array of them
        One label, or a column of labels (a list, tuple or 1-d numpy array
        of strings or integers, e.g. the ``MNTSTA`` column of an antenna
        table). For the ``fits-idi:*`` conventions, the ``MNTSTA`` code of the
        antenna table (an integer, a numpy integer or an integer-valued
        string such as ``"4"``). Otherwise the mount string, matched
        case-insensitively after stripping blanks: a Measurement Set
        ``MOUNT`` (``"casacore"``), a DiFX mount (``"difx"``), a VEX
        ``$ANTENNA`` ``axis_type`` such as ``"az:el"`` or ``"x:yns"``
        (``"vex"``; blanks anywhere are ignored), a pyuvdata ``mount_type``
        (``"pyuvdata"``) or a station-catalogue code (``"geodetic"``).
        `known_labels` lists them.
    software : str
        Whose convention: one of `SOFTWARE`.
    nasmyth : {'right', 'left', 'none'}, optional
        VEX 2 only: the ``nasmyth`` value of the band observed; ``'right'``
        or ``'left'`` turns ``az:el`` into a Nasmyth focus.

    Returns
    -------
    tuple or list of tuple
        For one label, the pair ``(mount, focus)`` below; for a column, a
        list with one such pair per label.
    mount : `~astropy_feedrot.antennas.mounts.Mount`
        `~astropy_feedrot.AltAzMount`, `~astropy_feedrot.EquatorialMount`,
        `~astropy_feedrot.XYMount`, `~astropy_feedrot.StationaryMount` (pyuvdata
        ``fixed``, geodetic ``GNSS``), or a `~astropy_feedrot.FixedAxisMount`
        (geodetic ``RICH``).
    focus : `~astropy_feedrot.antennas.focus.Focus` or None
        `~astropy_feedrot.NasmythFocus` or `~astropy_feedrot.BeamWaveguideFocus`
        when the label names one; None when it says nothing about the focus
        (`~astropy_feedrot.Antenna` then assumes a Cassegrain focus, and a
        prime or Gregorian focus gives the same feed rotation).

    Raises
    ------
    ValueError
        For an unknown ``software``; for a label the convention does not
        know (the message lists the ones it knows, and names the conventions
        that do know the label, if any); for a label with no feed-rotation
        model here (orbiting antennas, phased arrays, "other"); for a code
        that is not a whole number; for a bad ``nasmyth``, or one given for
        another axis type or another software.
    TypeError
        For a label of the wrong kind (a bool, a float for a mount string, a
        column of more than one dimension).

    The errors of a column name the row (``labels[3]: ...``).

    Notes
    -----
    The foci follow the signs of casacore, DiFX/HOPS, pyuvdata and VTD:
    Nasmyth right is :math:`\\Psi + E` and left :math:`\\Psi - E` (Eq 38),
    beam waveguide right :math:`\\Psi + E - A` and left :math:`\\Psi - E + A`
    (Eq 39). The module docstring gives the source file checked for each
    convention, and how X-Y without a direction (the east-west form) and the
    geodetic ``BWG`` (right-handed) are read.

    Examples
    --------
    >>> from astropy_feedrot.stations.labels import mount_from_label
    >>> mount_from_label("ALT-AZ+BWG-R", "casacore")
    (AltAzMount(), BeamWaveguideFocus(handedness='right'))
    >>> mount_from_label("x:yns", "vex")
    (XYMount(axis='north'), None)
    >>> mount_from_label("az:el", "vex", nasmyth="right")
    (AltAzMount(), NasmythFocus(handedness='right'))

    ``MNTSTA`` 6 depends on who wrote the file:

    >>> mount_from_label(6, "fits-idi:casacore")
    (AltAzMount(), BeamWaveguideFocus(handedness='right'))
    >>> mount_from_label(6, "fits-idi:difx")
    (XYMount(axis='north'), None)

    and, for casacore, on its version (6 was ``BIZARRE`` before 3.7):

    >>> mount_from_label(6, "fits-idi:casacore<3.7")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: 6 (fits-idi:casacore<3.7) has no feed-rotation model here: ... 'BIZARRE' ...

    A column of labels gives a list of pairs:

    >>> import numpy as np
    >>> mount_from_label(np.array([0, 4]), "fits-idi:difx")
    [(AltAzMount(), None), (AltAzMount(), NasmythFocus(handedness='right'))]
    """
    software = check_software(software)
    if nasmyth is not None and software != "vex":
        raise ValueError(f"nasmyth is the VEX 2 per-band value, for software='vex' only; "
                         f"the {software} label carries the focus itself")
    if _is_column(label):
        return _column(label, software, nasmyth)
    return _one(one_scalar(label), software, nasmyth)


def _is_column(label):
    """Whether ``label`` is a column of labels (a list, tuple or array with axes)."""
    return isinstance(label, (list, tuple)) or (isinstance(label, np.ndarray) and label.ndim)


def _column(labels, software, nasmyth):
    """``[(mount, focus), ...]`` for a 1-d column of labels; errors name the row."""
    if isinstance(labels, np.ndarray) and labels.ndim != 1:
        raise TypeError(f"a column of labels is 1-d, got an array of shape {labels.shape}")
    pairs = []
    for row, label in enumerate(labels):
        if _is_column(label):
            raise TypeError(f"labels[{row}] is itself a sequence ({label!r}); give a flat "
                            "column of labels")
        try:
            pairs.append(_one(one_scalar(label), software, nasmyth))
        except (TypeError, ValueError) as error:
            raise type(error)(f"labels[{row}]: {error}") from None
    return pairs


def _one(label, software, nasmyth):
    """The (mount, focus) of one scalar label."""
    _, kind = _lookup(software, label)
    if kind not in MAKERS:
        raise ValueError(f"{label!r} ({software}) has no feed-rotation model here: "
                         f"{NO_MODEL[kind]}")
    mount, focus = MAKERS[kind]()
    if software == "vex":
        focus = _vex_focus(nasmyth, label, kind)
    return mount, focus


_AXES = {
    "alt-az": ("enu", (0.0, 0.0, 1.0)),
    "equatorial": ("itrs", (0.0, 0.0, 1.0)),
    "xy-north": ("enu", (0.0, 1.0, 0.0)),
    "xy-east": ("enu", (1.0, 0.0, 0.0)),
    "richmond": ("enu", RICHMOND_AXIS),
}


def _axis_kind(mount):
    """The kind of a fixed-axis mount from its axis, or None for another axis."""
    for kind, (frame, axis) in _AXES.items():
        if mount.frame == frame and np.allclose(mount.axis, axis, rtol=0, atol=1e-12):
            return kind
    return None


def _kind(mount, focus):
    """The kind of label a mount and focus need; ValueError if no convention has one."""
    if isinstance(focus, MirrorTrain):
        raise ValueError(
            f"no software labels a MirrorTrain ({focus!r}): it is traced mirror by mirror. "
            "Label the closed form it reduces to instead: MirrorTrain.yebes40m() is "
            "NasmythFocus('right') and MirrorTrain.wark30m() BeamWaveguideFocus('right'), "
            "each up to a constant"
        )
    conventional = focus is None or isinstance(focus, (PrimeFocus, CassegrainFocus,
                                                       GregorianFocus))
    if isinstance(mount, StationaryMount):
        if not conventional:
            raise ValueError(f"a StationaryMount has no optics to add terms; {focus!r} "
                             "needs a steerable mount")
        return "stationary"
    if not isinstance(mount, FixedAxisMount):
        raise ValueError(f"no software labels the mount {mount!r}")
    kind = _axis_kind(mount)
    if kind is None:
        raise ValueError(
            f"no software labels the fixed axis of {mount!r}: the labels name the local "
            "vertical (alt-az), the celestial pole (equatorial), a horizontal north-south "
            "or east-west axis (X-Y) and the Richmond axis (geodetic 'RICH'); pass the "
            "FixedAxisMount to Antenna directly"
        )
    if conventional:
        return kind
    if not isinstance(focus, (NasmythFocus, BeamWaveguideFocus)):
        raise ValueError(f"no software labels the focus {focus!r}")
    if kind != "alt-az":
        raise ValueError(f"{type(focus).__name__} is defined for an AltAzMount, not for "
                         f"{mount!r}; no software labels that combination")
    prefix = "nasmyth" if isinstance(focus, NasmythFocus) else "bwg"
    return f"{prefix}-{focus.handedness}"


def _written(software, kind):
    """The label ``software`` writes for ``kind``, or None."""
    for label, known in TABLES[software]:
        if known == kind:
            if software == "vex":
                return label, None
            return label
    if software == "vex" and kind.startswith("nasmyth-"):
        return "az:el", kind[len("nasmyth-"):]
    return None


def label_from_mount(mount, focus=None, software=None):
    """The label another software uses for a mount and focus.

    Parameters
    ----------
    mount : `~astropy_feedrot.antennas.mounts.Mount`
        `~astropy_feedrot.AltAzMount`, `~astropy_feedrot.EquatorialMount`,
        `~astropy_feedrot.XYMount`, `~astropy_feedrot.StationaryMount`, or a
        `~astropy_feedrot.FixedAxisMount` whose axis is one of those (or
        VTD's Richmond axis).
    focus : `~astropy_feedrot.antennas.focus.Focus`, optional
        None, `~astropy_feedrot.PrimeFocus`, `~astropy_feedrot.CassegrainFocus`
        or `~astropy_feedrot.GregorianFocus` (all give the plain label of the
        mount), or `~astropy_feedrot.NasmythFocus` /
        `~astropy_feedrot.BeamWaveguideFocus` on an alt-az mount.
    software : str
        Whose convention: one of `SOFTWARE` (required).

    Returns
    -------
    int, str or tuple
        The ``MNTSTA`` code (int) for the ``fits-idi:*`` conventions; for
        ``"vex"`` the tuple ``(axis_type, nasmyth)`` with ``nasmyth``
        ``'right'``, ``'left'`` or None (no ``nasmyth`` statement); the
        mount string otherwise, in the case the software writes it.

    Raises
    ------
    TypeError
        If ``mount`` or ``focus`` is not an instance of the package's classes.
    ValueError
        For an unknown or missing ``software``; if no convention labels the
        combination (a `~astropy_feedrot.MirrorTrain`, another fixed axis, a
        Nasmyth or beam-waveguide focus on another mount); if this
        ``software`` cannot express it (e.g. a beam waveguide in DiFX, VEX
        or pyuvdata, a north-south X-Y mount in casacore or pyuvdata, whose
        X-Y is the east-west one): the message names the conventions that
        can.

    Examples
    --------
    >>> from astropy_feedrot import AltAzMount, NasmythFocus, XYMount
    >>> from astropy_feedrot.stations.labels import label_from_mount
    >>> label_from_mount(AltAzMount(), NasmythFocus("left"), software="casacore")
    'ALT-AZ+NASMYTH-L'
    >>> label_from_mount(AltAzMount(), NasmythFocus("left"), software="fits-idi:difx")
    5
    >>> label_from_mount(AltAzMount(), NasmythFocus("right"), software="vex")
    ('az:el', 'right')
    >>> label_from_mount(XYMount("north"), software="geodetic")
    'X-YN'
    """
    software = check_software(software)
    mount = as_mount(mount)
    if focus is not None:
        focus = as_focus(focus)
    kind = _kind(mount, focus)
    label = _written(software, kind)
    if label is not None:
        return label
    note = NOTES.get((software, kind))
    note = f"; {note}" if note else ""
    others = [(other, _written(other, kind)) for other in SOFTWARE
              if other != software and other not in OLD_ERAS]
    others = [f"{other} ({_shown(other, label)})" for other, label in others
              if label is not None]
    raise ValueError(f"{software} has no mount label for {DESCRIPTIONS[kind]}{note}. It can "
                     f"be labelled in {_join(others, 'or')}")
