# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Measurement Sets for the tests: a real one (the VLA's, as CASA's importuvfits
wrote it) whose data are replaced by a polarized point source.

The visibilities come from the voltage-level model of ``fitsidi_writer``,
independent of the package: receptor rows from their definitions, the feed
rotation of each alt-az Cassegrain antenna from ERFA's ``hd2pa`` on
astropy's HADec (geodetic latitude), the receptor angles added, and
V_pq = <v1p v2q*> = (J1 B J2^H)_pq, the Measurement Set convention (casacore,
not conjugated). ``linear=True`` turns the set into a linear-feed one first:
``CORR_TYPE`` XX, XY, YX, YY (9-12) and ``FEED`` receptors X, Y at given
angles.
"""

import tarfile
from pathlib import Path

import numpy as np
from astropy import units as u
from astropy.coordinates import FK5, SkyCoord
from astropy.time import Time
from casacore.tables import table
from fitsidi_writer import coherency, feed_rotation_reference, receptor_row

DATA = Path(__file__).parent / "data" / "uvdata"
VLA_MS = "day2_TDEM0003_10s_norx_1src_1spw_2ints.ms"

EVPA = 33.0
POLARIZED = 0.1


def unpack(where, name=VLA_MS):
    with tarfile.open(DATA / f"{name}.tar.gz") as archive:
        archive.extractall(where, filter="data")
    return Path(where) / name


def _angles(receptors, antenna):
    return receptors.get(antenna, receptors.get("default"))


def make_linear(ms, angles):
    """CORR_TYPE XX, XY, YX, YY and FEED receptors X, Y at ``angles`` (deg) per antenna."""
    with table(str(ms / "POLARIZATION"), readonly=False, ack=False) as pol:
        pol.putcell("CORR_TYPE", 0, np.array([9, 10, 11, 12], dtype=np.int32))
    with table(str(ms / "FEED"), readonly=False, ack=False) as feed:
        for row in range(feed.nrows()):
            antenna = int(feed.getcell("ANTENNA_ID", row))
            feed.putcell("POLARIZATION_TYPE", row, np.array(["X", "Y"]))
            feed.putcell("RECEPTOR_ANGLE", row, np.radians(_angles(angles, antenna)))


def set_feed(ms, antenna, types, angles):
    """The FEED rows of one antenna: receptor types and angles (deg)."""
    with table(str(ms / "FEED"), readonly=False, ack=False) as feed:
        for row in range(feed.nrows()):
            if int(feed.getcell("ANTENNA_ID", row)) == antenna:
                feed.putcell("POLARIZATION_TYPE", row, np.array(list(types)))
                feed.putcell("RECEPTOR_ANGLE", row, np.radians(np.asarray(angles, float)))


def fill_model(ms, column="DATA"):
    """Write the model into ``column``; return the sky-fixed products (rows, products)."""
    with table(str(ms / "ANTENNA"), ack=False) as ant:
        xyz = ant.getcol("POSITION")
    with table(str(ms / "FIELD"), ack=False) as field:
        ra, dec = field.getcell("PHASE_DIR", 0)[0]
    with table(str(ms / "POLARIZATION"), ack=False) as pol:
        codes = pol.getcell("CORR_TYPE", 0).tolist()
    receptors = {}
    with table(str(ms / "FEED"), ack=False) as feed:
        for k in range(feed.nrows()):
            receptors.setdefault(int(feed.getcell("ANTENNA_ID", k)), []).append((
                feed.getcell("TIME", k), feed.getcell("INTERVAL", k),
                "".join(feed.getcell("POLARIZATION_TYPE", k)),
                np.degrees(feed.getcell("RECEPTOR_ANGLE", k))))

    def feed_of(antenna, t):
        """The FEED row of an antenna valid at time t (MS v2: TIME +- INTERVAL / 2)."""
        rows = receptors[antenna]
        if len(rows) > 1:
            rows = [r for r in rows if abs(t - r[0]) <= r[1] / 2]
        return rows[0][2:]

    names = {5: "RR", 6: "RL", 7: "LR", 8: "LL", 9: "XX", 10: "XY", 11: "YX", 12: "YY"}
    products = [names[c] for c in codes]
    coord = SkyCoord(ra * u.rad, dec * u.rad, frame=FK5(equinox="J2000"))
    chi = np.radians(EVPA)
    sky = coherency(1.0, POLARIZED * np.cos(2 * chi), POLARIZED * np.sin(2 * chi), 0.02)
    with table(str(ms), readonly=False, ack=False) as main:
        time = main.getcol("TIME")
        a1, a2 = main.getcol("ANTENNA1"), main.getcol("ANTENNA2")
        shape = main.getcell(column, 0).shape
        epochs, index = np.unique(time, return_inverse=True)
        times = Time(epochs / 86400, format="mjd", scale="utc")
        phi = {a: feed_rotation_reference(xyz[a], None, coord, times)
               for a in np.unique(np.concatenate([a1, a2])).tolist()}
        data = np.zeros((len(time),) + shape, dtype=np.complex64)
        expected = np.zeros((len(time), len(products)), dtype=complex)
        for row in range(len(time)):
            i, j, k = int(a1[row]), int(a2[row]), int(index[row])
            types1, alpha1 = feed_of(i, time[row])
            types2, alpha2 = feed_of(j, time[row])
            for c, product in enumerate(products):
                # A circular feed turns as one: both receptors at the first one's
                # angle (CASA's rule, checked with casatools in test_casa.py).
                k1 = 0 if product[0] in "RL" else types1.index(product[0])
                k2 = 0 if product[1] in "RL" else types2.index(product[1])
                t1 = np.radians(phi[i][k] + alpha1[k1])
                t2 = np.radians(phi[j][k] + alpha2[k2])
                data[row, :, c] = (receptor_row(product[0], t1) @ sky
                                   @ receptor_row(product[1], t2).conj())
                # Receptors fixed on the sky: X north, Y east, R and L at angle 0.
                f1 = receptor_row(product[0], np.pi / 2 if product[0] == "Y" else 0.0)
                f2 = receptor_row(product[1], np.pi / 2 if product[1] == "Y" else 0.0)
                expected[row, c] = f1 @ sky @ f2.conj()
        gain = (1.0 + 0.01 * np.arange(shape[0]))[None, :, None]
        main.putcol(column, (data * gain).astype(np.complex64))
    return dict(expected=expected, products=products, gain=gain)
