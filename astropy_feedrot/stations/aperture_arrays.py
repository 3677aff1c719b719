# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Aperture arrays: telescopes whose elements are fixed to the ground.

An aperture array (MWA, LOFAR, the LWA stations, OVRO-LWA, HERA, PAPER,
SKA-Low and its prototypes AAVS and EDA) points by delays, not by turning:
its dipoles or tiles keep their azimuths while the beam is steered
electronically. What such an array records of a polarized source is the
direction-dependent response of its elements (a beam Jones matrix, from the
array's beam model), not the turning of a feed: no mount of this package
describes it, whatever ``MOUNT`` or ``MNTSTA`` the file holds (Birli writes
``ALT-AZ`` for the MWA's tiles, pyuvdata ``'phased'`` or ``'fixed'``).
`aperture_array` recognises one by the telescope name of a file, in the
list `APERTURE_ARRAYS` or as a station of the catalogue whose elements are
fixed to the ground (a `~astropy_feedrot.StationaryMount`), so that every
visibility format refuses it with the same reason (`aperture_array_reason`).
"""
import re

from ..antennas.mounts import StationaryMount
from .catalogue import default_catalogue, read_catalogue

__all__ = ["APERTURE_ARRAYS", "aperture_array", "aperture_array_reason"]

#: The aperture arrays recognised by name: the key form of a name (upper
#: case, letters and digits only) begins with one of these. Sources: the
#: telescope names pyuvdata 3.2 knows with ``mount_type`` 'phased' or 'fixed'
#: (``pyuvdata/telescopes.py``, ``KNOWN_TELESCOPES``: HERA, MWA, OVRO-LWA,
#: PAPER_SA), and the names the arrays' own writers put in TELESCOPE_NAME
#: (Birli and cotter: ``MWA``; LOFAR's DP3: ``LOFAR``; LWA's ``LWA1``,
#: ``LWA-SV``; SKA-Low's ``SKA-Low``, ``AAVS2``, ``AAVS3``, ``EDA2``).
APERTURE_ARRAYS = {
    "MWA": "the Murchison Widefield Array",
    "LOFAR": "the Low-Frequency Array",
    "OVROLWA": "the OVRO Long Wavelength Array",
    "LWA": "a Long Wavelength Array station",
    "HERA": "the Hydrogen Epoch of Reionization Array",
    "PAPER": "the Precision Array for Probing the Epoch of Reionization",
    "SKALOW": "SKA-Low",
    "AAVS": "an SKA-Low Aperture Array Verification System station",
    "EDA": "an SKA-Low Engineering Development Array",
}


def _key(name):
    return re.sub(r"[^0-9A-Z]", "", str(name).upper())


def aperture_array(telescope, catalogue=None):
    """What aperture array a telescope name stands for, or None.

    Parameters
    ----------
    telescope : str or None
        A file's telescope name (``TELESCOPE_NAME``, ``TELESCOP``,
        ``ARRNAM``, pyuvdata's ``telescope.name``).
    catalogue : `~astropy_feedrot.stations.StationCatalogue`, path or False, optional
        Also a station (or network) of this catalogue whose elements are
        fixed to the ground; the embedded catalogue by default, False for
        the names of `APERTURE_ARRAYS` only.

    Returns
    -------
    str or None
        The array's description, or None for a telescope that is no
        aperture array (or no name).

    Examples
    --------
    >>> from astropy_feedrot.stations.aperture_arrays import aperture_array
    >>> aperture_array("MWA")
    'the Murchison Widefield Array'
    >>> aperture_array("OVRO_LWA")
    'the OVRO Long Wavelength Array'
    >>> aperture_array("VLA") is None
    True
    """
    key = _key(telescope or "")
    if not key:
        return None
    for prefix, description in APERTURE_ARRAYS.items():
        if key.startswith(prefix):
            return description
    if catalogue is False:
        return None
    catalogue = default_catalogue() if catalogue is None else (
        catalogue if hasattr(catalogue, "stations_named") else read_catalogue(catalogue))
    for station in catalogue.stations_named(telescope):
        if isinstance(catalogue.get_antenna(station).mount, StationaryMount):
            return f"the catalogue's {station}, whose elements are fixed to the ground"
    return None


def aperture_array_reason(telescope, description):
    """Why an aperture array's data are not corrected, and what to do instead.

    Examples
    --------
    >>> from astropy_feedrot.stations.aperture_arrays import aperture_array_reason
    >>> print(aperture_array_reason("MWA", "the Murchison Widefield Array")[:60])
    the telescope 'MWA' is an aperture array (the Murchison Wide
    """
    return (f"the telescope {str(telescope).strip()!r} is an aperture array ({description}): "
            "its elements are fixed to the ground and its beams are steered by delays, so "
            "what it records of a polarized source is its elements' direction-dependent "
            "response, not a feed rotation, whatever the file's mount says; correct it "
            "with the array's beam model instead")
