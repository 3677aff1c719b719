# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Small sample files shipped with the package.

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
"""

from pathlib import Path

__all__ = ["sample_file", "SAMPLES", "DESCRIPTIONS"]

#: What each shipped sample file is, in one line (above, in full).
DESCRIPTIONS = {
    "sample.sp3": "SP3-c orbits of G01, G05, E11: 4 epochs at 15 min, 2023-01-25 (synthetic)",
    "sample.obx": "ORBEX attitude quaternions of the same satellites, first minute (synthetic)",
    "gnss_sample.sp3": "SP3-d orbits of 16 GNSS satellites, 3 h at 15 min, 2023-01-25 "
                       "(synthetic)",
    "gnss_sample.rnx": "RINEX 3.04 observations of those satellites from GGAO12M, 20 min at "
                       "30 s (synthetic)",
    "igs_satellite_metadata.snx": "IGS satellite metadata SINEX, release 2404 (real)",
    "stations.ecsv": "the station catalogue of astropy_feedrot.stations.catalogue",
    "vla_day2_8chan.uvfits": "VLA, 19 antennas, RR LL RL LR, 8 channels at 36.3 GHz (real)",
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
