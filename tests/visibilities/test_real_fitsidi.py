# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""A real FITS-IDI file of the VLBA hardware correlator, corrected: every byte
outside the visibilities kept (tests/data/real/README.md names the file).

CASA reads the primary header of a FITS-IDI file to tell which correlator
wrote it; a header written anew (astropy writes ``NAXIS = 0`` as
``NAXIS = 1``, ``NAXIS1 = 0``) made CASA's importfitsidi scale the corrected
visibilities by DiFX's digital correction, 1.966 (tests/visibilities/test_casa_real.py
checks the amplitudes against CASA's).
"""

from pathlib import Path

import numpy as np
from astropy.io import fits

from astropy_feedrot.visibilities import correct_fitsidi

BL146 = Path(__file__).parent.parent / "data" / "real" / "BL146_1.trim.fits"


def _cards(raw):
    cards = [raw[k:k + 80] for k in range(0, len(raw), 80)]
    return cards[:[card.rstrip() for card in cards].index(b"END")]


def test_primary_header_kept_card_for_card(tmp_path):
    output = tmp_path / "corrected.IDI"
    correct_fitsidi(BL146, output)
    with fits.open(BL146) as before, fits.open(output) as after:
        spans = [(hdu.fileinfo()["hdrLoc"], hdu.fileinfo()["datLoc"]) for hdu in before]
        new_spans = [(hdu.fileinfo()["hdrLoc"], hdu.fileinfo()["datLoc"]) for hdu in after]
        names = [hdu.name for hdu in before]
        assert names == [hdu.name for hdu in after]
        rows = before["UV_DATA"].data
        corrected = after["UV_DATA"].data
        # The visibilities changed (a correction of tens of degrees), nothing else
        # of the table did.
        assert not np.array_equal(rows["FLUX"], corrected["FLUX"])
        for name in rows.names:
            if name != "FLUX":
                np.testing.assert_array_equal(rows[name], corrected[name], err_msg=name)
    raw, new = BL146.read_bytes(), output.read_bytes()
    old_cards = _cards(raw[:spans[0][1]])
    new_cards = _cards(new[:new_spans[0][1]])
    assert new_cards[:len(old_cards)] == old_cards  # NAXIS = 0 stays NAXIS = 0
    added = new_cards[len(old_cards):]
    assert added and all(card.startswith(b"HISTORY ") for card in added)
    assert b"Feed rotation removed by astropy_feedrot" in b"".join(added)
    # Every other table, header and data, byte for byte.
    for k, name in enumerate(names[1:], start=1):
        if name == "UV_DATA":
            continue
        end = spans[k + 1][0] if k + 1 < len(spans) else None
        new_end = new_spans[k + 1][0] if k + 1 < len(new_spans) else None
        assert raw[spans[k][0]:end] == new[new_spans[k][0]:new_end], name
