# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The Python API: bad input gets a clear error; degenerate geometry gets NaN and one warning.

Masked epochs, moving stars, sites off the Earth, units that are not what
they should be, arrays of the wrong shape: each public entry point either
refuses them with a message that says what to do, or computes the right
thing; never a silent wrong number.
"""

import warnings

import erfa
import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import ICRS, ITRS, EarthLocation, HADec, SkyCoord
from astropy.table import MaskedColumn, Table
from astropy.time import Time
from astropy.utils.masked import Masked
from helpers import DAY, MAS, SITES, itrs_direction

from astropy_feedrot import (
    AltAzMount,
    Antenna,
    BeamWaveguideFocus,
    CassegrainFocus,
    DegenerateGeometryWarning,
    EquatorialMount,
    FixedAxisMount,
    MirrorTrain,
    NasmythFocus,
    Satellite,
    SP3Orbit,
    StationaryMount,
    XYMount,
    rotation_delay,
    unwrap,
)
from astropy_feedrot.applied.correction import (
    correct_linear_visibilities,
    correct_phase,
    correct_visibilities,
)
from astropy_feedrot.applied.feed_rotation_tables import (
    baseline_summary,
    baseline_table,
    feed_rotation_table,
)
from astropy_feedrot.applied.rr_ll import baseline_rr_ll
from astropy_feedrot.applied.simulations import gps_svn76
from astropy_feedrot.data import sample_file
from astropy_feedrot.earth.frames import (
    as_elevation_limit,
    check_station_xyz,
    fill_masked,
    local_frame,
    location_xyz,
    source_direction,
    time_axis,
)
from astropy_feedrot.engine.grid import (
    feed_rotation_grid,
    feed_rotation_grid_dask,
    receiver_arrays,
    rotation_delay_grid,
    wind_up,
)
from astropy_feedrot.stations.catalogue import StationCatalogue, get_antenna

SITE = SITES["WETTZ13S"]
SOURCE = SkyCoord(ra=49.95 * u.deg, dec=41.51 * u.deg)


# --- wrong kinds of object -------------------------------------------------


def test_location_must_be_earthlocation():
    with pytest.raises(TypeError, match="location must be an astropy EarthLocation, got tuple"):
        Antenna((4075659.18, 931824.551, 4801516.102), AltAzMount())


def test_location_must_be_scalar():
    from astropy.coordinates import EarthLocation

    sites = EarthLocation.from_geodetic([0, 1] * u.deg, [0, 1] * u.deg)
    with pytest.raises(ValueError, match=r"one location, got an array of shape \(2,\)"):
        Antenna(sites, AltAzMount())


def test_mount_must_be_instance():
    with pytest.raises(TypeError, match=r"did you mean AltAzMount\(\)\?"):
        Antenna(SITE, AltAzMount)
    with pytest.raises(TypeError, match="mount must be a Mount instance .* got str"):
        Antenna(SITE, "alt-az")


def test_focus_must_be_instance():
    with pytest.raises(TypeError, match="focus must be a Focus instance .* got AltAzMount"):
        Antenna(SITE, AltAzMount(), AltAzMount())
    with pytest.raises(TypeError, match=r"did you mean CassegrainFocus\(\)\?"):
        Antenna(SITE, AltAzMount(), CassegrainFocus)


def test_target_must_be_a_coordinate():
    antenna = Antenna(SITE, AltAzMount())
    with pytest.raises(TypeError, match="target must be an astropy SkyCoord .* got tuple"):
        antenna.feed_rotation((49.95, 41.51), DAY)


def test_target_without_direction():
    antenna = Antenna(SITE, AltAzMount())
    with pytest.raises(ValueError, match="ICRS frame without a direction"):
        antenna.feed_rotation(ICRS(), DAY)


def test_frame_with_data_is_accepted():
    antenna = Antenna(SITE, AltAzMount())
    frame = ICRS(ra=49.95 * u.deg, dec=41.51 * u.deg)
    assert antenna.feed_rotation(frame, DAY[0]) == antenna.feed_rotation(SOURCE, DAY[0])


def test_obstime_must_be_a_time():
    antenna = Antenna(SITE, AltAzMount())
    with pytest.raises(TypeError, match="obstime must be an astropy Time .* got float"):
        antenna.feed_rotation(SOURCE, 59969.5)
    with pytest.raises(TypeError, match="obstime must be an astropy Time .* got str"):
        antenna.feed_rotation(SOURCE, "yesterday evening")


def test_local_frame_needs_location():
    with pytest.raises(TypeError, match="location must be an astropy EarthLocation"):
        local_frame("Wettzell")


# --- unknown options ---------------------------------------------------------


def test_unknown_polarization_lists_choices():
    antenna = Antenna(SITE, AltAzMount())
    with pytest.raises(ValueError, match=r"polarization must be one of \['L', 'LCP', 'LHCP'"):
        antenna.feed_rotation(SOURCE, DAY, polarization="X")
    with pytest.raises(ValueError, match="polarization must be one of"):
        antenna.feed_rotation(SOURCE, DAY, polarization=5)


@pytest.mark.parametrize("cls", [NasmythFocus, BeamWaveguideFocus])
def test_unknown_handedness_lists_choices(cls):
    with pytest.raises(ValueError, match=r"handedness must be one of \('right', 'left'\), got 'r'"):
        cls("r")


def test_unknown_xy_axis_lists_choices():
    with pytest.raises(ValueError, match=r"axis must be one of \('north', 'east'\), got 'ns'"):
        XYMount("ns")


def test_unknown_vertical_lists_choices():
    with pytest.raises(ValueError, match=r"vertical must be one of \('geodetic', 'geocentric'\)"):
        Antenna(SITE, AltAzMount(), vertical="astronomical")
    with pytest.raises(ValueError, match=r"vertical must be one of"):
        local_frame(SITE, vertical="plumb")


def test_unknown_yebes_band():
    with pytest.raises(ValueError, match=r"band must be one of \('X', 'S', 'C'\), got 'K'"):
        MirrorTrain.yebes40m("K")


def test_fixed_axis_validation():
    with pytest.raises(ValueError, match="frame must be one of"):
        FixedAxisMount([0, 0, 1], frame="altaz")
    with pytest.raises(ValueError, match="three finite numbers"):
        FixedAxisMount([0, 1])
    with pytest.raises(ValueError, match="three finite numbers"):
        FixedAxisMount([0, np.nan, 1])
    with pytest.raises(ValueError, match="three numbers"):
        FixedAxisMount("up")
    with pytest.raises(ValueError, match="non-zero length"):
        FixedAxisMount([0, 0, 0])


# --- focus and mount combinations -----------------------------------------


@pytest.mark.parametrize("focus", [NasmythFocus("right"), BeamWaveguideFocus("left")])
@pytest.mark.parametrize("mount", [EquatorialMount(), XYMount("north")])
def test_closed_form_foci_need_altaz(focus, mount):
    with pytest.raises(ValueError, match="is defined for an AltAzMount"):
        Antenna(SITE, mount, focus)


@pytest.mark.parametrize("focus", [NasmythFocus("right"), MirrorTrain.wark30m()])
def test_stationary_mount_has_no_optics(focus):
    with pytest.raises(ValueError, match="StationaryMount has no optics"):
        Antenna(SITE, StationaryMount(), focus)


def test_mirror_train_needs_fixed_axis_mount():
    with pytest.raises(ValueError, match="needs a steerable mount"):
        MirrorTrain.wark30m().check_mount(StationaryMount(), local_frame(SITE))


# --- mirror-train validation ---------------------------------------------


def test_mirror_train_dipoles_must_be_unit():
    with pytest.raises(ValueError, match="feed_aligned must be a unit vector, got length 2"):
        MirrorTrain([[0, -1, 0]], [0, 0, 2], [1, 0, 0])
    with pytest.raises(ValueError, match="feed_transverse must be a unit vector"):
        MirrorTrain([[0, -1, 0]], [0, 0, 1], [0.9, 0, 0])


def test_mirror_train_dipoles_must_be_orthogonal():
    s = np.sqrt(0.5)
    with pytest.raises(ValueError, match="feed dipoles must be orthogonal"):
        MirrorTrain([[0, -1, 0]], [0, 0, 1], [s, 0, s])


def test_mirror_train_feed_must_face_the_wave():
    with pytest.raises(ValueError, match="the feed must face the arriving wave"):
        MirrorTrain([[0, -1, 0]], [1, 0, 0], [0, 0, 1])  # boresight +eta = k_out
    with pytest.raises(ValueError, match="the feed must face the arriving wave"):
        MirrorTrain([[0, -1, 0]], [1, 0, 0], [0, 1, 0])  # boresight up


def test_mirror_train_ground_fixed_feed_must_be_on_axis():
    with pytest.raises(ValueError, match="along the fixed axis"):
        MirrorTrain([[0, -1, 0]], [1, 0, 0], [0, 1, 0], feed_rotates=False)
    # Facing down the axis instead of up it.
    with pytest.raises(ValueError, match="up the fixed axis of AltAzMount"):
        Antenna(SITE, AltAzMount(), MirrorTrain([[0, -1, 0], [0, 0, -1]], [0, 1, 0], [1, 0, 0],
                                                feed_rotates=False))


def test_mirror_train_wave_vectors():
    with pytest.raises(ValueError, match="no mirror between them"):
        MirrorTrain([[0, -1, 0], [0, -2, 0]], [0, 0, 1], [-1, 0, 0])
    with pytest.raises(ValueError, match="wave vector 3 has zero length"):
        MirrorTrain([[0, -1, 0], [0, 0, 0]], [0, 0, 1], [-1, 0, 0])
    with pytest.raises(ValueError, match="one or more 3-vectors"):
        MirrorTrain([[0, -1]], [0, 0, 1], [-1, 0, 0])
    with pytest.raises(ValueError, match="must be finite"):
        MirrorTrain([[0, np.inf, 0]], [0, 0, 1], [-1, 0, 0])
    with pytest.raises(ValueError, match="must be numbers"):
        MirrorTrain([["a", "b", "c"]], [0, 0, 1], [-1, 0, 0])
    with pytest.raises(ValueError, match="each be one 3-vector"):
        MirrorTrain([[0, -1, 0]], [[0, 0, 1], [0, 0, 1]], [-1, 0, 0])


# --- degenerate geometry: NaN and one warning ------------------------------


def _zenith_and_more(site, n_zenith=2):
    up = local_frame(site).up
    other = np.array([[0.3, 0.2, 0.9], [0.0, 0.7, 0.7], [0.6, 0.8, 0.0]])
    return itrs_direction(np.vstack([np.tile(up, (n_zenith, 1)), other]))


def test_zenith_of_altaz_gives_nan_and_one_warning():
    antenna = Antenna(SITE, AltAzMount())
    with pytest.warns(DegenerateGeometryWarning, match="undefined at 2 of 5 epochs") as record:
        phi = antenna.feed_rotation(_zenith_and_more(SITE), DAY[0])
    assert len(record) == 1
    assert np.all(np.isnan(phi[:2])) and np.all(np.isfinite(phi[2:]))


@pytest.mark.parametrize("focus", [NasmythFocus("right"), BeamWaveguideFocus("right"),
                                   MirrorTrain.yebes40m("X"), MirrorTrain.wark30m()])
def test_zenith_for_every_alt_az_focus(focus):
    antenna = Antenna(SITE, AltAzMount(), focus)
    with pytest.warns(DegenerateGeometryWarning, match="undefined at 1 of 4 epochs"):
        phi = antenna.feed_rotation(_zenith_and_more(SITE, 1), DAY[0])
    assert np.isnan(phi[0]) and np.all(np.isfinite(phi[1:]))


def test_pole_of_equatorial_mount_gives_nan():
    antenna = Antenna(SITE, EquatorialMount())
    targets = itrs_direction([[0, 0, 1.0], [0.6, 0.0, 0.8]])
    with pytest.warns(DegenerateGeometryWarning, match="undefined at 1 of 2 epochs"):
        phi = antenna.feed_rotation(targets, DAY[0])
    assert np.isnan(phi[0]) and phi[1] == 0


def test_source_on_fixed_axis_gives_nan():
    antenna = Antenna(SITE, FixedAxisMount([1.0, 0, 0]))
    with pytest.warns(DegenerateGeometryWarning, match="undefined at 1 of 2 epochs"):
        phi = antenna.feed_rotation(itrs_direction([[1.0, 0, 0], [0, 1.0, 0]]), DAY[0])
    assert np.isnan(phi[0]) and np.isfinite(phi[1])


def test_celestial_pole_for_stationary_antenna_gives_nan():
    antenna = Antenna(SITE, StationaryMount())
    with pytest.warns(DegenerateGeometryWarning, match="celestial pole"):
        phi = antenna.feed_rotation(itrs_direction([0, 0, 1.0]), DAY[0])
    assert np.isnan(phi)


def test_parallactic_angle_warns_at_zenith():
    antenna = Antenna(SITE, EquatorialMount())
    with pytest.warns(DegenerateGeometryWarning, match="parallactic angle is undefined"):
        antenna.parallactic_angle(_zenith_and_more(SITE, 1), DAY[0])


def test_nan_input_gives_nan_without_warning():
    antenna = Antenna(SITE, AltAzMount())
    targets = SkyCoord(ra=[49.95, np.nan] * u.deg, dec=[41.51, 10.0] * u.deg)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        phi = antenna.feed_rotation(targets, DAY[0])
    assert np.isfinite(phi[0]) and np.isnan(phi[1])


# --- frames -----------------------------------------------------------------


def test_itrs_position_is_differenced_with_site():
    # A position 1000 km straight above the site is at its zenith (Eq 2).
    up = local_frame(SITE).up
    xyz = location_xyz(SITE) + 1e6 * up
    position = SkyCoord(ITRS(*(xyz * u.m), obstime=DAY[0], representation_type="cartesian"))
    np.testing.assert_allclose(source_direction(position, SITE, DAY[0]), up, atol=1e-12)
    # The same point given topocentrically (ITRS with a location).
    topo = SkyCoord(ITRS(*(1e6 * up * u.m), obstime=DAY[0], location=SITE,
                         representation_type="cartesian"))
    np.testing.assert_allclose(source_direction(topo, SITE, DAY[0]), up, atol=1e-12)


def test_source_direction_agrees_with_altaz():
    from astropy.coordinates import AltAz
    from helpers import MAS, sky_grid

    grid = sky_grid(30)[:, np.newaxis]
    s = source_direction(grid, SITE, DAY)
    aa = grid.transform_to(AltAz(obstime=DAY, location=SITE))
    e, n, up = local_frame(SITE)
    expected = (np.cos(aa.alt.rad) * np.sin(aa.az.rad))[..., None] * e + (
        np.cos(aa.alt.rad) * np.cos(aa.az.rad))[..., None] * n + np.sin(aa.alt.rad)[..., None] * up
    separation = np.arccos(np.clip(np.sum(s * expected, axis=-1), -1, 1))
    assert separation.max() < 10 * MAS  # diurnal-aberration conventions differ by < 10 mas


def test_computations_stay_offline():
    from astropy.utils import iers

    from astropy_feedrot import conf
    from astropy_feedrot.earth.eop import iers_context

    with iers.conf.set_temp("auto_download", True):
        with iers_context():
            assert iers.conf.auto_download is False
        with conf.set_temp("iers_auto_download", True), iers_context():
            assert iers.conf.auto_download is True
        assert iers.conf.auto_download is True


# --- shared inputs ------------------------------------------------------------

#: A GNSS antenna and a telescope 73 m apart (Table 1), and GPS SVN 76 over
#: them on 2023-01-25 (Sec. 4.1).
DBR, FD = get_antenna("DBR205"), get_antenna("FD-VLBA")
GPS_PASS = Time("2023-01-25T08:10") + np.arange(1000) * 20 * u.s
L1 = 1575.42 * u.MHz


def masked_copy(times, where):
    """``times`` with the epochs at ``where`` masked (astropy >= 6)."""
    out = times.copy()
    out[where] = np.ma.masked
    return out


# --- masked epochs: NaN, never a number, for any number of epochs ------------

# 16 epochs switch the fast path on (frames._FAST_PATH_MIN_EPOCHS).
EPOCH_COUNTS = [1, 2, 15, 16, 17, 1000]


def _mask_of(n):
    mask = np.zeros(n, bool)
    mask[0] = True
    mask[n // 2] = True
    return mask


def _targets():
    return {"natural": (get_antenna("WETTZ13S"), SOURCE), "satellite": (DBR, gps_svn76()),
            "telescope-satellite": (FD, gps_svn76())}


@pytest.mark.parametrize("n", EPOCH_COUNTS)
@pytest.mark.parametrize("kind", ["natural", "satellite", "telescope-satellite"])
def test_masked_epochs_give_nan_without_warning(n, kind):
    antenna, target = _targets()[kind]
    times = GPS_PASS[:n]
    mask = _mask_of(n)
    masked = masked_copy(times, mask)
    for method in ("feed_rotation", "parallactic_angle"):
        reference = getattr(antenna, method)(target, times)
        result = getattr(antenna, method)(target, masked)  # warnings are errors here
        assert np.all(np.isnan(result[mask]))
        # The other epochs are those of the unmasked series, to the last bit.
        assert np.array_equal(result[~mask], reference[~mask])
    terms = antenna.feed_rotation_terms(target, masked)
    for angle in terms:
        assert np.all(np.isnan(angle[mask])) and np.all(np.isfinite(angle[~mask]))
    az, el = antenna.altaz(target, masked)
    assert np.all(np.isnan(az[mask])) and np.all(np.isnan(el[mask]))
    assert np.all(np.isfinite(el[~mask]))


@pytest.mark.parametrize("n", [1, 17])
def test_every_epoch_masked(n):
    times = masked_copy(GPS_PASS[:n], slice(None))
    for antenna, target in _targets().values():
        assert np.all(np.isnan(antenna.feed_rotation(target, times)))
    scalar = masked_copy(GPS_PASS[:1], 0)[0]
    assert scalar.isscalar and np.isnan(DBR.feed_rotation(gps_svn76(), scalar))
    assert np.isnan(get_antenna("WETTZ13S").feed_rotation(SOURCE, scalar))


def test_masked_epochs_never_reach_the_orbit():
    # A masked Time made from a masked array holds J2000 under the mask, far
    # outside the 45 min of this SP3 file: the orbit is never asked for it.
    orbit = SP3Orbit(sample_file("sample.sp3"), "G01", points=4)
    start = Time("2023-01-25T00:00", scale="utc")
    mjd = np.ma.masked_array(start.mjd + np.arange(20) / 1440, mask=np.arange(20) % 7 == 3)
    times = Time(mjd, format="mjd", scale="utc")
    assert times.masked and np.all(times.unmasked.mjd[times.mask] == 51544.5)
    phi = FD.feed_rotation(Satellite(orbit), times)
    assert np.array_equal(np.isnan(phi), times.mask)


def test_fill_masked_stand_ins():
    times = masked_copy(DAY[:5], [0, 3])
    filled, mask = fill_masked(times)
    assert mask.tolist() == [True, False, False, True, False]
    # Leading masked epochs take the first valid one, the others the previous one.
    assert filled.isot.tolist() == DAY[[1, 1, 2, 2, 4]].isot.tolist()
    assert not filled.masked
    plain = DAY[:3]
    unmasked, none = fill_masked(plain)
    assert none is None and unmasked is plain


@pytest.mark.parametrize("n", [2, 17, 1000])
@pytest.mark.parametrize("natural", [False, True])
def test_masked_epochs_in_grids(n, natural):
    targets = SOURCE.reshape((1,)) if natural else [gps_svn76()]
    antennas = [DBR, FD, get_antenna("WETTZ13S")]
    mask = _mask_of(n)
    times = masked_copy(GPS_PASS[:n], mask)
    reference = feed_rotation_grid(antennas, targets, GPS_PASS[:n])
    phi = feed_rotation_grid(antennas, targets, times)
    assert np.all(np.isnan(phi[mask]))
    assert np.array_equal(phi[~mask], reference[~mask])
    lazy = feed_rotation_grid_dask(antennas, targets, times, chunks=7).compute()
    assert np.array_equal(np.isnan(lazy), np.isnan(phi.deg))
    every = feed_rotation_grid(antennas, targets, masked_copy(GPS_PASS[:n], slice(None)))
    assert np.all(np.isnan(every))


def test_masked_epochs_in_delays_and_tables():
    times = GPS_PASS[:200]
    mask = np.zeros(times.size, bool)
    mask[[0, 50, 51, 120]] = True
    masked = masked_copy(times, mask)
    # The delay: NaN at masked epochs, and the series restarts after them as
    # after any left-out sample (unwrap with mask=).
    result = rotation_delay(DBR, FD, gps_svn76(), masked, L1, max_gap=10 * u.min)
    assert np.all(np.isnan(result.delay[mask])) and np.all(np.isfinite(result.delay[~mask]))
    difference = FD.feed_rotation(gps_svn76(), times) - DBR.feed_rotation(gps_svn76(), times)
    expected = unwrap(difference, mask=mask).to_value(u.rad) / (2 * np.pi * L1.to_value(u.Hz))
    np.testing.assert_allclose(result.delay.to_value(u.s), expected, rtol=0, atol=1e-18)
    phi = feed_rotation_grid([DBR, FD], [gps_svn76()], masked)
    grid_delay = rotation_delay_grid(phi, L1, obstime=masked, max_gap=10 * u.min).delay
    np.testing.assert_allclose(grid_delay[:, 0].to_value(u.ps),
                               result.delay.to_value(u.ps), rtol=0, atol=1e-6)
    table = feed_rotation_table(FD, gps_svn76(), masked, min_elevation=10 * u.deg)
    assert np.all(np.isnan(table["total"][mask])) and np.all(np.isnan(table["elevation"][mask]))
    assert np.all(table["time"].mask == mask)
    baseline = baseline_table(DBR, FD, gps_svn76(), masked, L1)
    assert not np.any(baseline["both_visible"][mask])
    assert np.all(np.isnan(baseline["rotation_delay"][mask]))
    assert "both above None" in baseline_summary(baseline)


def test_masked_epochs_in_unwrap_obstime():
    angles = np.radians([170.0, -170, -150, 170, -170])
    times = masked_copy(DAY[:5], 2)
    out = unwrap(angles, obstime=times)
    # NaN at the masked epoch, and a restart after it.
    np.testing.assert_allclose(np.degrees(out.value), [170, 190, np.nan, 170, 190])


def test_tables_refuse_unsorted_epochs_masked_aside():
    times = masked_copy(DAY[[0, 1, 1, 2]], 1)  # a repeated epoch, masked: fine
    assert len(feed_rotation_table(get_antenna("WETTZ13S"), SOURCE, times)) == 4
    with pytest.raises(ValueError, match=r"obstime must increase strictly \(masked epochs "
                                         r"aside\); sort it"):
        feed_rotation_table(get_antenna("WETTZ13S"), SOURCE, DAY[[0, 2, 1]])


# --- sites that are not Earth stations --------------------------------------


@pytest.mark.parametrize("xyz, match", [
    ((np.nan, 0, 0), r"location has a NaN or infinite coordinate: \[nan, 0.0, 0.0\]"),
    ((0, np.inf, 0), r"location has a NaN or infinite coordinate"),
    ((0, 0, 0), r"location is 0 m from the geocentre, at a geodetic height of -6356.8 km; "
                r"an Earth station lies between -12 and 100 km"),
    ((4075.659, 931.825, 4801.516), r"location is 6367 m from the geocentre.* \(are the "
                                    r"coordinates in metres\?\)"),
    ((-6.6e25, -6.6e25, 7.7e25), r"location is .* m from the geocentre.* an Earth station"),
    ((1.18e26, 0, 0), r"location is .* m from the geocentre.* an Earth station"),
    ((0, 0, 1.18e26), r"location is .* m from the geocentre.* an Earth station"),
])
def test_antenna_refuses_sites_off_the_earth(xyz, match):
    with pytest.raises(ValueError, match=match):
        Antenna(EarthLocation.from_geocentric(*xyz, unit=u.m), AltAzMount())


@pytest.mark.parametrize("height, accepted", [
    (-12.5 * u.km, False), (-11.9 * u.km, True), (99.9 * u.km, True), (100.1 * u.km, False),
    (1000 * u.km, False)])
def test_antenna_height_bounds(height, accepted):
    # STATION_HEIGHTS: -12 km (below the Challenger Deep) to 100 km (the Karman line).
    site = EarthLocation.from_geodetic(12 * u.deg, 49 * u.deg, height)
    if accepted:
        Antenna(site, AltAzMount())
    else:
        with pytest.raises(ValueError, match=r"geodetic height of .* an Earth station lies "
                                             r"between -12 and 100 km"):
            Antenna(site, AltAzMount())


def test_check_station_xyz_names_the_bad_row():
    xyz = np.array([[4075659.18, 931824.551, 4801516.102], [4075.659, 931.825, 4801.516]])
    with pytest.raises(ValueError, match=r"station_xyz\[1\] is 6367 m from the geocentre"):
        check_station_xyz(xyz, "station_xyz")
    with pytest.raises(ValueError, match=r"must be geocentric x, y, z, got shape \(2,\)"):
        check_station_xyz([1.0, 2.0])


def _catalogue(**columns):
    table = Table({"name": ["A"], "x": [4075659.18] * u.m, "y": [931824.551] * u.m,
                   "z": [4801516.102] * u.m, "mount": ["AZEL"]})
    for name, value in columns.items():
        table[name] = value
    return table


def _velocity(vx, unit=u.m / u.yr, epoch=58849.0):
    return dict(vx=[vx] * unit, vy=[0.0] * unit, vz=[0.0] * unit, epoch=[epoch])


@pytest.mark.parametrize("columns, match", [
    (dict(x=[np.nan] * u.m), r"station A: position has a NaN or infinite coordinate"),
    (dict(x=[4075659.18 * 1.1] * u.m), r"station A: position is .* geodetic height of "),
    (dict(x=MaskedColumn([4075659.18], mask=[True], unit=u.m)),
     r"station A: no value in column\(s\) x; every station needs x, y, z"),
    # Velocities in mm/yr labelled m/yr, and in m/s: both far above plate motions.
    (_velocity(-14.31), r"station A: velocity is 14.31 m/yr; station velocities are below "
                        r"1 m/yr .*\(mm/yr labelled m/yr\?"),
    (_velocity(0.0143, u.m / u.s), r"velocity is 4.513e\+05 m/yr"),
    (_velocity(np.nan), r"velocity is nan m/yr"),
    (dict(vx=MaskedColumn([0.01], mask=[True], unit=u.m / u.yr), vy=[0.0] * u.m / u.yr,
          vz=[0.0] * u.m / u.yr, epoch=[58849.0]),
     r"no value in column\(s\) vx; every station needs vx, vy, vz"),
    (_velocity(0.01, epoch=np.inf), r"station A: epoch is inf; give the MJD"),
    (dict(vx=[0.01] * u.m / u.yr, vy=[0.0] * u.m / u.yr, vz=[0.0] * u.m / u.yr,
          epoch=["2020-01-01"]), r"column 'epoch' must hold MJD numbers"),
])
def test_catalogue_refuses_what_is_not_a_station(columns, match):
    with pytest.raises(ValueError, match=match):
        StationCatalogue(_catalogue(**columns))


def test_catalogue_velocity_within_bound_and_missing():
    # The fastest plates move ~0.2 m/yr; 0.9 m/yr is accepted, and a row with
    # no velocity at all has no velocity model.
    moving = StationCatalogue(_catalogue(**_velocity(0.9)))
    x = moving.location("A", epoch=Time("2030-01-01", scale="tt")).x
    np.testing.assert_allclose(x.to_value(u.m), 4075659.18 + 0.9 * 10.0, atol=0.02)
    gone = MaskedColumn([0.0], mask=[True], unit=u.m / u.yr)
    still = StationCatalogue(_catalogue(vx=gone, vy=gone, vz=gone, epoch=[58849.0]))
    assert still.location("A", epoch="2030-01-01").x == 4075659.18 * u.m


def test_get_antenna_epoch_checks():
    catalogue = StationCatalogue(_catalogue(**_velocity(0.9)))
    with pytest.raises(TypeError, match=r"epoch must be an astropy Time or an ISO string .* "
                                        r"got str 'garbage'"):
        get_antenna("A", catalogue, epoch="garbage")
    with pytest.raises(TypeError, match="got float 2030.0"):
        get_antenna("A", catalogue, epoch=2030.0)
    masked = masked_copy(Time(["2030-01-01"], scale="tt"), 0)[0]
    with pytest.raises(ValueError, match="epoch is masked"):
        get_antenna("A", catalogue, epoch=masked)
    with pytest.raises(ValueError, match=r"epoch must be a single time, got shape \(2,\)"):
        get_antenna("A", catalogue, epoch=["2030-01-01", "2031-01-01"])
    # 0.9 m/yr over 200,000 years would put the station 180 km off.
    far = Time(202020.0, format="jyear", scale="tt")
    with pytest.raises(ValueError, match=r"station A: position at .* is .* from the "
                                         r"geocentre, at a geodetic height"):
        get_antenna("A", catalogue, epoch=far)


# --- frequencies that are not one frequency -----------------------------------

FREQUENCY_ERRORS = [
    (1.4e9, TypeError, r"frequency must be a frequency Quantity \(e.g. 1575.42 \* u.MHz\), "
                       r"got float 1400000000.0; plain numbers are refused"),
    (21 * u.cm, u.UnitsError, r"frequency must be a frequency .* got a quantity in cm; for a "
                              r"wavelength convert it first: wavelength.to\(u.GHz, "
                              r"equivalencies=u.spectral\(\)\)"),
    (1 * u.s, u.UnitsError, r"got a quantity in s$"),
    (1 * u.one, u.UnitsError, r"got a quantity in dimensionless units"),
    ([1, 2] * u.GHz, ValueError, r"frequency must be a single frequency, got shape \(2,\)"),
    (0 * u.Hz, ValueError, r"frequency must be positive and finite, got 0.0 Hz"),
    (-1 * u.GHz, ValueError, r"must be positive and finite"),
    (np.nan * u.GHz, ValueError, r"must be positive and finite, got nan GHz"),
    (np.inf * u.GHz, ValueError, r"must be positive and finite, got inf GHz"),
]


@pytest.mark.parametrize("frequency, error, match", FREQUENCY_ERRORS)
def test_rotation_delay_refuses_what_is_not_a_frequency(frequency, error, match):
    times = GPS_PASS[:20]
    with pytest.raises(error, match=match):
        rotation_delay(DBR, FD, gps_svn76(), times, frequency)
    with pytest.raises(error, match=match):
        baseline_table(DBR, FD, gps_svn76(), times, frequency)
    phi = feed_rotation_grid([DBR, FD], [gps_svn76()], times)
    with pytest.raises(error, match=match):
        rotation_delay_grid(phi, frequency)


# --- the time axis of a continuous series ------------------------------------

#: Three sources that rise and set over Wettzell in a day.
SOURCES = SkyCoord(ra=[49.95, 150.0, 280.0] * u.deg, dec=[41.51, 20.0, 75.0] * u.deg)


def test_rotation_delay_follows_the_time_axis():
    wettzell, effelsberg = get_antenna("WETTZ13S"), get_antenna("EFLSBERG")
    times = DAY[:40]
    # Reference: one 1-d series per source.
    single = np.stack([rotation_delay(wettzell, effelsberg, source, times, 8.4 * u.GHz).delay
                       for source in SOURCES])
    last = rotation_delay(wettzell, effelsberg, SOURCES[:, np.newaxis], times, 8.4 * u.GHz)
    first = rotation_delay(wettzell, effelsberg, SOURCES, times[:, np.newaxis], 8.4 * u.GHz)
    assert last.delay.shape == (3, 40) and first.delay.shape == (40, 3)
    np.testing.assert_allclose(last.delay.to_value(u.ps), single.to_value(u.ps), atol=1e-9)
    np.testing.assert_allclose(first.delay.T.to_value(u.ps), single.to_value(u.ps), atol=1e-9)
    # One epoch: each source is a series of one sample; nothing is carried between them.
    one = rotation_delay(wettzell, effelsberg, SOURCES, times[5], 8.4 * u.GHz)
    np.testing.assert_allclose(one.delay.to_value(u.ps), single[:, 5].to_value(u.ps),
                               atol=1e-9)


def test_time_axis_refuses_ambiguity():
    wettzell, effelsberg = get_antenna("WETTZ13S"), get_antenna("EFLSBERG")
    grid_of_times = DAY[:6].reshape(2, 3)
    with pytest.raises(ValueError, match=r"obstime of shape \(2, 3\) runs along axes \[0, 1\] "
                                         r"of the shape \(2, 3\); a continuous series"):
        rotation_delay(wettzell, effelsberg, SOURCE, grid_of_times, 8.4 * u.GHz)
    with pytest.raises(ValueError, match=r"runs along axes \[0, 1\]"):
        baseline_rr_ll(wettzell, effelsberg, SOURCE, grid_of_times, wrap=False)
    with pytest.raises(ValueError, match=r"does not broadcast to the shape \(3,\)"):
        time_axis((2, 3), (3,))
    assert time_axis((1, 4), (3, 4)) == 1


def test_rr_minus_ll_follows_the_time_axis():
    wettzell, effelsberg = get_antenna("WETTZ13S"), get_antenna("EFLSBERG")
    times = DAY[:40]
    rows = baseline_rr_ll(wettzell, effelsberg, SOURCES[:, np.newaxis], times, wrap=False)
    columns = baseline_rr_ll(wettzell, effelsberg, SOURCES, times[:, np.newaxis], wrap=False)
    np.testing.assert_allclose(columns.T.deg, rows.deg, atol=1e-9)
    for i, source in enumerate(SOURCES):
        np.testing.assert_allclose(
            rows[i].deg, baseline_rr_ll(wettzell, effelsberg, source, times, wrap=False).deg,
            atol=1e-9)


def test_unwrap_time_axis_and_order():
    angles = np.radians([[170.0, -170, -150], [10, 20, 30]])
    times = DAY[:3]
    with pytest.raises(ValueError, match=r"obstime of shape \(2, 1\) runs along axis 0 of the "
                                         r"angles of shape \(2, 3\), but axis=1: pass axis=0"):
        unwrap(angles, obstime=times[:2, np.newaxis])
    assert unwrap(angles.T, axis=0, obstime=times[:, np.newaxis]).shape == (3, 2)
    with pytest.raises(ValueError, match="obstime decreases along the time axis; sort the "
                                         "series by time"):
        unwrap(angles, obstime=times[::-1])
    with pytest.raises(ValueError, match=r"axis 2 is out of range for angles with 2 "
                                         r"dimensions; give one of -2..1"):
        unwrap(angles, axis=2)
    with pytest.raises(TypeError, match="axis must be an integer, got float 1.5"):
        unwrap(angles, axis=1.5)


# --- elevation limits that are not one angle in [-90, 90] deg -----------------

ELEVATION_ERRORS = [
    (np.nan * u.deg, ValueError, r"min_elevation must be within \[-90, 90\] deg, got nan deg"),
    (10, TypeError, r"min_elevation must be an angle Quantity \(e.g. 10 \* u.deg\) or None, "
                    r"got int 10; plain numbers are refused"),
    (10 * u.m, u.UnitsError, r"min_elevation must be an angle .* got a quantity in m"),
    (95 * u.deg, ValueError, r"within \[-90, 90\] deg, got 95.0 deg"),
    (-1.6 * u.rad, ValueError, r"within \[-90, 90\] deg, got -1.6 rad"),
    ([5, 10] * u.deg, ValueError, r"min_elevation must be a single angle, got shape \(2,\)"),
]


@pytest.mark.parametrize("limit, error, match", ELEVATION_ERRORS)
def test_elevation_limit_refused_everywhere(limit, error, match):
    times = GPS_PASS[:20]
    calls = [
        lambda: FD.feed_rotation(gps_svn76(), times, min_elevation=limit),
        lambda: FD.feed_rotation_terms(SOURCE, times, min_elevation=limit),
        lambda: feed_rotation_grid([DBR, FD], [gps_svn76()], times, min_elevation=limit),
        lambda: feed_rotation_grid_dask([DBR, FD], SOURCE, times, min_elevation=limit),
        lambda: feed_rotation_table(FD, gps_svn76(), times, min_elevation=limit),
        lambda: baseline_table(DBR, FD, gps_svn76(), times, L1, min_elevation=limit),
        lambda: rotation_delay(DBR, FD, gps_svn76(), times, L1, min_elevation=limit),
        lambda: baseline_rr_ll(DBR, FD, SOURCE, times, min_elevation=limit),
    ]
    for call in calls:
        with pytest.raises(error, match=match):
            call()


def test_elevation_limit_edges():
    assert as_elevation_limit(None) is None
    assert as_elevation_limit(90 * u.deg) == np.pi / 2
    assert as_elevation_limit(-90 * u.deg) == -np.pi / 2
    below = FD.feed_rotation(gps_svn76(), GPS_PASS[:20], min_elevation=90 * u.deg)
    assert np.all(np.isnan(below))
    every = FD.feed_rotation(gps_svn76(), GPS_PASS[:20], min_elevation=-90 * u.deg)
    assert np.all(np.isfinite(every))


# --- unwrap: masked arrays, units, kinds -----------------------------------


def test_unwrap_honours_masks_of_masked_arrays():
    degrees = np.array([170.0, -170, 0, -150, 170, -170])
    mask = np.array([False, False, True, False, False, False])
    expected = unwrap(degrees * u.deg, mask=mask)
    # NaN at the masked sample (its value, 0, is never used) and a restart after it.
    np.testing.assert_allclose(expected.deg, [170, 190, np.nan, -150, -190, -170])
    numpy_masked = unwrap(np.ma.masked_array(np.radians(degrees), mask=mask))
    np.testing.assert_allclose(numpy_masked.to_value(u.deg), expected.deg)
    astropy_masked = unwrap(Masked(degrees * u.deg, mask=mask))
    assert astropy_masked.unit == u.deg and not isinstance(astropy_masked, Masked)
    np.testing.assert_allclose(astropy_masked.deg, expected.deg)


@pytest.mark.parametrize("angle, kwargs, error, match", [
    ([1, 2] * u.m, {}, u.UnitsError, "angle must be an angle .* got a quantity in m"),
    (np.array(["a", "b"], dtype=object), {}, TypeError,
     "angle must be an angle Quantity or numbers .* dtype object"),
    ("abc", {}, TypeError, r"dtype <U3"),
    ([1.0, 2.0], {"mask": ["yes", "no"]}, TypeError, r"mask must be booleans, got dtype <U3"),
    ([1.0, 2.0], {"mask": [True, False, True]}, ValueError,
     r"angle has shape \(2,\), mask has shape \(3,\)"),
    ([1.0, 2.0], {"obstime": DAY[:2], "max_gap": 5}, TypeError,
     "max_gap must be a time Quantity .* got int 5"),
    ([1.0, 2.0], {"obstime": DAY[:2], "max_gap": 5 * u.m}, u.UnitsError,
     "max_gap must be a time .* got a quantity in m"),
    ([1.0, 2.0], {"obstime": DAY[:2], "max_gap": -5 * u.min}, ValueError,
     "max_gap must be one positive finite time, got -5.0 min"),
    ([1.0, 2.0], {"obstime": [1.0, 2.0]}, TypeError,
     "obstime must be an astropy Time .* plain numbers; their format cannot be guessed"),
])
def test_unwrap_refuses(angle, kwargs, error, match):
    with pytest.raises(error, match=match):
        unwrap(angle, **kwargs)


def test_unwrap_accepts_dimensionless_and_object_numbers():
    np.testing.assert_allclose(unwrap([3.0, -3.0] * u.one).value, [3.0, 2 * np.pi - 3.0])
    np.testing.assert_allclose(unwrap(np.array([3.0, -3.0], dtype=object)).value,
                               [3.0, 2 * np.pi - 3.0])
    assert unwrap([] * u.deg).shape == (0,)


# --- wind_up on plain arrays -------------------------------------------------

ENU = np.array([[[0.0, 1, 0], [0, 0, 1], [1, 0, 0]]])  # east, north, up at lon 0, lat 0
ON_EQUATOR = [[6.378137e6, 0, 0]]
C30, S30 = np.cos(np.radians(30)), np.sin(np.radians(30))
OVERHEAD = [[[2.6e7, 1e6, 2e6]]]
ALIGNED, TRANSVERSE = [[[0, C30, S30]]], [[[0, S30, -C30]]]
DIRECTION = np.array([[[0.6, 0.0, 0.8]]])


@pytest.mark.parametrize("kwargs, error, match", [
    (dict(station_xyz=[[np.nan, 0, 0]]), ValueError,
     r"station_xyz\[0\] has a NaN or infinite coordinate"),
    (dict(station_xyz=[[6378.137, 0, 0]]), ValueError,
     r"station_xyz\[0\] is 6378 m from the geocentre"),
    (dict(station_xyz=[["a", 0, 0]]), TypeError, "station_xyz must be an array of numbers"),
    (dict(station_axes=2 * ENU), ValueError,
     r"station_axes must be unit vectors .* station_axes\[0, 0\] has length 2"),
    (dict(station_axes=ENU[:, [1, 0, 2]]), ValueError,
     r"station_axes\[0\] must hold east, north and up as an orthonormal right-handed set"),
    (dict(stationary=["False"]), TypeError, "stationary must be booleans"),
    (dict(stationary=[0.5]), TypeError, "stationary must be booleans"),
    (dict(target=[[[2.6e4, 0, 0]]]), ValueError,
     r"target\[0, 0\] is 26000 m from the geocentre, inside the Earth; .* \(kilometres\?\)"),
    (dict(target=[[[np.inf, 0, 0]]]), ValueError, "target positions have infinite components"),
    (dict(aligned=[[[0, 2 * C30, 2 * S30]]]), ValueError,
     r"aligned must be unit vectors .* aligned\[0, 0\] has length 2"),
    (dict(aligned=[[[0, 0, 0]]]), ValueError, "has length 0; normalize them .* a zero vector "
                                              "has no direction"),
    (dict(transverse=ALIGNED), ValueError,
     r"aligned\[0, 0\] and transverse\[0, 0\] must be orthogonal"),
    (dict(fixed_axis=[[0, 0, 0]]), ValueError, r"fixed_axis\[0\] has length 0"),
    (dict(focus_terms=[[0.5, 0]]), ValueError,
     r"focus_terms\[0\] is \[0.5, 0.0\]; it must be one of \[\(0, 0\), \(1, 0\)"),
    (dict(directions="yes"), TypeError, "directions must be True or False, got 'yes'"),
])
def test_wind_up_refuses(kwargs, error, match):
    arguments = dict(station_xyz=ON_EQUATOR, station_axes=ENU, stationary=[True],
                     target=OVERHEAD, aligned=ALIGNED, transverse=TRANSVERSE)
    arguments.update(kwargs)
    with pytest.raises(error, match=match):
        wind_up(**arguments)


@pytest.mark.parametrize("scale, match", [(2.0, "has length 2"), (0.0, "has length 0")])
def test_wind_up_refuses_directions_that_are_not_unit(scale, match):
    with pytest.raises(ValueError, match=r"target directions must be unit vectors \(length "
                                         r"within 1e-06 of 1\), but target directions\[0, 0\] "
                                         + match):
        wind_up(ON_EQUATOR, ENU, [False], scale * DIRECTION, directions=True)


def test_wind_up_normalizes_rounding_and_keeps_missing_data():
    exact = wind_up(ON_EQUATOR, ENU, [False, ], DIRECTION, directions=True)
    rounded = wind_up(ON_EQUATOR, ENU, [False], DIRECTION * (1 + 5e-7), directions=True)
    assert np.array_equal(exact, rounded)
    # A NaN direction or position is missing data: NaN, without a warning.
    missing = np.concatenate([DIRECTION, np.full((1, 1, 3), np.nan)], axis=1)
    phi = wind_up(ON_EQUATOR, ENU, [False], missing, directions=True)
    assert np.isfinite(phi[0, 0, 0]) and np.isnan(phi[0, 0, 1])
    # A transmitter at the antenna: no line of sight, NaN.
    assert np.isnan(wind_up(ON_EQUATOR, ENU, [False], [ON_EQUATOR])[0, 0, 0])


def test_receiver_arrays_pass_the_checks():
    # What receiver_arrays builds from Antenna objects is what wind_up accepts.
    arrays = receiver_arrays([DBR, FD, get_antenna("YEBES40M", focus=NasmythFocus("right"))])
    s = np.array([[[0.3, -0.8, 0.52]]]) / np.linalg.norm([0.3, -0.8, 0.52])
    assert wind_up(*arrays[:3], s, fixed_axis=arrays.fixed_axis,
                   focus_terms=arrays.focus_terms, directions=True).shape == (1, 3, 1)


# --- moving stars: proper motion is applied from the coordinate's epoch -------

#: Barnard's star, Gaia DR2 (Gaia Collaboration, Brown et al. 2018, A&A 616,
#: A1): position at the epoch J2015.5 (TCB), proper motion, parallax 547.45
#: mas (1.8266 pc), and the radial velocity.
BARNARD = SkyCoord(ra=269.452075 * u.deg, dec=4.693391 * u.deg,
                   pm_ra_cosdec=-801.551 * u.mas / u.yr, pm_dec=10362.394 * u.mas / u.yr,
                   distance=1.8266 * u.pc, radial_velocity=-110.6 * u.km / u.s,
                   obstime=Time("J2015.5", scale="tcb"))


def _astropy_parallactic_angle(coord, site, times):
    """ERFA's hd2pa of astropy's HADec of a coordinate moved to the epochs."""
    moved = coord.apply_space_motion(new_obstime=times)
    # Positions only: astropy cannot carry velocities of a star without distance.
    moved = SkyCoord(moved.frame.realize_frame(moved.data.without_differentials()))
    hadec = moved.transform_to(HADec(obstime=times, location=site))
    return erfa.hd2pa(hadec.ha.rad, hadec.dec.rad, site.lat.rad)


@pytest.mark.parametrize("n", [1, 3, 20])
def test_proper_motion_is_applied(n):
    site = SITES["YEBES"]
    antenna = Antenna(site, EquatorialMount())
    # Ten years after the catalogue epoch, over a night.
    times = Time("2025-07-02T20:00") + np.arange(n) * 20 * u.min
    psi = antenna.parallactic_angle(BARNARD, times)
    expected = _astropy_parallactic_angle(BARNARD, site, times)
    assert np.max(np.abs(psi.rad - expected)) < 1 * MAS
    # Without the motion (104 arcsec in ten years) the angle would differ by far more.
    static = SkyCoord(BARNARD.frame.realize_frame(BARNARD.data.without_differentials()))
    assert np.min(np.abs(antenna.parallactic_angle(static, times).rad - expected)) > 1000 * MAS
    grid = feed_rotation_grid([Antenna(site, AltAzMount())], BARNARD.reshape((1,)), times)
    np.testing.assert_allclose(np.radians(grid.deg[..., 0, 0]), np.atleast_1d(expected),
                               rtol=0, atol=MAS)


def test_proper_motion_needs_an_epoch():
    moving = SkyCoord(ra=269.45 * u.deg, dec=4.69 * u.deg, pm_ra_cosdec=-801.551 * u.mas / u.yr,
                      pm_dec=10362.394 * u.mas / u.yr)
    with pytest.raises(ValueError, match=r"target has a proper motion or radial velocity but "
                                         r"no epoch for its position; give the catalogue "
                                         r"epoch, e.g. SkyCoord\(..., obstime="):
        get_antenna("YEBES40M").feed_rotation(moving, DAY[:3])
    # No motion at all needs no epoch.
    still = SkyCoord(ra=269.45 * u.deg, dec=4.69 * u.deg, pm_ra_cosdec=0 * u.mas / u.yr,
                     pm_dec=0 * u.mas / u.yr)
    antenna = get_antenna("WETTZ13S")
    assert np.array_equal(antenna.feed_rotation(still, DAY[:3]),
                          antenna.feed_rotation(SkyCoord(ra=269.45 * u.deg, dec=4.69 * u.deg),
                                                DAY[:3]))


def test_proper_motion_without_distance():
    # ERFA takes a star without parallax as very distant (and says so; not us).
    site = SITES["WETTZ13S"]
    star = SkyCoord(ra=269.452075 * u.deg, dec=4.693391 * u.deg,
                    pm_ra_cosdec=-801.551 * u.mas / u.yr, pm_dec=10362.394 * u.mas / u.yr,
                    obstime=Time("J2015.5", scale="tcb"))
    times = Time("2025-07-02T20:00") + np.arange(3) * u.hour
    psi = Antenna(site, EquatorialMount()).parallactic_angle(star, times)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", erfa.ErfaWarning)
        expected = _astropy_parallactic_angle(star, site, times)
    assert np.max(np.abs(psi.rad - expected)) < 1 * MAS


# --- other hostile inputs at the edge ----------------------------------------


@pytest.mark.parametrize("obstime, match", [
    (DAY - DAY[0], r"got a TimeDelta \(a duration\); add it to a start epoch"),
    (np.arange(3.0), r"got ndarray of plain numbers; their format cannot be guessed: say it, "
                     r"e.g. Time\(values, format='mjd', scale='utc'\)"),
    (59969.5, "got float of plain numbers"),
    (3 * u.hour, r"got a Quantity in h; add durations to a start epoch"),
    (np.array([1.0, "x"], dtype=object), "got ndarray: Input values did not match"),
    ([["2023-01-25"], ["2023-01-25", "2023-01-26"]], "got list"),
])
def test_obstime_refused(obstime, match):
    with pytest.raises(TypeError, match="obstime must be an astropy Time.*" + match):
        get_antenna("WETTZ13S").feed_rotation(SOURCE, obstime)


def test_obstime_kinds_accepted():
    antenna = get_antenna("WETTZ13S")
    reference = antenna.feed_rotation(SOURCE, DAY[:2])
    as_objects = np.array([DAY[0], DAY[1]], dtype=object)
    as_datetime64 = DAY[:2].datetime64
    for obstime in (as_objects, as_datetime64, DAY[:2].isot.tolist()):
        np.testing.assert_allclose(antenna.feed_rotation(SOURCE, obstime).deg, reference.deg,
                                   rtol=0, atol=1e-9)


def test_empty_epochs_give_empty_results():
    antenna = get_antenna("WETTZ13S")
    none = DAY[:0]
    assert antenna.feed_rotation(SOURCE, none).shape == (0,)
    assert DBR.feed_rotation(gps_svn76(), none).shape == (0,)
    assert antenna.altaz(SOURCE, none)[1].shape == (0,)
    assert feed_rotation_grid([DBR, FD], [gps_svn76()], none).shape == (0, 2, 1)
    assert len(feed_rotation_table(antenna, SOURCE, none)) == 0
    assert rotation_delay(DBR, FD, gps_svn76(), none, L1).delay.shape == (0,)


def test_tables_take_one_target():
    sources = SkyCoord([1, 2] * u.deg, [3, 4] * u.deg)
    with pytest.raises(ValueError, match=r"a table follows one target, got a coordinate of "
                                         r"shape \(2,\); make one table per source"):
        feed_rotation_table(get_antenna("WETTZ13S"), sources, DAY[:3])
    with pytest.raises(ValueError, match="a table follows one target"):
        baseline_table(DBR, FD, sources, DAY[:3], L1)
    with pytest.raises(TypeError, match="target must be an astropy SkyCoord"):
        feed_rotation_table(FD, "3C 84", DAY[:3])
    one = feed_rotation_table(get_antenna("WETTZ13S"), SOURCE.reshape((1, 1)), DAY[:3])
    assert one["total"].shape == (3,)


def test_baseline_summary_needs_a_baseline_table():
    single = feed_rotation_table(get_antenna("WETTZ13S"), SOURCE, DAY[:3])
    with pytest.raises(ValueError, match="table is not from baseline_table: its meta has no "
                                         "'antennas' pair"):
        baseline_summary(single)
    with pytest.raises(TypeError, match="table must be an astropy Table from baseline_table, "
                                        "got dict"):
        baseline_summary({"antennas": ["A", "B"]})
    table = baseline_table(DBR, FD, gps_svn76(), GPS_PASS[:10], L1)
    del table["rotation_delay"]
    with pytest.raises(ValueError, match="table is not from baseline_table: it lacks "
                                         "rotation_delay"):
        baseline_summary(table)


def test_correction_reads_masked_angles_as_nan():
    angles = Masked([10.0, 20.0] * u.deg, mask=[False, True])
    corrected = correct_phase([100.0, 100.0] * u.deg, angles)
    assert corrected[0] == 90 * u.deg and np.isnan(corrected[1])


def test_correction_keeps_the_mask_of_visibilities():
    values = np.exp(1j * np.radians([[10.0, -10.0], [30.0, 50.0]]))
    mask = np.array([[False, True], [False, False]])
    numpy_masked = correct_visibilities(np.ma.masked_array(values, mask), 5 * u.deg,
                                        15 * u.deg, ("RR", "LL"))
    assert isinstance(numpy_masked, np.ma.MaskedArray)
    assert np.array_equal(numpy_masked.mask, mask)
    astropy_masked = correct_visibilities(Masked(values * u.Jy, mask=mask), 5 * u.deg,
                                          15 * u.deg, ("RR", "LL"))
    assert isinstance(astropy_masked, Masked) and astropy_masked.unit == u.Jy
    assert np.array_equal(astropy_masked.mask, mask)
    # Linear feeds mix the four products of a sample: one flag flags the sample.
    linear = np.ones((2, 4), complex)
    flags = np.array([[False, False, True, False], [False] * 4])
    out = correct_linear_visibilities(np.ma.masked_array(linear, flags), 30 * u.deg,
                                      30 * u.deg)
    assert out.mask.tolist() == [[True] * 4, [False] * 4]
