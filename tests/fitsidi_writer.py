# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Synthetic FITS-IDI and UVFITS antenna tables for the tests.

The FITS-IDI files follow the tables and keywords that DiFX's difx2fits writes
(``fitsAG.c``, ``fitsAN.c``, ``fitsFR.c``, ``fitsSU.c``, ``fitsUV.c``,
``fitsHeader.c`` of difx/difx; see the FITS-IDI section of :doc:`/fitsidi`).
Their visibilities are a polarized point source at the phase centre, made
here by a voltage-level model written from the definitions, independent of
the package:

* a dipole at position angle theta (north through east) answers to the field
  (E_north, E_east) with the row (cos theta, sin theta); a receptor R is
  (X + iY)/sqrt(2) and L is (X - iY)/sqrt(2), with Y 90 deg east of X;
* the position angle of a receptor is the feed rotation of its antenna plus
  its angle in the antenna (POLAA/POLAB);
* the feed rotation of an alt-az Cassegrain antenna is ERFA's ``hd2pa`` of
  astropy's HADec (geodetic latitude); a Nasmyth focus adds (right) or
  subtracts (left) astropy's AltAz elevation (the closed forms of casacore's
  ``MSDerivedValues::parAngle``);
* the visibility is V_pq = <v1p v2q*> = (J1 B J2^H)_pq and FITS-IDI stores its
  complex conjugate (casacore ``FitsIDItoMS.cc``, DiFX ``fitsUV.c``).

An EVPA given in ICRS is turned into the apparent frame of date with the
position angle of the ICRS north there, from ERFA's ``atci13`` and ``pas``.
"""

import erfa
import numpy as np
from astropy import units as u
from astropy.coordinates import AltAz, EarthLocation, HADec, SkyCoord
from astropy.io import fits
from astropy.time import Time

from astropy_feedrot.stations.catalogue import get_antenna

STOKES = {"RR": -1, "LL": -2, "RL": -3, "LR": -4, "XX": -5, "YY": -6, "XY": -7, "YX": -8}

# Stations (positions from the package's catalogue: the paper's Table 1 and
# the GSFC 2019d solution as listed by SCHED): name -> MNTSTA written and
# the focus the model uses. WETTZ13S is written as a left-handed Nasmyth
# antenna to exercise that closed form (it is not one).
STATIONS = [
    ("FD-VLBA", 0, None),
    ("EFLSBERG", 0, None),
    ("YEBES40M", 4, "right"),
    ("WETTZ13S", 5, "left"),
]

# 3C 84 and 0923+392 (J2000), and the epoch at which all four stations see
# them above 10 deg.
SOURCES = [(1, "3C84", 49.9506671, 41.5116961), (2, "4C39.25", 141.7625563, 39.0391260)]
START = Time("2023-01-25T20:00:00", scale="utc")


def station_xyz(name):
    return get_antenna(name).location.get_itrs().cartesian.xyz.to_value(u.m)


def dipole(theta):
    return np.array([np.cos(theta), np.sin(theta)])


def receptor_row(letter, theta):
    if letter == "X" or letter == "Y":
        return dipole(theta)
    hand = 1 if letter == "R" else -1
    return (dipole(theta) + hand * 1j * dipole(theta + np.pi / 2)) / np.sqrt(2)


def coherency(i, q, u_, v):
    """<E E^H> in (north, east): IAU Q along north-south, U at 45 deg east of north."""
    return 0.5 * np.array([[i + q, u_ + 1j * v], [u_ - 1j * v, i - q]])


def feed_rotation_reference(xyz, focus, coord, times):
    """Feed rotation (deg) from ERFA hd2pa on astropy's HADec, plus +-elevation for Nasmyth."""
    location = EarthLocation.from_geocentric(*xyz, unit=u.m)
    hadec = coord.transform_to(HADec(obstime=times, location=location))
    pa = erfa.hd2pa(hadec.ha.rad, hadec.dec.rad, location.lat.rad)
    if focus is not None:
        el = coord.transform_to(AltAz(obstime=times, location=location)).alt.rad
        pa = pa + (el if focus == "right" else -el)
    return np.degrees(pa)


