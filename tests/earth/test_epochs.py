# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Epochs: made once, handed down; every front-end agrees with the rigorous path.

The rigorous path is astropy's own transformation at every epoch
(``conf.fast_path = False``: ``SkyCoord.transform_to(ITRS(location=...))``),
an independent computation of the same directions; the fast path must agree
with it to 0.1 mas (the package's target) on a golden-spiral sky.
"""

import pathlib

import erfa
import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import SkyCoord, golden_spiral_grid
from astropy.time import Time
from astropy.utils import iers
from hypothesis import given, settings, strategies as st

import astropy_feedrot
from astropy_feedrot import Epochs, conf, feed_rotation_grid, get_antenna
from astropy_feedrot.core.inputs import as_time
from astropy_feedrot.earth.eop import iers_context, utc_earth_orientation
from astropy_feedrot.earth.epochs import as_epochs, fill_masked
from astropy_feedrot.visibilities.rows import feed_rotation_rows

PACKAGE = pathlib.Path(astropy_feedrot.__file__).parent
MAS = u.mas
TOLERANCE = 0.1 * MAS  # the package's target against the rigorous path
# The grid's shared directions (and the visibility rows, which use the grid)
# against each antenna's own: 1e-4 mas in direction (grid_natural), which the
# angle multiplies by up to 1 / sin(distance) near the pole, zenith and nadir.
SHARED = 0.05 * MAS
STATIONS = ["WETTZ13S", "YEBES40M", "GGAO12M"]  # alt-az Cassegrain, Nasmyth, Cassegrain


def sky(n=60):
    """A golden-spiral grid of directions over the whole sphere (as astropy's tests)."""
    grid = golden_spiral_grid(n)
    return SkyCoord(grid.lon, grid.lat, frame="icrs")


def wrapped_mas(a, b):
    """Largest |a - b| wrapped to +-180 deg, in mas, ignoring NaN pairs."""
    d = (u.Quantity(a) - u.Quantity(b)).to_value(u.deg)
    d = (d + 180.0) % 360.0 - 180.0
    return np.nanmax(np.abs(d)) * 3.6e6 * MAS


@pytest.fixture(params=["scalar", "array"])
def epochs_kind(request):
    return request.param


def times(kind, masked=False):
    if kind == "scalar":
        return Time("2023-01-25T20:00")
    t = Time("2023-01-25T00:00") + np.linspace(0, 2, 40) * u.day
    if masked:
        t[[3, 17]] = np.ma.masked
    return t


# --- the object itself -------------------------------------------------------------------

def test_epochs_are_made_once_and_handed_down():
    t = times("array", masked=True)
    epochs = Epochs(t)
    assert as_epochs(epochs) is epochs
    assert as_time(epochs) is t
    filled, mask = fill_masked(epochs)
    assert filled is epochs.filled and mask is epochs.mask
    assert epochs.masked and epochs.shape == (40,) and len(epochs) == 40
    assert epochs.orientation is epochs.orientation  # built once
    assert Epochs(epochs).time is t
    assert "2 masked" in repr(epochs)


def test_epochs_refuse_what_is_not_a_time():
    with pytest.raises(TypeError, match="obstime must be an astropy Time"):
        Epochs(60000.0)


def test_utc_earth_orientation_is_astropys():
    # Against astropy's Time.tt, Time.ut1 and its polar motion (an independent
    # route through astropy's IERS interpolation), across a leap second
    # (2016-12-31) and beyond the tables (where both hold the last values).
    from astropy.coordinates.builtin_frames.utils import get_polar_motion

    with pytest.warns(astropy_feedrot.StaleEarthOrientationWarning), iers_context():
        t = Time(["2016-12-31T12:00", "2016-12-31T23:59:59.5", "2017-01-01T00:00:00.5",
                  "2023-01-25T20:00", "2100-01-01T00:00"], scale="utc")  # ERFA: dubious year
        with iers_context(t):
            tt1, tt2, ut11, ut12, xp, yp = utc_earth_orientation(t.jd1, t.jd2)
        tt, ut1 = t.tt, t.ut1
        xp0, yp0 = get_polar_motion(t)
    day = 86400.0
    assert np.all(np.abs(((tt1 - tt.jd1) + (tt2 - tt.jd2)) * day) < 1e-9)
    assert np.all(np.abs(((ut11 - ut1.jd1) + (ut12 - ut1.jd2)) * day) < 1e-9)
    assert np.allclose(xp, xp0, rtol=0, atol=1e-15)
    assert np.allclose(yp, yp0, rtol=0, atol=1e-15)


def test_pole_and_sun_of_the_epochs():
    t = times("array", masked=True)
    epochs = Epochs(t)
    pole = epochs.celestial_pole()
    assert np.all(np.isnan(pole[[3, 17]])) and np.all(np.isfinite(pole[0]))
    # ERFA pom00 from astropy's own polar motion and TT: an independent route.
    from astropy.coordinates.builtin_frames.utils import get_polar_motion

    filled = epochs.filled
    with iers_context(filled):
        xp, yp = get_polar_motion(filled)
        tt = filled.tt
    reference = erfa.pom00(xp, yp, erfa.sp00(tt.jd1, tt.jd2))[..., :, 2]
    keep = ~epochs.mask
    assert np.allclose(pole[keep], reference[keep], rtol=0, atol=1e-15)
    # The Sun from nodes against astropy's transformation of ERFA epv00.
    fast, exact = epochs.sun_position(exact=False), epochs.sun_position(exact=True)
    sine = np.linalg.norm(np.cross(fast[keep], exact[keep]), axis=-1)
    assert np.all(sine / np.linalg.norm(exact[keep], axis=-1) ** 2 < 1e-11)  # radians
    assert np.all(np.isnan(fast[[3, 17]]))
    # The Earth's speed about the Sun: 29.3 to 30.3 km/s (ERFA epv00, in January).
    speed = np.linalg.norm(epochs.earth_velocity()[keep], axis=-1)
    assert np.all((speed > 30.0e3) & (speed < 30.4e3))


# --- every front-end agrees with the rigorous path ---------------------------------------

@pytest.mark.parametrize("station", STATIONS)
def test_antenna_on_a_golden_spiral_sky(station, epochs_kind):
    antenna = get_antenna(station)
    sources = sky()[:, np.newaxis] if epochs_kind == "array" else sky()
    t = times(epochs_kind, masked=epochs_kind == "array")
    fast = antenna.feed_rotation(sources, t)
    with conf.set_temp("fast_path", False):
        rigorous = antenna.feed_rotation(sources, t)
    assert fast.shape == rigorous.shape
    assert np.array_equal(np.isnan(fast), np.isnan(rigorous))
    assert wrapped_mas(fast, rigorous) < TOLERANCE
    if epochs_kind == "array":
        assert np.all(np.isnan(fast[:, [3, 17]]))  # masked epochs


def test_grid_and_shared_epochs_on_a_golden_spiral_sky():
    antennas = [get_antenna(name) for name in STATIONS]
    sources = sky(40)
    epochs = Epochs(times("array", masked=True))
    grid = feed_rotation_grid(antennas, sources, epochs)
    with conf.set_temp("fast_path", False):
        rigorous = feed_rotation_grid(antennas, sources, epochs.time)
    assert wrapped_mas(grid, rigorous) < TOLERANCE
    assert np.all(np.isnan(grid[[3, 17]]))
    # The same Epochs given to each antenna in turn: the same numbers, but for
    # the grid's shared directions (grid_natural: each site's diurnal aberration
    # added to the geocentric directions, 1e-4 mas in direction; the angle
    # moves more within a few degrees of the zenith and the nadir).
    for i, antenna in enumerate(antennas):
        one = antenna.feed_rotation(sources, epochs.time[:, np.newaxis])
        assert wrapped_mas(one, grid[:, i]) < SHARED
        assert np.array_equal(np.isnan(one), np.isnan(grid[:, i]))


def test_rate_takes_the_pole_and_sun_of_the_epochs():
    antenna = get_antenna("WETTZ13S")
    source = SkyCoord("03h19m48.16s +41d30m42.1s")
    epochs = Epochs(Time("2023-01-25T18:00") + np.arange(5) * u.hour)
    rate = antenna.feed_rotation_rate(source, epochs)
    # A centred difference of the rigorous angles over 2 s: an independent rate.
    step = 1 * u.s
    with conf.set_temp("fast_path", False):
        ahead = antenna.feed_rotation(source, epochs.time + step)
        behind = antenna.feed_rotation(source, epochs.time - step)
    difference = (ahead - behind).wrap_at(180 * u.deg) / (2 * step)
    assert np.allclose(rate.to_value(u.deg / u.s), difference.to_value(u.deg / u.s),
                       rtol=0, atol=1e-9)


@settings(max_examples=15, deadline=None)
@given(hours=st.lists(st.floats(0, 48), min_size=1, max_size=6),
       ra=st.floats(0, 360), dec=st.floats(-40, 89))
def test_antenna_grid_and_rows_agree(hours, ra, dec):
    antennas = {1: get_antenna("WETTZ13S"), 2: get_antenna("YEBES40M")}
    source = SkyCoord(ra * u.deg, dec * u.deg)
    t = Time("2023-01-25T00:00") + np.array(hours) * u.hour
    grid = feed_rotation_grid(list(antennas.values()), source, t)  # (T, 2, 1)
    rows = feed_rotation_rows(antennas, np.ones(t.size, int), np.full(t.size, 2), t, source)
    for i, antenna in enumerate(antennas.values()):
        one = antenna.feed_rotation(source, Epochs(t))
        assert wrapped_mas(one, grid[:, i, 0]) < SHARED  # the shared directions
        assert wrapped_mas(one, rows[:, i]) < SHARED
        assert wrapped_mas(grid[:, i, 0], rows[:, i]) < 1e-5 * MAS  # rounding only


def test_iers_tables_are_the_ones_in_use():
    # utc_earth_orientation follows a table set by the user (UT1 - UTC + 0.5 s).
    t = Time(["2023-01-25T00:00"])
    shifted = iers.IERS_Auto.open().copy()
    shifted["UT1_UTC"] = shifted["UT1_UTC"] + 0.5 * u.s
    with iers_context(t):
        before = utc_earth_orientation(t.jd1, t.jd2)
        with iers.earth_orientation_table.set(shifted):
            after = utc_earth_orientation(t.jd1, t.jd2)
    lead = ((after[2] - before[2]) + (after[3] - before[3])) * 86400.0
    assert np.allclose(lead, 0.5, atol=1e-9)


def test_kept_tables_are_astropys():
    # A fresh process reads the arrays of the bundled tables from the kept copy
    # (written by the first process that needed them) without loading astropy's
    # table; they must be the columns of that table once astropy loads it.
    import subprocess
    import sys

    code = (
        "import numpy as np\n"
        "from astropy.utils import iers\n"
        "from astropy_feedrot.earth.eop import iers_context, table_arrays, table_in_use\n"
        "with iers_context():\n"
        "    before = table_arrays()\n"
        "    assert table_in_use() is None\n"
        "    table = iers.earth_orientation_table.get()\n"
        "    after = table_arrays()\n"
        "assert table_in_use() is table\n"
        "for a, b in zip(before, after):\n"
        "    assert np.array_equal(a, b, equal_nan=True)\n"
        "print('same')\n"
    )
    for _ in range(2):  # the first may write the copy, the second reads it
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                             cwd=PACKAGE.parent, check=True)
        assert out.stdout.strip() == "same"


def cip_xy(tt1, tt2):
    """X, Y of the CIP from ERFA (IAU 2006/2000A), the reference of the kept nodes."""
    return np.stack(erfa.bpn2xy(erfa.pnm06a(tt1, tt2)), axis=-1)


def test_kept_nodes_agree_with_erfa_and_survive_a_bad_file(tmp_path, monkeypatch):
    from astropy_feedrot.earth import nodes as series

    monkeypatch.setattr(series, "get_cache_dir", lambda: str(tmp_path))
    series.clear_kept_nodes()
    kept = series.KeptSeries("test-cip", cip_xy, 16, 2459945.5, 0.0)  # 2023-01-01 TT
    tt = np.random.default_rng(3).uniform(0, 300, 50)
    # ERFA at the instants themselves: 16 nodes a day apart give 1e-13 rad.
    assert np.abs(kept.at(tt) - cip_xy(2459945.5, tt)).max() < 1e-12
    files = sorted(tmp_path.rglob("test-cip-*.npy"))
    assert files  # a year of nodes kept
    good = kept.at(tt)
    np.save(files[0], np.zeros((3, 2)))  # a file of the wrong shape is computed again
    series.clear_kept_nodes()
    fresh = series.KeptSeries("test-cip", cip_xy, 16, 2459945.5, 0.0)
    assert np.array_equal(fresh.at(tt), good)
    series.clear_kept_nodes()


def test_rate_on_the_grid():
    from astropy_feedrot import feed_rotation_rate_grid

    antennas = [get_antenna(name) for name in STATIONS]
    sources = sky(12)
    t = times("array", masked=True)[:12]
    rate = feed_rotation_rate_grid(antennas, sources, t, min_elevation=5 * u.deg)
    assert rate.shape == (12, 3, 12) and rate.unit == u.deg / u.s
    assert np.all(np.isnan(rate[3]))  # the masked epoch
    for i, antenna in enumerate(antennas):
        # Antenna.feed_rotation_rate is checked against a centred difference of
        # the rigorous angles (test_rate_takes_the_pole_and_sun_of_the_epochs).
        one = antenna.feed_rotation_rate(sources[:, np.newaxis], t, min_elevation=5 * u.deg)
        assert np.array_equal(np.isnan(one.T), np.isnan(rate[:, i]))
        # The grid's shared directions (grid_natural) move the rates by < 1e-11 deg/s.
        assert np.allclose(one.T, rate[:, i], rtol=0, atol=1e-10 * u.deg / u.s,
                           equal_nan=True)
    lcp = feed_rotation_rate_grid(antennas, sources, t, polarization="LCP")
    rcp = feed_rotation_rate_grid(antennas, sources, t)
    assert np.allclose(lcp, -rcp, equal_nan=True)  # Appendix D: the hands are opposite


def test_rate_on_the_grid_refuses():
    from astropy_feedrot import feed_rotation_rate_grid
    from astropy_feedrot.applied.simulations import gps_svn76

    antenna = [get_antenna("WETTZ13S")]
    t = times("array")
    with pytest.raises(TypeError, match="takes natural sources"):
        feed_rotation_rate_grid(antenna, [gps_svn76()], t)
    with pytest.raises(ValueError, match="scalar or 1-d SkyCoord"):
        feed_rotation_rate_grid(antenna, SkyCoord([[1, 2]] * u.deg, [[3, 4]] * u.deg), t)
    with pytest.raises(ValueError, match="scalar or 1-d Time"):
        feed_rotation_rate_grid(antenna, sky(3), t.reshape(4, 10))
