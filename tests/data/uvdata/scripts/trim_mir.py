"""Make sma_test_corrchunk1.mir.tar.gz from sma_test.mir of the pyuvdata 3.1.3 wheel.

SRC is the directory holding the original (pyuvdata/data/sma_test.mir of the unpacked wheel).
Keeps correlator chunk 1 (2 spectral windows x 16384 channels), cross-correlations only, and
writes it with pyuvdata's MirParser.write: the container is written by pyuvdata, the values
are the real SMA data. Run it where the archive should appear.
"""
import os
import shutil
import tarfile
import warnings

from astropy.coordinates import EarthLocation
from astropy.coordinates.sites import SiteRegistry


def main():
    warnings.simplefilter("ignore")
    # pyuvdata asks astropy's site registry, which would download sites.json.
    registry = SiteRegistry()
    registry.add_site(["offline-placeholder"],
                      EarthLocation.from_geocentric(6378137.0, 0, 0, unit="m"))
    EarthLocation._site_registry = registry
    from pyuvdata.uvdata.mir_parser import MirParser

    source = os.environ.get("SRC", ".")
    parser = MirParser(os.path.join(source, "sma_test.mir"), has_auto=False)
    parser.select(where=("corrchunk", "eq", [1]))
    parser.load_data(load_cross=True)
    out = "sma_trim.mir"
    shutil.rmtree(out, ignore_errors=True)
    parser.write(out, load_data=True)
    with tarfile.open("sma_test_corrchunk1.mir.tar.gz", "w:gz") as archive:
        archive.add(out)
    shutil.rmtree(out)


if __name__ == "__main__":
    main()
