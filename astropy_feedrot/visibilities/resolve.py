# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The antennas of a file resolved once, the same way for every format.

Every reader (`~astropy_feedrot.visibilities.fitsidi_antennas`,
`~astropy_feedrot.visibilities.uvfits_antennas`,
`~astropy_feedrot.visibilities.ms_antennas`,
`~astropy_feedrot.visibilities.antennas_from_uvdata`, the MSv4 reader)
gives the antennas as the file describes them. `resolve_antennas` then takes
the steps that decide what can be corrected, in one order for every format
and for ``feedrot antennas`` alike:

1. an aperture array (`~astropy_feedrot.stations.aperture_arrays`, by the
   file's telescope name) makes every antenna an
   `~astropy_feedrot.visibilities.UnusableAntenna` of problem
   ``'aperture array'``, whatever its mount says;
2. the mounts are compared with the station catalogue's
   (`~astropy_feedrot.visibilities.catalogue_mounts`);
3. receptors given by the user replace those the file's could not
   (`~astropy_feedrot.visibilities.unusable.given_feeds`).

The refusal itself (`~astropy_feedrot.visibilities.unusable.usable_antennas`)
names every antenna with its reason.
"""
from ..stations.aperture_arrays import aperture_array, aperture_array_reason
from .catalogue import catalogue_mounts
from .unusable import UnusableAntenna, given_feeds

__all__ = ["resolve_antennas", "mark_aperture_array", "refuse_aperture_array"]


def _aperture_reason(telescope, catalogue):
    """Why the first of the telescope names that is an aperture array is refused, or
    None."""
    names = [telescope] if telescope is None or isinstance(telescope, str) else telescope
    for name in names:
        description = aperture_array(name, catalogue)
        if description is not None:
            return aperture_array_reason(name, description)
    return None


def mark_aperture_array(antennas, telescope, catalogue=None):
    """The antennas, every one unusable if ``telescope`` is an aperture array.

    Parameters
    ----------
    antennas : mapping
        ``{antenna number: Antenna or UnusableAntenna}``.
    telescope : str, sequence of str or None
        The file's telescope name (or names, as the ``OBSERVATION`` rows of
        a Measurement Set give them).
    catalogue : `~astropy_feedrot.stations.StationCatalogue`, path or False, optional
        As `~astropy_feedrot.stations.aperture_arrays.aperture_array`.

    Returns
    -------
    antennas : dict
        A new mapping.
    aperture : bool
        Whether the telescope is an aperture array.

    Examples
    --------
    >>> from astropy_feedrot import get_antenna
    >>> from astropy_feedrot.visibilities.resolve import mark_aperture_array
    >>> antennas, aperture = mark_aperture_array({0: get_antenna("VLA_W9")}, "MWA")
    >>> aperture, antennas[0].problem
    (True, 'aperture array')
    """
    reason = _aperture_reason(telescope, catalogue)
    if reason is None:
        return dict(antennas), False
    out = {}
    for number, antenna in antennas.items():
        label = getattr(antenna, "label", None)
        out[number] = UnusableAntenna(antenna.location, antenna.name, "aperture array",
                                      reason, label=label, vertical=antenna.vertical)
    return out, True


def refuse_aperture_array(telescope, catalogue=None, where="the file"):
    """Refuse the data of an aperture array before anything is read or written.

    Parameters
    ----------
    telescope : str, sequence of str or None
        The file's telescope name (or names).
    catalogue : `~astropy_feedrot.stations.StationCatalogue`, path or False, optional
        As `~astropy_feedrot.stations.aperture_arrays.aperture_array`.
    where : str, optional
        The file, for the message.

    Raises
    ------
    ValueError
        If ``telescope`` is an aperture array: the message is the reason every
        antenna of `mark_aperture_array` gives.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.resolve import refuse_aperture_array
    >>> refuse_aperture_array("VLA")
    >>> refuse_aperture_array("MWA", where="x.ms")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: x.ms: the telescope 'MWA' is an aperture array (the Murchison ...
    """
    reason = _aperture_reason(telescope, catalogue)
    if reason is not None:
        raise ValueError(f"{where}: {reason}")


def resolve_antennas(antennas, *, telescope=None, mounts="file", catalogue=None, feeds=None,
                     numbers=None, where="the file"):
    """The antennas of a file as a correction uses them: aperture arrays marked, the
    mounts compared with the catalogue's, the receptors the user gives.

    Parameters
    ----------
    antennas : mapping
        ``{antenna number: Antenna or UnusableAntenna}``, as a reader gives
        them (``unusable='keep'``).
    telescope : str or sequence of str, optional
        The file's telescope name (or names): an aperture array is refused by
        it (`mark_aperture_array`).
    mounts : {'file', 'catalogue'}, optional
        As `~astropy_feedrot.visibilities.catalogue_mounts`.
    catalogue : `~astropy_feedrot.stations.StationCatalogue`, path or False, optional
        The station catalogue (default: the embedded one); False for none.
    feeds : `~astropy_feedrot.Receptors` or mapping, optional
        Receptors for the antennas whose own cannot be used
        (`~astropy_feedrot.visibilities.unusable.given_feeds`).
    numbers : iterable of int, optional
        Only these antennas are compared with the catalogue (those the data
        use); default all.
    where : str, optional
        The file, for the messages.

    Returns
    -------
    dict
        A new ``{antenna number: Antenna or UnusableAntenna}``.

    Warns
    -----
    CatalogueMountWarning
        As `~astropy_feedrot.visibilities.catalogue_mounts`.

    Examples
    --------
    >>> from astropy_feedrot import get_antenna
    >>> from astropy_feedrot.visibilities.resolve import resolve_antennas
    >>> resolve_antennas({1: get_antenna("FD-VLBA")}, telescope="VLBA")[1].name
    'FD-VLBA'
    >>> resolve_antennas({1: get_antenna("FD-VLBA")}, telescope="LOFAR")[1].problem
    'aperture array'
    """
    antennas, aperture = mark_aperture_array(antennas, telescope, catalogue)
    if aperture:  # the catalogue's mounts would make dishes of them again
        return antennas
    antennas, _ = catalogue_mounts(antennas, mounts, catalogue, numbers=numbers, where=where)
    return given_feeds(antennas, feeds)