def icrs_north_in_apparent(ra, dec, times):
    """Position angle (deg) of the ICRS north at (ra, dec) in the CIRS of date (ERFA)."""
    tdb = times.tdb
    ra, dec = np.radians(ra), np.radians(dec)
    offset = np.radians(1 / 3600)
    r1, d1, _ = erfa.atci13(ra, dec, 0, 0, 0, 0, tdb.jd1, tdb.jd2)
    r2, d2, _ = erfa.atci13(ra, dec + offset, 0, 0, 0, 0, tdb.jd1, tdb.jd2)
    return np.degrees(erfa.pas(r1, d1, r2, d2))


def _stokes_axis(codes):
    codes = list(codes)
    step = codes[1] - codes[0] if len(codes) > 1 else -1
    if any(b - a != step for a, b in zip(codes, codes[1:])):
        raise ValueError(f"codes {codes} are not evenly spaced")
    return codes[0], step


def write_fitsidi(path, *, products=("RR", "LL", "RL", "LR"), angles=None, evpa=33.0,
                  polarized=0.1, frame="apparent", n_times=6, step_minutes=40, n_band=2,
                  n_chan=3, complex_length=2, program="difx", mntsta=None, crpix=1.0,
                  stations=STATIONS, sources=SOURCES, start=START, autocorrelations=True,
                  extra_primary=None, n_freqid=1, n_arrays=1):
    """Write a FITS-IDI file; return the expected corrected products per row.

    ``angles`` maps a station index to its (POLAA, POLAB) in degrees (the
    same in every band). Rows cycle through the sources (one scan each) and,
    with ``n_freqid`` > 1, through as many frequency setups (FREQID), each with
    its own rows of the ANTENNA table as difx2fits writes them (fitsAN.c).
    ``n_arrays`` > 1 splits the stations among as many ARRAY_GEOMETRY tables
    (EXTVER = array number, AIPS Memo 114), the ANTENNA table's ARRAY column
    saying which.
    Returns a dict with ``expected`` (rows, products) of sky-fixed products
    in the <v1 v2*> convention, ``chi`` (EVPA, deg, in ``frame``) and the
    row metadata.
    """
    basis_letters = "RL" if products[0][0] in "RL" else "XY"
    angles = angles or {}
    crval, cdelt = _stokes_axis([STOKES[p] for p in products])
    n_pol = len(products)
    n_ant = len(stations)
    xyz = [station_xyz(name) for name, _, _ in stations]
    codes = mntsta or [code for _, code, _ in stations]
    times = start + np.arange(n_times) * step_minutes * u.min
    coords = {sid: SkyCoord(ra * u.deg, dec * u.deg) for sid, _, ra, dec in sources}
    # Rows: for each time, one source, every baseline.
    first = 0 if autocorrelations else 1
    pairs = [(i, j) for i in range(n_ant) for j in range(i + first, n_ant)]
    rows = []
    for k in range(n_times):
        sid = sources[k % len(sources)][0]
        for i, j in pairs:
            rows.append((k, sid, i, j))
    n_rows = len(rows)
    phi = {}
    for sid, coord in coords.items():
        for a, (name, _, focus) in enumerate(stations):
            phi[sid, a] = feed_rotation_reference(xyz[a], focus, coord, times)
    chi_app = {}
    for sid, _, ra, dec in sources:
        delta = icrs_north_in_apparent(ra, dec, times) if frame == "icrs" else np.zeros(n_times)
        chi_app[sid] = evpa + delta
    flux = np.zeros((n_rows, 1, 1, n_band, n_chan, n_pol, complex_length), dtype=np.float32)
    expected = np.zeros((n_rows, n_pol), dtype=complex)
    for r, (k, sid, i, j) in enumerate(rows):
        chi = np.radians(chi_app[sid][k])
        sky = coherency(1.0, polarized * np.cos(2 * chi), polarized * np.sin(2 * chi), 0.02)
        chi_ref = np.radians(evpa)
        sky_ref = coherency(1.0, polarized * np.cos(2 * chi_ref),
                            polarized * np.sin(2 * chi_ref), 0.02)
        a1 = angles.get(i, (0.0, 90.0 if basis_letters == "XY" else 0.0))
        a2 = angles.get(j, (0.0, 90.0 if basis_letters == "XY" else 0.0))
        values = []
        for p in products:
            # A circular feed turns as one: both receptors at POLAA, the first
            # receptor's angle (CASA's rule, checked with casatools in test_casa.py).
            k1 = 0 if basis_letters == "RL" else basis_letters.index(p[0])
            k2 = 0 if basis_letters == "RL" else basis_letters.index(p[1])
            t1 = np.radians(phi[sid, i][k] + a1[k1])
            t2 = np.radians(phi[sid, j][k] + a2[k2])
            v = receptor_row(p[0], t1) @ sky @ receptor_row(p[1], t2).conj()
            values.append(v)
            # Fixed receptors on the sky: X north, Y east, R and L at angle 0.
            f1 = receptor_row(p[0], 0.0 if p[0] != "Y" else np.pi / 2)
            f2 = receptor_row(p[1], 0.0 if p[1] != "Y" else np.pi / 2)
            expected[r, len(values) - 1] = f1 @ sky_ref @ f2.conj()
        values = np.conj(values)  # FITS-IDI stores the conjugate of <v1 v2*>
        for b in range(n_band):
            for c in range(n_chan):
                gain = 1.0 + 0.1 * c + 0.01 * b
                flux[r, 0, 0, b, c, :, 0] = gain * values.real
                flux[r, 0, 0, b, c, :, 1] = gain * values.imag
                if complex_length == 3:
                    flux[r, 0, 0, b, c, :, 2] = 1.0
    # Tables.
    primary = fits.PrimaryHDU()
    h = primary.header
    if program == "difx":
        # difx2fits (fitsHeader.c) and AIPS Memo 114: no primary array, but
        # GROUPS = T with GCOUNT = PCOUNT = 0 (astropy opens it as a GroupsHDU).
        h["EXTEND"] = True
        h["BLOCKED"] = True
    h["OBJECT"] = "BINARYTB"
    h["TELESCOP"] = "VLBA"
    h["OBSERVER"] = "TEST1"
    if program == "difx":
        h["ORIGIN"] = "VLBA Correlator"
        h["CORRELAT"] = "DIFX"
        h["DATE-OBS"] = start.isot[:10]
        h["DATE-MAP"] = start.isot[:10]
        h["GROUPS"] = True
        h["GCOUNT"] = 0
        h["PCOUNT"] = 0
        h.add_history("OPENED FITS FILE : 2023JAN26 10h00m00s")
        h.add_history("CORRELATOR = 'DIFX'")
        h.add_history("CORRVERS = DiFX-2.8.1")
        h.add_history("OBSCODE : TEST1")
    else:
        h["DATE-OBS"] = start.isot[:10]
    if program == "casacore":
        h["ORIGIN"] = "casacore"
    for key, value in (extra_primary or {}).items():
        h[key] = value
    common = dict(OBSCODE="TEST1", RDATE=start.isot[:10], NO_STKD=n_pol, STK_1=crval,
                  NO_BAND=n_band, NO_CHAN=n_chan, REF_FREQ=8.4e9, CHAN_BW=0.5e6,
                  REF_PIXL=1.0, TABREV=1)
    array_of = [a * n_arrays // n_ant + 1 for a in range(n_ant)]
    geometries = []
    for array in range(1, n_arrays + 1):
        members = [a for a in range(n_ant) if array_of[a] == array]
        geometry = fits.BinTableHDU.from_columns([
            fits.Column("ANNAME", "8A", array=[stations[a][0][:8] for a in members]),
            fits.Column("STABXYZ", "3D", unit="METERS", array=np.array([xyz[a] for a in members])),
            fits.Column("DERXYZ", "3E", unit="METERS/SEC", array=np.zeros((len(members), 3))),
            fits.Column("ORBPARM", "0D", array=np.zeros((len(members), 0))),
            fits.Column("NOSTA", "1J", array=np.array(members) + 1),
            fits.Column("MNTSTA", "1J", array=np.array([codes[a] for a in members])),
            fits.Column("STAXOF", "3E", unit="METERS", array=np.zeros((len(members), 3))),
            fits.Column("DIAMETER", "1E", unit="METERS", array=np.full(len(members), 25.0)),
        ], name="ARRAY_GEOMETRY")
        geometry.header["EXTVER"] = array
        geometry.header.update(common)
        geometry.header.update(ARRAYX=0.0, ARRAYY=0.0, ARRAYZ=0.0, ARRNAM=f"VLBA{array}",
                               FRAME="GEOCENTRIC", TIMSYS="UTC", TIMESYS="UTC", NUMORB=0,
                               GSTIA0=0.0, DEGPDY=360.9856449733, FREQ=8.4e9, POLARX=0.0,
                               POLARY=0.0, UT1UTC=0.0, IATUTC=37.0)
        geometries.append(geometry)
    polaa = np.array([[angles.get(a, (0.0, 0.0))[0]] * n_band for a in range(n_ant)])
    polab = np.array([[angles.get(a, (0.0, 90.0 if basis_letters == "XY" else 0.0))[1]]
                      * n_band for a in range(n_ant)])
    # One row per antenna and frequency setup (difx2fits, fitsAN.c).
    an_rows = [(f, a) for f in range(1, n_freqid + 1) for a in range(n_ant)]
    antenna = fits.BinTableHDU.from_columns([
        fits.Column("TIME", "1D", unit="DAYS", array=np.zeros(len(an_rows))),
        fits.Column("TIME_INTERVAL", "1E", unit="DAYS", array=np.full(len(an_rows), 1.0)),
        fits.Column("ANNAME", "8A", array=[stations[a][0][:8] for _, a in an_rows]),
        fits.Column("ANTENNA_NO", "1J", array=[a + 1 for _, a in an_rows]),
        fits.Column("ARRAY", "1J", array=[array_of[a] for _, a in an_rows]),
        fits.Column("FREQID", "1J", array=[f for f, _ in an_rows]),
        fits.Column("NO_LEVELS", "1J", array=np.full(len(an_rows), 4)),
        fits.Column("POLTYA", "1A", array=[basis_letters[0]] * len(an_rows)),
        fits.Column("POLAA", f"{n_band}E", unit="DEGREES",
                    array=np.array([polaa[a] for _, a in an_rows])),
        fits.Column("POLCALA", "0E", array=np.zeros((len(an_rows), 0))),
        fits.Column("POLTYB", "1A", array=[basis_letters[1]] * len(an_rows)),
        fits.Column("POLAB", f"{n_band}E", unit="DEGREES",
                    array=np.array([polab[a] for _, a in an_rows])),
        fits.Column("POLCALB", "0E", array=np.zeros((len(an_rows), 0))),
    ], name="ANTENNA")
    antenna.header.update(common)
    antenna.header.update(NOPCAL=0, POLTYPE="APPROX")
    frequency = fits.BinTableHDU.from_columns([
        fits.Column("FREQID", "1J", array=np.arange(1, n_freqid + 1)),
        fits.Column("BANDFREQ", f"{n_band}D", unit="HZ",
                    array=[np.arange(n_band) * 32e6 + f * 1e9 for f in range(n_freqid)]),
        fits.Column("CH_WIDTH", f"{n_band}E", unit="HZ",
                    array=[np.full(n_band, 0.5e6)] * n_freqid),
        fits.Column("TOTAL_BANDWIDTH", f"{n_band}E", unit="HZ",
                    array=[np.full(n_band, 32e6)] * n_freqid),
        fits.Column("SIDEBAND", f"{n_band}J", array=[np.ones(n_band, int)] * n_freqid),
        fits.Column("BB_CHAN", f"{n_band}J", array=[np.ones(n_band, int)] * n_freqid),
    ], name="FREQUENCY")
    frequency.header.update(common)
    n_src = len(sources)
    source = fits.BinTableHDU.from_columns([
        fits.Column("SOURCE_ID", "1J", array=[s[0] for s in sources]),
        fits.Column("SOURCE", "16A", array=[s[1] for s in sources]),
        fits.Column("QUAL", "1J", array=np.zeros(n_src, int)),
        fits.Column("CALCODE", "4A", array=[""] * n_src),
        fits.Column("FREQID", "1J", array=np.ones(n_src, int)),
        fits.Column("RAEPO", "1D", unit="DEGREES", array=[s[2] for s in sources]),
        fits.Column("DECEPO", "1D", unit="DEGREES", array=[s[3] for s in sources]),
        fits.Column("EQUINOX", "8A", array=["J2000"] * n_src),
        fits.Column("RAAPP", "1D", unit="DEGREES", array=[s[2] for s in sources]),
        fits.Column("DECAPP", "1D", unit="DEGREES", array=[s[3] for s in sources]),
        fits.Column("PMRA", "1D", unit="DEG/DAY", array=np.zeros(n_src)),
        fits.Column("PMDEC", "1D", unit="DEG/DAY", array=np.zeros(n_src)),
        fits.Column("EPOCH", "1D", unit="YEARS", array=np.full(n_src, 2000.0)),
    ], name="SOURCE")
    source.header.update(common)
    jd = np.array([times[k].jd for k, _, _, _ in rows])
    date = np.floor(jd - 0.5) + 0.5
    k_time = np.array([(times[k] - Time(d, format="jd", scale="utc")).to_value(u.day)
                       for (k, _, _, _), d in zip(rows, date)])
    baseline = np.array([256 * (i + 1) + (j + 1) for _, _, i, j in rows])
    uv_columns = [
        fits.Column("UU---SIN", "1E", unit="SECONDS", array=np.zeros(n_rows)),
        fits.Column("VV---SIN", "1E", unit="SECONDS", array=np.zeros(n_rows)),
        fits.Column("WW---SIN", "1E", unit="SECONDS", array=np.zeros(n_rows)),
        fits.Column("DATE", "1D", unit="DAYS", array=date),
        fits.Column("TIME", "1D", unit="DAYS", array=k_time),
        fits.Column("BASELINE", "1J", array=baseline),
        fits.Column("FILTER", "1J", array=np.zeros(n_rows, int)),
        fits.Column("SOURCE", "1J", array=[sid for _, sid, _, _ in rows]),
        fits.Column("FREQID", "1J", array=[k % n_freqid + 1 for k, _, _, _ in rows]),
        fits.Column("INTTIM", "1E", unit="SECONDS", array=np.full(n_rows, 2.0)),
    ]
    if complex_length == 2:
        uv_columns.append(fits.Column("WEIGHT", f"{n_band * n_pol}E",
                                      array=np.ones((n_rows, n_band * n_pol))))
    if program == "difx":
        # difx2fits writes an empty GATEID column ('0J') before FLUX.
        uv_columns.append(fits.Column("GATEID", "0J", array=np.zeros((n_rows, 0), int)))
    uv_columns.append(fits.Column("FLUX", f"{flux[0].size}E", unit="UNCALIB",
                                  array=flux.reshape(n_rows, -1)))
    uv = fits.BinTableHDU.from_columns(uv_columns, name="UV_DATA")
    uv.header.update(common)
    axes = [("COMPLEX", complex_length, 1.0, 1.0, 1.0),
            ("STOKES", n_pol, float(crval), float(cdelt), 1.0),
            ("FREQ", n_chan, 8.4e9, 0.5e6, 1.0),
            ("BAND", n_band, 1.0, 1.0, 1.0),
            ("RA", 1, 0.0, 1.0, 1.0),
            ("DEC", 1, 0.0, 1.0, 1.0)]
    uv.header["NMATRIX"] = 1
    uv.header["MAXIS"] = len(axes)
    for k, (ctype, n, crv, cde, crp) in enumerate(axes, start=1):
        uv.header[f"MAXIS{k}"] = n
        uv.header[f"CTYPE{k}"] = ctype
        uv.header[f"CDELT{k}"] = cde
        uv.header[f"CRPIX{k}"] = crp
        uv.header[f"CRVAL{k}"] = crv
    if crpix != 1.0:
        # The same codes with another reference pixel.
        uv.header["CRPIX2"] = crpix
        uv.header["CRVAL2"] = float(crval + cdelt * (crpix - 1))
    uv.header.update(TMATX11=True, EQUINOX="J2000", WEIGHTYP="CORRELAT", SORT="T*",
                     VIS_SCAL=1.0)
    fits.HDUList([primary, *geometries, antenna, frequency, source, uv]).writeto(
        path, overwrite=True)
    return dict(expected=expected, rows=rows, products=list(products), evpa=evpa,
                n_band=n_band, n_chan=n_chan)


def write_uvfits_an(path, *, program="casacore", mntsta=(0, 0), stations=("FD-VLBA", "EFLSBERG"),
                    polty=("R", "L"), pola=((0.0, 0.0), (0.0, 0.0)), centre=None,
                    frame="ITRF", xyzhand="RIGHT", hasmnt=True, extra_an=None, telescope="VLBA"):
    """Write the primary header and ``AIPS AN`` table of a UVFITS file.

    ``program``: ``'casacore'`` (ORIGIN 'casacore', ARRAYX/Y/Z = 0, absolute
    STABXYZ; MSFitsOutput.cc), ``'pyuvdata'`` (HISTORY 'Read/written with
    pyuvdata version', ARRAYX/Y/Z = ``centre`` and STABXYZ rotated to its
    longitude, HASMNT; pyuvdata uvfits.py), ``'aips'`` (HISTORY AIPS
    ``RELEASE``) or ``'unknown'``. The random-group visibilities are left
    out: the antenna readers do not need them.
    """
    xyz = np.array([station_xyz(name) for name in stations])
    n = len(stations)
    primary = fits.PrimaryHDU()
    primary.header["TELESCOP"] = telescope
    primary.header["OBJECT"] = "MULTI"
    if program == "casacore":
        primary.header["ORIGIN"] = "casacore"
        primary.header.add_history("AIPS WTSCAL = 1.0")
    elif program == "pyuvdata":
        primary.header.add_history("Read/written with pyuvdata version: 3.2.8.")
    elif program == "aips":
        primary.header.add_history("AIPS   RELEASE = '31DEC24'")
    if centre is not None:
        centre = np.asarray(centre, float)
        lon = np.arctan2(centre[1], centre[0])
        rel = xyz - centre
        # pyuvdata's rotECEF_from_ECEF: rotate by -longitude about z.
        c, s = np.cos(-lon), np.sin(-lon)
        stab = np.column_stack([c * rel[:, 0] - s * rel[:, 1], s * rel[:, 0] + c * rel[:, 1],
                                rel[:, 2]])
    else:
        centre = np.zeros(3)
        stab = xyz
    an = fits.BinTableHDU.from_columns([
        fits.Column("ANNAME", "8A", array=[s[:8] for s in stations]),
        fits.Column("STABXYZ", "3D", unit="METERS", array=stab),
        fits.Column("NOSTA", "1J", array=np.arange(1, n + 1)),
        fits.Column("MNTSTA", "1J", array=np.array(mntsta)),
        fits.Column("STAXOF", "1E", unit="METERS", array=np.zeros(n)),
        fits.Column("POLTYA", "1A", array=[polty[0]] * n),
        fits.Column("POLAA", "1E", unit="DEGREES", array=[a[0] for a in pola]),
        fits.Column("POLTYB", "1A", array=[polty[1]] * n),
        fits.Column("POLAB", "1E", unit="DEGREES", array=[a[1] for a in pola]),
    ], name="AIPS AN")
    h = an.header
    h["EXTVER"] = 1
    h["ARRAYX"], h["ARRAYY"], h["ARRAYZ"] = (float(v) for v in centre)
    if frame is not None:
        h["FRAME"] = frame
    if xyzhand is not None:
        h["XYZHAND"] = xyzhand
    h["ARRNAM"] = telescope
    if program == "pyuvdata":
        h["TIMESYS"] = "UTC"
        h["POLTYPE"] = "X-Y LIN"
        if hasmnt is not None:
            h["HASMNT"] = hasmnt
    else:
        h["TIMSYS"] = "UTC"
    for key, value in (extra_an or {}).items():
        h[key] = value
    fits.HDUList([primary, an]).writeto(path, overwrite=True)
    return xyz
