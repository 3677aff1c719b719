# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Make the sample files that the printed examples name, in ``astropy_feedrot/data``.

Run from the repository root (README.md here says where each comes from)::

    python samples/make_samples.py --vlbifiles PATH/TO/VLBIFiles.jl-testdata

``gps.tle``
    The element set of GPS SVN 76 of the paper's Table 2
    (`astropy_feedrot.applied.simulations.GPS_SVN76_TLE`) and two hypothetical
    GPS-like satellites (circular, 20200 km, 55 deg, ascending nodes 60 and
    240 deg at 2023-01-25T00:00 UTC; `~astropy_feedrot.TLEOrbit.from_elements`,
    as in docs/network.rst).
``difx_k08161.idifits``
    ``misc/K08161.0.FITS`` of aplavin/VLBIFiles.jl-testdata, copied whole
    (checked against its SHA-1).
``codg0080.20i.Z``, ``codg0090.20i.Z``
    CODE's global ionosphere maps of 2020 January 8 and 9, as spinifex ships
    them with its tests (``spinifex/data/tests``; needs spinifex installed),
    copied whole.
``rm_effelsberg.ecsv``
    A made-up table of rotation measures for ``feedrot faraday --rm-table``:
    Effelsberg, 0.5 and 1.5 rad/m2 on 2024-06-01 and 02 at 00:00 UTC.
``rm_constant.ecsv``
    A made-up rotation measure, 2 rad/m2 for every antenna from 2008 to 2025,
    for ``feedrot correct --rm-table`` on the visibility samples.
``vla_sim.ms``
    The Measurement Set that CASA's simulator wrote for the tests,
    ``tests/data/real/casa_sim_vla_2spw.ms.tar.gz``, without its
    ``CORRECTED_DATA`` column (CASA's, which ``feedrot correct`` would refuse
    to overwrite); ``MODEL_DATA`` kept. Needs python-casacore.
"""

import argparse
import hashlib
import shutil
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path

import astropy.units as u
from astropy.table import QTable
from astropy.time import Time

from astropy_feedrot import TLEOrbit
from astropy_feedrot.applied.simulations import GPS_SVN76_TLE

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "astropy_feedrot" / "data"
K08161 = "misc/K08161.0.FITS"
K08161_SHA1 = "8628431e8fd0a94e006818bee3d29b294957ff15"
MS_ARCHIVE = ROOT / "tests" / "data" / "real" / "casa_sim_vla_2spw.ms.tar.gz"


def make_tle(path):
    date = Time("2023-01-25T00:00", scale="utc")
    lines = ["GPS SVN 76", *GPS_SVN76_TLE]
    for raan in (60, 240):
        orbit = TLEOrbit.from_elements(date, inclination=55 * u.deg, raan=raan * u.deg,
                                       altitude=20200 * u.km, satnum=90000 + raan)
        lines += [f"GPS-LIKE {raan}", orbit.line1, orbit.line2]
    path.write_text("\n".join(lines) + "\n")


def copy_k08161(testdata, path):
    """The file as it is in the repository (a git checkout or a bare mirror)."""
    testdata = Path(testdata)
    if (testdata / K08161).is_file():
        raw = (testdata / K08161).read_bytes()
    else:
        raw = subprocess.run(["git", "-C", str(testdata), "show", f"HEAD:{K08161}"],
                             check=True, capture_output=True).stdout
    if hashlib.sha1(raw).hexdigest() != K08161_SHA1:
        sys.exit(f"{K08161} of {testdata} is not the file described (SHA-1 {K08161_SHA1})")
    path.write_bytes(raw)


def copy_ionex(data):
    from astropy_feedrot.ionosphere import sample_ionex  # spinifex's files

    for path in sample_ionex("codg00[89]0.20i.Z"):
        shutil.copyfile(path, data / path.name)


def make_rm_table(path):
    QTable({"time": Time(["2024-06-01T00:00", "2024-06-02T00:00"], scale="utc"),
            "rm": [0.5, 1.5] * u.rad / u.m**2,
            "antenna": ["EFLSBERG"] * 2}).write(path, overwrite=True)


def make_rm_constant(path):
    QTable({"time": Time(["2008-01-01T00:00", "2025-01-01T00:00"], scale="utc"),
            "rm": [2.0, 2.0] * u.rad / u.m**2}).write(path, overwrite=True)


def make_ms(path):
    from casacore.tables import table  # the ms extra

    with tempfile.TemporaryDirectory() as work:
        with tarfile.open(MS_ARCHIVE) as archive:
            archive.extractall(work, filter="data")
        (ms,) = Path(work).glob("*.ms")
        with table(str(ms), readonly=False, ack=False) as t:
            t.removecols("CORRECTED_DATA")
        # A deep copy writes the table anew, without the removed column's files.
        with table(str(ms), ack=False) as t:
            if path.exists():
                shutil.rmtree(path)
            t.copy(str(path), deep=True)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--vlbifiles", required=True, metavar="DIR",
                        help="a clone (or bare mirror) of aplavin/VLBIFiles.jl-testdata")
    args = parser.parse_args(argv)
    make_tle(DATA / "gps.tle")
    copy_k08161(args.vlbifiles, DATA / "difx_k08161.idifits")
    copy_ionex(DATA)
    make_rm_table(DATA / "rm_effelsberg.ecsv")
    make_rm_constant(DATA / "rm_constant.ecsv")
    make_ms(DATA / "vla_sim.ms")


if __name__ == "__main__":
    main()
