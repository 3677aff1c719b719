# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Make ``BL146_1.trim.fits`` from ``pkg-data/BL146_1.fits`` of
aplavin/VLBIFiles.jl-testdata (see README.md here for its source).

Run as ``python make_bl146.py PATH/TO/BL146_1.fits``. The file is the VLBA
hardware correlator's FITS-IDI sample of the NASA GSFC FITS registry (10
stations, 4 bands x 8 channels x RR/LL/RL/LR, 1000 rows). The trimmed copy keeps
the tables a correction and CASA's ``importfitsidi`` read (the primary
header, ARRAY_GEOMETRY, SOURCE, ANTENNA, FREQUENCY, UV_DATA), byte for
byte as in the original; the calibration and model tables (1.2 MB of the
2.4 MB) are left out.
"""

import sys
from pathlib import Path

from astropy.io import fits

KEEP = ("PRIMARY", "ARRAY_GEOMETRY", "SOURCE", "ANTENNA", "FREQUENCY", "UV_DATA")


def main(source):
    # The kept HDUs are copied as the bytes of the original (headers and data,
    # 2880-byte blocks), not written anew by astropy: CASA's importfitsidi
    # refuses the file astropy rewrites (its primary header is normalised).
    raw = Path(source).read_bytes()
    pieces = []
    with fits.open(source) as hdus:
        for hdu in hdus:
            info = hdu.fileinfo()
            if hdu.name in KEEP:
                pieces.append(raw[info["hdrLoc"]:info["datLoc"] + info["datSpan"]])
    Path(__file__).with_name("BL146_1.trim.fits").write_bytes(b"".join(pieces))


if __name__ == "__main__":
    main(sys.argv[1])
