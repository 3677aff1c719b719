# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Small sample files shipped with the package.

``feedrot samples`` lists them; ``feedrot samples NAME`` prints the path of
one, which is how the printed examples name them. Those not made by a test
script are made by ``samples/make_samples.py`` of the source tree, which
says where each comes from.

``gps.tle``
    Element sets of three GPS satellites at 2023-01-25: SVN 76 (PRN 5,
    catalogue number 41328) as in Table 2 of the paper, and two hypothetical
    GPS-like satellites (90060 and 90240: circular, 20200 km, 55 deg,
    ascending nodes at 60 and 240 deg) as in the network example of the
    documentation.
``sample.sp3``
    An SP3-c orbit file: three satellites (G01, G05, E11) on circular orbits,
    four epochs at 15-minute spacing on 2023-01-25, GPS time. Synthetic.
``sample.obx``
    An ORBEX file with yaw-steering attitude quaternions (Earth-fixed to body)
    for the same satellites over the first minute. Synthetic.
``gnss_sample.sp3``, ``gnss_sample.rnx``
    Synthetic GNSS files made by ``tests/data/gnss/make_samples.py``
    (`astropy_feedrot.gnss.synthetic`): an SP3-d orbit file of 16 simulated
    satellites (GPS, Galileo, GLONASS, BeiDou; circular orbits with their
    systems' planes and periods) over 3 hours at 15 minutes on 2023-01-25,
    GPS time, long enough for the default 10-point interpolation; and a
    RINEX 3.04 observation file of the same satellites at 30 s for 20
    minutes, three frequencies each, seen from GGAO12M. Made-up numbers,
    not measurements.
``igs_satellite_metadata.snx``
    The IGS satellite metadata SINEX file, release 2404 (file created
    2026-02-04, ``%=SNX 2.02 DLR 26:035:25117``; P. Steigenberger and O.
    Montenbruck, IGS Satellite Metadata File Description 1.10,
    doi:10.57677/metadata-sinex), as published at
    https://files.igs.org/pub/station/general/igs_satellite_metadata.snx;
    this copy, unchanged (SHA-256 7aaabd25...6859a7db), from the repository
    nfb2021/canvodpy at commit 3bb22a17 (path
    ``packages/canvod-readers/src/canvod/readers/gnss_specs/data/``). Read by
    `~astropy_feedrot.io.read_satellite_metadata`.
``stations.ecsv``
    The station catalogue of `astropy_feedrot.stations.catalogue` (positions cited in
    its header).
``vla_day2_8chan.uvfits``
    Real data: two 10-s integrations of the VLA (19 antennas, 153 baselines,
    RR, LL, RL and LR, 8 channels at 36.3 GHz) from the VLA tutorial data set
    of CASA, as exported to UVFITS by casacore and distributed with pyuvdata's
    test data; cut down from 64 channels by
    ``tests/data/uvdata/scripts/make_package_sample.py``.
``difx_k08161.idifits``
    Real data: the FITS-IDI file ``K08161.0.FITS`` that DiFX 1.5.0 wrote for
    the MPIfR's DiFX test experiment k08161 (Ny-Alesund and Wettzell, RR only,
    2008-06-09), as distributed in aplavin/VLBIFiles.jl-testdata
    (``misc/K08161.0.FITS``), unchanged.
``codg0080.20i.Z``, ``codg0090.20i.Z``
    Real data: CODE's global ionosphere maps (IONEX, hourly, 5 x 2.5 deg) of
    2020 January 8 and 9, as spinifex ships them with its tests; for
    ``feedrot faraday --ionex``, which needs spinifex (the ``ionosphere``
    extra).
``rm_effelsberg.ecsv``
    A made-up table of rotation measures (Effelsberg, 0.5 and 1.5 rad/m2 on
    2024-06-01 and 02) for ``feedrot faraday --rm-table``.
``rm_constant.ecsv``
    A made-up rotation measure, 2 rad/m2 for every antenna from 2008 to
    2025, for ``feedrot correct --rm-table`` on the visibility samples.
``vla_sim.ms``
    A Measurement Set (a directory) that CASA's simulator wrote: four VLA
    pads, two spectral windows, ``DATA`` and a ``MODEL_DATA`` column
    (``tests/data/real/casa_sim_vla_2spw.ms.tar.gz`` without CASA's
    ``CORRECTED_DATA``). Synthetic. Reading it needs python-casacore (the
    ``ms`` extra). Correct a copy in place, not this one
    (``feedrot samples --copy vla_sim.ms``).
