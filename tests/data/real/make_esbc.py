# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Trim georust/rinex's ESBC00DNK day (Compact RINEX 3.05, 4 MB) to a few satellites and hours.

Usage::

    python make_esbc.py ESBC00DNK_R_20201770000_01D_30S_MO.crx.gz OUT.rnx.gz

Keeps the header as it is (one COMMENT line added before END OF HEADER), and of the
epoch records the ones in WINDOWS (GPS time), each with the satellites of SATELLITES
only: their lines verbatim, the count of the epoch line (columns 33-35) rewritten.
Event records (flags 2-5) in the windows are kept whole. Needs the hatanaka package
(crx2rnx) to read the original.
"""

import gzip
import sys

import hatanaka

#: The satellites kept: R04 and R12 (218 and 259 epochs where only L3Q has its
#: loss-of-lock bit set, the others not), E05 and E26 (one such epoch each), R09
#: (GLONASS-K1B: no yaw law, nominal yaw under --attitude model), GPS ones, and J01 and
#: C06, which the GRG orbit product lacks (left untouched).
SATELLITES = ("R04", "R09", "R12", "E05", "E26", "G05", "G10", "J01", "C06")

#: (start, end) as "hh mm" of GPS time, both included: around R04's flagged epoch of
#: 12:11:30 and E05's of 10:58:00, E26's of 13:07:30; and the last 45 minutes of the day,
#: past the 23:45 end of a 15-minute SP3 product.
WINDOWS = (("10 30", "13 30"), ("23 15", "23 59"))


def _kept(epoch_line):
    hhmm = epoch_line[13:18]
    return any(start <= hhmm <= end for start, end in WINDOWS)


def trim(source, target):
    text = hatanaka.crx2rnx(gzip.decompress(open(source, "rb").read())).decode("latin-1")
    lines = text.splitlines(keepends=True)
    end = next(i for i, line in enumerate(lines) if line[60:73] == "END OF HEADER")
    out = lines[:end]
    out.append(f"{'TRIMMED BY make_esbc.py (astropy_feedrot tests)':<60}COMMENT\n")
    out.append(lines[end])
    i = end + 1
    while i < len(lines):
        head = lines[i]
        count = int(head[32:35])
        body = lines[i + 1:i + 1 + count]
        i += 1 + count
        if not _kept(head):
            continue
        if head[31] in "016":
            body = [line for line in body if line[:3] in SATELLITES]
            head = head[:32] + f"{len(body):3d}" + head[35:]
        out.append(head)
        out.extend(body)
    with open(target, "wb") as fh:  # mtime 0: the same bytes at every run
        fh.write(gzip.compress("".join(out).encode("latin-1"), compresslevel=9, mtime=0))


if __name__ == "__main__":
    trim(sys.argv[1], sys.argv[2])
