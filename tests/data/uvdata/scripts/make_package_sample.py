"""Make astropy_feedrot/data/vla_day2_8chan.uvfits, the sample visibility file of the package.

From day2_TDEM0003_10s_norx_1src_1spw_2ints.uvfits (two integrations of the VLA data of
CASA's tutorial, exported by casacore; see ../README.md): the same 306 rows and all four
polarization products, the 8 channels around the reference pixel instead of 64. Only the
frequency axis (NAXIS4, CRPIX4) and the FQ table's total bandwidth change; every other
header card and table is copied as it is.

Run from the repository root: python tests/data/uvdata/scripts/make_package_sample.py
"""
from pathlib import Path

import numpy as np
from astropy.io import fits

SOURCE = Path("tests/data/uvdata/day2_TDEM0003_10s_norx_1src_1spw_2ints.uvfits")
TARGET = Path("astropy_feedrot/data/vla_day2_8chan.uvfits")
FIRST, COUNT = 28, 8  # channels 29-36 of 64 (1-based); the reference pixel is 33

with fits.open(SOURCE) as hdus:
    primary = hdus[0]
    header = primary.header.copy()
    groups = primary.data
    data = np.ascontiguousarray(groups.data[..., FIRST:FIRST + COUNT, :, :])
    names = groups.parnames
    # Parameters as stored (two DATE parameters share a name: take them by index).
    parameters = [groups.par(i) for i in range(len(names))]
    new = fits.GroupData(data, parnames=names, pardata=parameters, bitpix=-32)
    hdu = fits.GroupsHDU(new)
    for card in header.cards:
        if card.keyword in ("HISTORY", "COMMENT"):
            continue
        if card.keyword not in hdu.header or card.keyword.startswith(("PTYPE", "PSCAL", "PZERO",
                                                                      "CTYPE", "CRVAL", "CDELT",
                                                                      "CRPIX", "CROTA")):
            hdu.header[card.keyword] = (card.value, card.comment)
    for key in ("HISTORY", "COMMENT"):
        for value in header.get(key, []):
            hdu.header.add_history(str(value)) if key == "HISTORY" else hdu.header.add_comment(
                str(value))
    hdu.header["CRPIX4"] = header["CRPIX4"] - FIRST
    tables = [table.copy() for table in hdus[1:]]
    for table in tables:
        if table.name == "AIPS FQ":
            table.data["TOTAL BANDWIDTH"] = COUNT * table.data["CH WIDTH"]
    fits.HDUList([hdu] + tables).writeto(TARGET, overwrite=True)
print(TARGET, TARGET.stat().st_size, "bytes")