"""

import shutil
from pathlib import Path

__all__ = ["sample_file", "copy_sample", "SAMPLES", "DESCRIPTIONS"]

#: What each shipped sample file is, in one line (above, in full).
DESCRIPTIONS = {
    "gps.tle": "element sets of GPS SVN 76 (41328) and two GPS-like satellites, 2023-01-25",
    "sample.sp3": "SP3-c orbits of G01, G05, E11: 4 epochs at 15 min, 2023-01-25 (synthetic)",
    "sample.obx": "ORBEX attitude quaternions of the same satellites, first minute (synthetic)",
    "gnss_sample.sp3": "SP3-d orbits of 16 GNSS satellites, 3 h at 15 min, 2023-01-25 "
                       "(synthetic)",
    "gnss_sample.rnx": "RINEX 3.04 observations of those satellites from GGAO12M, 20 min at "
                       "30 s (synthetic)",
    "igs_satellite_metadata.snx": "IGS satellite metadata SINEX, release 2404 (real)",
    "stations.ecsv": "the station catalogue of astropy_feedrot.stations.catalogue",
    "vla_day2_8chan.uvfits": "VLA, 19 antennas, RR LL RL LR, 8 channels at 36.3 GHz (real)",
    "difx_k08161.idifits": "FITS-IDI of DiFX 1.5.0, Ny-Alesund and Wettzell, RR only, "
                           "2008-06-09 (real)",
    "codg0080.20i.Z": "IONEX: CODE's global ionosphere maps of 2020-01-08, hourly (real)",
    "codg0090.20i.Z": "IONEX: CODE's global ionosphere maps of 2020-01-09, hourly (real)",
    "rm_effelsberg.ecsv": "rotation measures of EFLSBERG, 2024-06-01 and 02 (made up)",
    "rm_constant.ecsv": "a rotation measure of 2 rad/m2 for every antenna, 2008 to 2025 "
                        "(made up)",
    "vla_sim.ms": "Measurement Set of CASA's simulator: 4 VLA pads, 2 windows, DATA and "
                  "MODEL_DATA (synthetic; the ms extra)",
}

#: Names of the shipped sample files.
SAMPLES = tuple(DESCRIPTIONS)


def sample_file(name):
    """Path of a sample file shipped with the package.

    Parameters
    ----------
    name : str
        One of `SAMPLES`.

    Returns
    -------
    pathlib.Path

    Raises
    ------
    ValueError
        For an unknown name (listing the samples).

    Examples
    --------
    >>> from astropy_feedrot.data import sample_file
    >>> sample_file("sample.sp3").name
    'sample.sp3'
    """
    if name not in SAMPLES:
        raise ValueError(f"name must be one of {SAMPLES}, got {name!r}")
    return Path(__file__).parent / name


def copy_sample(name, target=None, overwrite=False):
    """Copy a sample file (or the Measurement Set, a folder) to change it.

    The copy has the contents, not the permissions, of the installed sample
    (which may be read-only), so that it can be corrected in place.

    Parameters
    ----------
    name : str
        One of `SAMPLES`.
    target : str or path-like, optional
        Where to copy it; by default ``name`` in the current directory.
    overwrite : bool, optional
        Replace an existing file or folder ``target``; refused otherwise.

    Returns
    -------
    pathlib.Path
        ``target``.

    Raises
    ------
    ValueError
        For an unknown name (listing the samples).
    FileExistsError
        If ``target`` exists and ``overwrite`` is false.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from astropy_feedrot.data import copy_sample
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     copy = copy_sample("vla_sim.ms", Path(folder) / "obs.ms")
    ...     (copy / "table.dat").is_file()
    True
    """
    source = sample_file(name)
    target = Path(name if target is None else target)
    if target.exists() or target.is_symlink():
        if not overwrite:
            raise FileExistsError(f"{target} exists; remove it, work on it as it is, or "
                                  "pass overwrite=True to replace it with the sample")
        if target.is_dir() and not target.is_symlink():
            shutil.rmtree(target)
        else:
            target.unlink()
    if source.is_dir():
        shutil.copytree(source, target, copy_function=shutil.copyfile)
    else:
        shutil.copyfile(source, target)
    return target
