"""Make sma_test_corrchunk1.mir from the original sma_test.mir (pyuvdata 3.1.3 wheel, pyuvdata/data/sma_test.mir).

SRC = directory holding the original sma_test.mir (e.g. unzip the wheel). Keeps only correlator
chunk 1 (2 spectral windows x 16384 channels), cross-correlations only, and re-writes it with
pyuvdata's MirParser.write (so the Mir container is pyuvdata-written; values are the real SMA data).
"""
import os, shutil, numpy as np, warnings
warnings.simplefilter("ignore")
from astropy.coordinates import EarthLocation
from astropy.coordinates.sites import SiteRegistry
_reg = SiteRegistry(); _reg.add_site(["offline-placeholder"], EarthLocation.from_geocentric(6378137.0, 0, 0, unit="m"))
EarthLocation._site_registry = _reg          # pyuvdata's known_telescopes() would otherwise download sites.json
from pyuvdata.uvdata.mir_parser import MirParser
SRC = os.environ.get("SRC", "/tmp/cand")
mp = MirParser(os.path.join(SRC, "sma_test.mir"), has_auto=False)
mp.select(where=("corrchunk", "eq", [1]))
mp.load_data(load_cross=True)
out = "sma_trim.mir"; shutil.rmtree(out, ignore_errors=True)
mp.write(out, load_data=True)
os.system(f"tar czf sma_test_corrchunk1.mir.tar.gz {out} && rm -rf {out}")
