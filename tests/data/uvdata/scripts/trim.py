"""Make the *_2ints VLA files from the originals in the pyuvdata 3.1.3 wheel
(pyuvdata/data/day2_TDEM0003_10s_norx_1src_1spw.uvfits and .ms).

Row selection only: keeps the 5th and 6th unique DATE values (2 complete integrations,
153 baselines each, 306 rows). Primary header, AIPS FQ/AN/WX tables and all MS subtables
are untouched. SRC = directory holding the originals. Afterwards: tar czf <out_m>.tar.gz <out_m>
"""
import os, shutil, numpy as np
from astropy.io import fits
from casacore import tables
SRC = os.environ.get("SRC", "/tmp/cand")
base = "day2_TDEM0003_10s_norx_1src_1spw"
src_u = f"{SRC}/{base}.uvfits"; src_m = f"{SRC}/{base}.ms"
out_u = f"{base}_2ints.uvfits"; out_m = f"{base}_2ints.ms"
with fits.open(src_u) as h:
    date = h[0].data.par("DATE")
    ut = np.unique(date)
    mask = np.isin(date, ut[4:6])   # two complete integrations (153 baselines each)
    rows = np.nonzero(mask)[0]
    new0 = fits.GroupsHDU(data=h[0].data[mask], header=h[0].header)
    fits.HDUList([new0] + [x.copy() for x in h[1:]]).writeto(out_u, overwrite=True)
t = tables.table(src_m, ack=False)   # MS rows are in the same order as the UVFITS groups (importuvfits)
sel = t.selectrows(rows.tolist())
shutil.rmtree(out_m, ignore_errors=True)
sel.copy(out_m, deep=True)
sel.close(); t.close()
