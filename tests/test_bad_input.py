# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Bad input gets a clear error; degenerate geometry gets NaN and one warning."""

import warnings

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import ICRS, ITRS, SkyCoord
from helpers import DAY, SITES, itrs_direction

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
    StationaryMount,
    XYMount,
)
from astropy_feedrot.frames import local_frame, location_xyz, source_direction

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
    from astropy_feedrot.eop import iers_context

    with iers.conf.set_temp("auto_download", True):
        with iers_context():
            assert iers.conf.auto_download is False
        with conf.set_temp("iers_auto_download", True), iers_context():
            assert iers.conf.auto_download is True
        assert iers.conf.auto_download is True
