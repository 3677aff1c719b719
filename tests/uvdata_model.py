# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""An independent voltage-level model of a polarized point source in pyuvdata's convention.

Nothing here calls astropy_feedrot. Definitions:

* the field of the source in the apparent (north, east) basis has the
  coherency B = [[I + Q, U + iV], [U - iV, I - Q]], with Q + iU = P exp(2i chi)
  and chi the EVPA from north through east;
* a dipole at sky position angle theta answers cos(theta) E_n + sin(theta) E_e;
  Y is 90 deg east of X; R = (X + iY)/sqrt(2), L = (X - iY)/sqrt(2);
* the sky position angle of a receptor: alt-az Cassegrain, the parallactic
  angle (erfa.hd2pa on astropy's HADec, geodetic latitude) plus the feed
  angle; Nasmyth, plus or minus the elevation (astropy AltAz); a dipole fixed
  to the ground at azimuth f (pyuvdata: 0 north, 90 east), the position angle
  of its projection on the plane of the sky, with the apparent pole from
  astropy's HADec frame;
* V_uvfits = J1 B J2^H (rows of J = receptors in the order of the products),
  data_array = conj(V_uvfits) (pyuvdata).
"""

import erfa
import numpy as np
from astropy import units as u
from astropy.coordinates import AltAz, EarthLocation, HADec, SkyCoord
from astropy.time import Time

PRODUCTS = {-1: "RR", -2: "LL", -3: "RL", -4: "LR", -5: "XX", -6: "YY", -7: "XY", -8: "YX"}


def coherency(stokes):
    i, q, uu, v = stokes
    return np.array([[i + q, uu + 1j * v], [uu - 1j * v, i - q]])


def stokes_from_evpa(p, chi_deg, i=1.0, v=0.0):
    chi = np.radians(chi_deg)
    return (i, p * np.cos(2 * chi), p * np.sin(2 * chi), v)


def rows(letter, theta):
    """The row of a receptor at sky position angle theta (rad), shape theta.shape + (2,).

    A dipole (X or Y) at theta; R and L built on an X dipole at theta and a Y
    dipole at theta + 90 deg.
    """
    x = np.stack([np.cos(theta), np.sin(theta)], axis=-1)
    y = np.stack([-np.sin(theta), np.cos(theta)], axis=-1)
    if letter in "XY":
        return x + 0j
    if letter == "R":
        return (x + 1j * y) / np.sqrt(2)
    return (x - 1j * y) / np.sqrt(2)


def enu_vectors(coord, location, obstime):
    """Unit vectors (E, N, U) of a direction at a site, from astropy AltAz."""
    aa = coord.transform_to(AltAz(obstime=obstime, location=location))
    az, el = aa.az.rad, aa.alt.rad
    return np.stack([np.cos(el) * np.sin(az), np.cos(el) * np.cos(az), np.sin(el)], axis=-1), \
        az, el


def projected_dipole_pa(source, location, obstime, azimuth_deg):
    """Sky position angle (rad) of a horizontal dipole at an azimuth, seen from the source."""
    s, _, _ = enu_vectors(source, location, obstime)
    shape = obstime.shape
    pole = SkyCoord(HADec(ha=np.zeros(shape) * u.deg, dec=np.full(shape, 90) * u.deg,
                          obstime=obstime, location=location))
    z, _, _ = enu_vectors(pole, location, obstime)
    f = np.radians(azimuth_deg)
    d = np.array([np.sin(f), np.cos(f), 0.0])
    n_sky = z - np.sum(z * s, axis=-1)[..., None] * s
    n_sky /= np.linalg.norm(n_sky, axis=-1)[..., None]
    e_sky = np.cross(z, s)
    e_sky /= np.linalg.norm(e_sky, axis=-1)[..., None]
    return np.arctan2(e_sky @ d, n_sky @ d)


def parallactic_angle(source, location, obstime):
    hd = source.transform_to(HADec(obstime=obstime, location=location))
    return erfa.hd2pa(hd.ha.rad, hd.dec.rad, location.lat.rad)


def receptor_angles(mount, feeds, angles, source, location, obstime):
    """Sky position angles (rad), shape obstime.shape + (2,), in the order of ``feeds``."""
    if mount == "fixed":
        return np.stack([projected_dipole_pa(source, location, obstime, np.degrees(a))
                         for a in angles], axis=-1)
    phi = parallactic_angle(source, location, obstime)
    if mount.startswith("alt-az+nasmyth"):
        _, _, el = enu_vectors(source, location, obstime)
        phi = phi + (el if mount.endswith("-r") else -el)
    return phi[..., None] + np.asarray(angles)


def inject(uv, stokes, source_of_time, mount):
    """Fill uv.data_array (pyuvdata's convention) with a point source at the phase centre.

    ``source_of_time(Time)`` gives the source (SkyCoord) at those epochs;
    ``stokes`` are in the apparent (north, east) basis, or a function of the
    epochs giving them.
    """
    tel = uv.telescope
    centre = np.array([tel.location.x.value, tel.location.y.value, tel.location.z.value])
    times = Time(uv.time_array, format="jd", scale="utc")
    source = source_of_time(times)
    st = stokes(times) if callable(stokes) else stokes
    b = coherency(st)
    if b.ndim == 2:
        b = np.broadcast_to(b, (uv.Nblts, 2, 2))
    else:
        b = np.moveaxis(b, -1, 0)
    letters = [str(f).upper() for f in tel.feed_array[0]]
    if len(letters) == 1:
        letters += ["L"] if letters[0] == "R" else ["Y"]
    theta = {}
    for k, number in enumerate(tel.antenna_numbers):
        loc = EarthLocation.from_geocentric(*(centre + tel.antenna_positions[k]), unit=u.m)
        theta[number] = receptor_angles(mount, letters, tel.feed_angle[k], source, loc, times)
    names = [PRODUCTS[c] for c in uv.polarization_array]
    n = uv.Nblts
    for k, name in enumerate(names):
        p, q = name
        t1 = np.array([theta[a][i, letters.index(p)] for i, a in enumerate(uv.ant_1_array)])
        t2 = np.array([theta[a][i, letters.index(q)] for i, a in enumerate(uv.ant_2_array)])
        j1, j2 = rows(p, t1), rows(q, t2)
        v = np.einsum("ni,nij,nj->n", j1, b, j2.conj())
        uv.data_array[:, :, k] = np.conj(v).reshape(n, 1)
    return uv


def sky_data(uv, stokes, times=None):
    """What corrected data should be: receptors fixed on the sky (R, L; X north, Y east)."""
    times = Time(uv.time_array, format="jd", scale="utc") if times is None else times
    st = stokes(times) if callable(stokes) else stokes
    b = coherency(st)
    b = np.broadcast_to(b, (uv.Nblts, 2, 2)) if b.ndim == 2 else np.moveaxis(b, -1, 0)
    out = np.empty((uv.Nblts, len(uv.polarization_array)), dtype=complex)
    for k, code in enumerate(uv.polarization_array):
        p, q = PRODUCTS[code]
        sky = {"X": 0.0, "Y": np.pi / 2, "R": 0.0, "L": 0.0}  # X north, Y east
        j1 = rows(p, np.full(uv.Nblts, sky[p]))
        j2 = rows(q, np.full(uv.Nblts, sky[q]))
        out[:, k] = np.conj(np.einsum("ni,nij,nj->n", j1, b, j2.conj()))
    return out


def evpa(uv):
    """EVPA (deg) of every row: from RL (circular) or XX - YY and XY + YX (linear)."""
    names = [PRODUCTS[c] for c in uv.polarization_array]
    v = np.conj(uv.data_array[:, 0, :])  # back to V_uvfits
    if "RL" in names:
        return np.degrees(np.angle(v[:, names.index("RL")])) / 2
    q = (v[:, names.index("XX")] - v[:, names.index("YY")]).real / 2
    uu = (v[:, names.index("XY")] + v[:, names.index("YX")]).real / 2
    return np.degrees(np.arctan2(uu, q)) / 2
