# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Make the trimmed real files of this directory from their published originals.

``python trim_fits_rows.py ORIGINAL TRIMMED ROWS``: a verbatim subset of a FITS
file. Every HDU is copied byte for byte but the rows of its visibility
container: the first ROWS rows of each ``UV_DATA`` table (FITS-IDI) or the
first ROWS groups of the primary array (UVFITS random groups), each copied
byte for byte, and the one card that counts them (``NAXIS2``, ``GCOUNT``)
rewritten; the data are padded to 2880 bytes with zeros, as FITS requires.
No value is recomputed. README.md in this directory lists the files made so
and the number of rows of each.
"""

import sys

import numpy as np
from astropy.io import fits

BLOCK = 2880


def _card(header_bytes, key, value):
    """The header's bytes with the integer card ``key`` set to ``value``."""
    cards = [header_bytes[k:k + 80] for k in range(0, len(header_bytes), 80)]
    for k, card in enumerate(cards):
        if card[:8].decode("ascii").strip() == key:
            cards[k] = f"{key:<8}= {value:>20d}".ljust(80).encode("ascii")
            return b"".join(cards)
    raise KeyError(key)


def trim(original, trimmed, rows):
    with fits.open(original, memmap=True) as hdus, open(original, "rb") as raw:
        out = []
        for index, hdu in enumerate(hdus):
            info = hdus.fileinfo(index)
            raw.seek(info["hdrLoc"])
            header = raw.read(info["datLoc"] - info["hdrLoc"])
            raw.seek(info["datLoc"])
            data = raw.read(info["datSpan"])
            h = hdu.header
            if index == 0 and h.get("GROUPS") and int(h.get("GCOUNT", 0)) > rows:
                per = abs(h["BITPIX"]) // 8 * (h["PCOUNT"] + int(np.prod(
                    [h[f"NAXIS{k}"] for k in range(2, h["NAXIS"] + 1)])))
                header, data = _card(header, "GCOUNT", rows), data[:rows * per]
            elif hdu.name == "UV_DATA" and h["NAXIS2"] > rows:
                if h.get("PCOUNT", 0):
                    raise ValueError("UV_DATA with a heap is not trimmed by this script")
                header, data = _card(header, "NAXIS2", rows), data[:rows * h["NAXIS1"]]
            out += [header, data, b"\0" * (-len(data) % BLOCK)]
    with open(trimmed, "wb") as handle:
        handle.write(b"".join(out))


if __name__ == "__main__":
    trim(sys.argv[1], sys.argv[2], int(sys.argv[3]))
