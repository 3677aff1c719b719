# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The antennas of UVFITS files.

`uvfits_antennas` reads the ``AIPS AN`` table of a UVFITS file: names,
positions, mounts and receptors, as `~astropy_feedrot.Antenna` objects.
:doc:`/fitsidi` gives the conventions (shared with FITS-IDI) and their
sources.
"""

from .antenna_tables import read_antennas

__all__ = ["uvfits_antennas"]


def uvfits_antennas(path, *, vertical="geodetic", software=None, unusable="raise"):
    """The antennas of a UVFITS file, from its ``AIPS AN`` table.

    Parameters
    ----------
    path : str or os.PathLike
        The UVFITS file.
    vertical : {'geodetic', 'geocentric'}, optional
        The local vertical of each `~astropy_feedrot.Antenna`; CASA uses the
        geocentric one.
    software : str, optional
        Whose ``MNTSTA`` convention: ``'fits-idi:casacore'`` (3.7 and later),
        ``'fits-idi:casacore<3.7'``, ``'fits-idi:casacore<3.2'``,
        ``'fits-idi:difx'`` or ``'fits-idi:pyuvdata'``. By default the
        convention of the program that wrote the file
        (`~astropy_feedrot.visibilities.writing_program`).
    unusable : {'raise', 'keep'}, optional
        Raise for an antenna that cannot be described (default), or keep it
        as an `~astropy_feedrot.visibilities.UnusableAntenna` (see
        `~astropy_feedrot.visibilities.antenna_tables.read_antennas`).

    Returns
    -------
    dict
        ``{antenna number (NOSTA): Antenna}``, each with its name
        (``ANNAME``), ITRF position (``STABXYZ`` and ``ARRAYX/Y/Z``), mount
        and focus (``MNTSTA``) and `~astropy_feedrot.antennas.receptors.Receptors`
        (``POLTYA``, ``POLAA``, ``POLTYB``, ``POLAB``).

    Raises
    ------
    FileNotFoundError
        If there is no such file.
    FITSFormatError
        If the file has no ``AIPS AN`` table (or several: subarrays), lacks a
        column or keyword, holds non-finite positions, positions in another
        frame, or a non-zero array centre from a writer other than pyuvdata.
    ValueError
        For a ``MNTSTA`` code whose meaning depends on a writer the file
        does not reveal (codes 6 and up; the message says which
        ``software=`` to pass), a code with no feed-rotation model
        (orbiting, phased, unknown), receptor angles that differ between IFs,
        unknown receptor types, or a position off the Earth; the message
        names the antenna.

    Examples
    --------
    A two-antenna table as casacore writes it (absolute positions, ``ARRAYX
    = 0``; Pie Town and Los Alamos from the package's station list):

    >>> import os, tempfile
    >>> import numpy as np
    >>> from astropy.io import fits
    >>> from astropy_feedrot.visibilities import uvfits_antennas
    >>> primary = fits.PrimaryHDU()
    >>> primary.header["ORIGIN"] = "casacore"
    >>> an = fits.BinTableHDU.from_columns([
    ...     fits.Column("ANNAME", "8A", array=["PT", "LA"]),
    ...     fits.Column("STABXYZ", "3D", array=[[-1640953.9, -5014816.0, 3575411.8],
    ...                                         [-1449752.6, -4975298.6, 3709123.8]]),
    ...     fits.Column("NOSTA", "1J", array=[1, 2]),
    ...     fits.Column("MNTSTA", "1J", array=[0, 0]),
    ...     fits.Column("POLTYA", "1A", array=["R", "R"]),
    ...     fits.Column("POLAA", "1E", array=[0.0, 0.0]),
    ...     fits.Column("POLTYB", "1A", array=["L", "L"]),
    ...     fits.Column("POLAB", "1E", array=[0.0, 0.0])], name="AIPS AN")
    >>> for key in ("ARRAYX", "ARRAYY", "ARRAYZ"):
    ...     an.header[key] = 0.0
    >>> an.header["FRAME"] = "ITRF"
    >>> path = os.path.join(tempfile.mkdtemp(), "two.uvfits")
    >>> fits.HDUList([primary, an]).writeto(path)
    >>> antennas = uvfits_antennas(path)
    >>> antennas[1].name, antennas[1].mount, antennas[2].receptors
    ('PT', AltAzMount(), Receptors('RL', [0.0, 0.0] * u.deg))
    """
    return read_antennas(path, "uvfits", vertical=vertical, software=software,
                         unusable=unusable)
