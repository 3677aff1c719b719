"""Make the *_2ints VLA files from the originals in the pyuvdata 3.1.3 wheel.

The originals are pyuvdata/data/day2_TDEM0003_10s_norx_1src_1spw.uvfits and .ms; SRC is the
directory holding them. Row selection only: keeps the 5th and 6th distinct DATE values (two
complete integrations, 153 baselines each, 306 rows). The primary header, the AIPS FQ, AN and
WX tables and all Measurement Set subtables are untouched. Afterwards:
tar czf <ms>.tar.gz <ms>.
"""
import os
import shutil

import numpy as np
from astropy.io import fits


def main():
    from casacore import tables

    source = os.environ.get("SRC", ".")
    base = "day2_TDEM0003_10s_norx_1src_1spw"
    with fits.open(f"{source}/{base}.uvfits") as hdus:
        date = hdus[0].data.par("DATE")
        keep = np.isin(date, np.unique(date)[4:6])
        rows = np.nonzero(keep)[0]
        primary = fits.GroupsHDU(data=hdus[0].data[keep], header=hdus[0].header)
        fits.HDUList([primary] + [hdu.copy() for hdu in hdus[1:]]).writeto(
            f"{base}_2ints.uvfits", overwrite=True)
    # The Measurement Set rows are in the order of the UVFITS groups (importuvfits).
    table = tables.table(f"{source}/{base}.ms", ack=False)
    selected = table.selectrows(rows.tolist())
    shutil.rmtree(f"{base}_2ints.ms", ignore_errors=True)
    selected.copy(f"{base}_2ints.ms", deep=True)
    selected.close()
    table.close()


if __name__ == "__main__":
    main()
