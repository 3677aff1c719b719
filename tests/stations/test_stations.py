# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The station catalogue."""

import io

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import EarthLocation
from astropy.table import Table
from astropy.tests.helper import assert_quantity_allclose

from astropy_feedrot import (
    AltAzMount,
    CassegrainFocus,
    GregorianFocus,
    MirrorTrain,
    NasmythFocus,
    PrimeFocus,
    StationaryMount,
)
from astropy_feedrot.stations.catalogue import (
    StationCatalogue,
    default_catalogue,
    focus_from_name,
    get_antenna,
    read_catalogue,
)

# The paper's Table 1 (DBR205, FD-VLBA) and Table 3 (GGAO12M, WETTZ13S), metres.
PAPER_TABLES = {
    "DBR205": (-1324070.478, -5332176.001, 3231921.799),
    "FD-VLBA": (-1324009.454, -5332181.955, 3231962.369),
    "GGAO12M": (1130730.179, -4831245.954, 3994228.241),
    "WETTZ13S": (4075659.180, 931824.551, 4801516.102),
}

# Geodetic latitude and longitude (deg) of the telescopes as published by
# their observatories (rounded to about 100 m), independent of the geodetic
# VLBI positions of the catalogue: Effelsberg 50 31 29 N, 6 52 58 E; Parkes
# 32 59 54 S, 148 15 49 E; Yebes 40 31 29 N, 3 05 13 W; Warkworth 36 26 S,
# 174 39.8 E.
OBSERVATORY_SITES = {
    "EFLSBERG": (50.5247, 6.8828),
    "PARKES": (-32.9983, 148.2636),
    "YEBES40M": (40.5247, -3.0869),
    "WARK12M": (-36.4335, 174.6630),
    "WARK30M": (-36.4332, 174.6633),
}


@pytest.mark.parametrize("name", sorted(PAPER_TABLES))
def test_paper_positions(name):
    location = get_antenna(name).location
    assert_quantity_allclose(u.Quantity([location.x, location.y, location.z]),
                             PAPER_TABLES[name] * u.m, atol=1 * u.mm)


@pytest.mark.parametrize("name", sorted(OBSERVATORY_SITES))
def test_geodetic_positions_are_the_named_telescopes(name):
    lat, lon = OBSERVATORY_SITES[name]
    geodetic = get_antenna(name).location.to_geodetic()
    # 0.003 deg is about 300 m: the right dish, not a neighbouring one.
    assert abs(geodetic.lat.deg - lat) < 3e-3
    assert abs(geodetic.lon.deg - lon) < 3e-3


@pytest.mark.parametrize("name, mount, focus", [
    ("DBR205", StationaryMount(), CassegrainFocus()),
    ("FD-VLBA", AltAzMount(), CassegrainFocus()),
    ("GGAO12M", AltAzMount(), CassegrainFocus()),
    ("WETTZ13S", AltAzMount(), CassegrainFocus()),
    ("YEBES40M", AltAzMount(), MirrorTrain.yebes40m("X")),
    ("WARK30M", AltAzMount(), MirrorTrain.wark30m()),
    ("WARK12M", AltAzMount(), CassegrainFocus()),
    ("EFLSBERG", AltAzMount(), GregorianFocus()),
    ("PARKES", AltAzMount(), PrimeFocus()),
])
def test_mounts_and_foci_of_the_paper(name, mount, focus):
    # Appendix C and Sec. 4 of the paper.
    antenna = get_antenna(name)
    assert antenna.mount == mount
    assert antenna.focus == focus
    assert antenna.name == name


@pytest.mark.parametrize("alias", ["Effelsberg", "eflsberg", "EF", " ef ", "Ef"])
def test_aliases_and_case(alias):
    assert get_antenna(alias).name == "EFLSBERG"


def test_punctuation_does_not_matter():
    assert get_antenna("fd vlba").name == "FD-VLBA"
    assert "wettz 13s" in default_catalogue()


def test_velocity_moves_the_position():
    # SCHED locations.dat: WARK12M z = -3767192.6092 m at MJD 58849 with
    # dz/dt = 0.03338 m/yr; 2030-01-01 is 3653 days (10.0014 Julian years) later.
    catalogue = default_catalogue()
    years = (3653 * u.day).to_value(u.yr)
    assert_quantity_allclose(catalogue.location("WARK12M", epoch="2030-01-01T00:00:00").z,
                             (-3767192.6092 + 0.03338 * years) * u.m, atol=1 * u.mm)
    # Without an epoch the catalogue position; the paper's stations have none.
    assert_quantity_allclose(catalogue.location("WARK12M").z, -3767192.6092 * u.m)
    assert_quantity_allclose(catalogue.location("DBR205", epoch="2030-01-01").x,
                             -1324070.478 * u.m)
    with pytest.raises(ValueError, match="epoch must be a single time"):
        catalogue.location("WARK12M", epoch=["2030-01-01", "2031-01-01"])


def test_focus_override():
    antenna = get_antenna("YEBES40M", focus=NasmythFocus("right"))
    assert antenna.focus == NasmythFocus("right")


def test_catalogue_api():
    catalogue = default_catalogue()
    assert len(catalogue) >= 90
    assert catalogue.names[:2] == ["DBR205", "FD-VLBA"]
    assert f"{len(catalogue)} antennas" in repr(catalogue)
    table = catalogue.table
    table["x"][0] = 0.0
    assert catalogue.table["x"][0] != 0.0  # a copy


@pytest.mark.parametrize("name, suggestion", [
    ("YEBES40", "YEBES40M"),
    ("EFFELSBURG", "EFLSBERG"),
    ("WARK31M", "WARK30M"),
])
def test_unknown_names_give_the_nearest_five(name, suggestion):
    with pytest.raises(ValueError, match=rf"unknown antenna {name!r}.*nearest names: ") as error:
        get_antenna(name)
    message = str(error.value)
    assert "\n" not in message
    nearest = message.split("the nearest names: ")[1].split(", ")
    assert len(nearest) == 5 and suggestion in nearest


def test_unknown_name_without_close_match_names_five_not_all():
    with pytest.raises(ValueError, match=r"unknown antenna 'ZZZZ'.*nearest names: ") as error:
        get_antenna("ZZZZ")
    assert len(str(error.value).split("the nearest names: ")[1].split(", ")) == 5


def test_name_must_be_a_string():
    with pytest.raises(TypeError, match="an antenna name must be a str, got int"):
        get_antenna(42)


def _ecsv(rows, header=None):
    header = header or ("# - {name: name, datatype: string}\n"
                        "# - {name: x, unit: m, datatype: float64}\n"
                        "# - {name: y, unit: m, datatype: float64}\n"
                        "# - {name: z, unit: m, datatype: float64}\n"
                        "# - {name: mount, datatype: string}\n")
    names = " ".join(line.split("name: ")[1].split(",")[0] for line in header.splitlines())
    return io.StringIO("# %ECSV 1.0\n# ---\n# datatype:\n" + header + names + "\n"
                       + "\n".join(rows) + "\n")


def test_users_catalogue(tmp_path):
    text = _ecsv(["MYDISH 4075539.5173 931735.6497 4801629.6028 AZEL",
                  "MYGNSS 4075540.0 931736.0 4801629.0 GNSS"])
    path = tmp_path / "mine.ecsv"
    path.write_text(text.getvalue())
    antenna = get_antenna("mydish", catalogue=path)
    assert antenna.mount == AltAzMount()
    assert get_antenna("MYGNSS", catalogue=read_catalogue(path)).mount == StationaryMount()
    location = EarthLocation.from_geocentric(4075539.5173, 931735.6497, 4801629.6028, u.m)
    assert_quantity_allclose(antenna.location.x, location.x)


def test_users_catalogue_in_km_is_caught():
    header = ("# - {name: name, datatype: string}\n"
              "# - {name: x, unit: km, datatype: float64}\n"
              "# - {name: y, unit: km, datatype: float64}\n"
              "# - {name: z, unit: km, datatype: float64}\n"
              "# - {name: mount, datatype: string}\n")
    # Units given as km are converted: this is fine.
    catalogue = read_catalogue(_ecsv(["A 4075.5395 931.7356 4801.6296 AZEL"], header))
    assert_quantity_allclose(catalogue.location("A").x, 4075539.5 * u.m)
    # Kilometres labelled as metres are not on the Earth's surface.
    with pytest.raises(ValueError, match=r"station A: position is 6367 m from the geocentre"):
        read_catalogue(_ecsv(["A 4075.5395 931.7356 4801.6296 AZEL"]))


@pytest.mark.parametrize("rows, header, error, match", [
    (["A 4075539.5 931735.6 4801629.6"],
     "# - {name: name, datatype: string}\n# - {name: x, unit: m, datatype: float64}\n"
     "# - {name: y, unit: m, datatype: float64}\n# - {name: z, unit: m, datatype: float64}\n",
     ValueError, r"missing column\(s\) mount; a catalogue needs name, x, y, z, mount"),
    (["A 4075539.5 931735.6 4801629.6 AZEL"],
     "# - {name: name, datatype: string}\n# - {name: x, datatype: float64}\n"
     "# - {name: y, unit: m, datatype: float64}\n# - {name: z, unit: m, datatype: float64}\n"
     "# - {name: mount, datatype: string}\n",
     u.UnitsError, r"column 'x' has no unit"),
    (["A 4075539.5 931735.6 4801629.6 AZEL"],
     "# - {name: name, datatype: string}\n# - {name: x, unit: s, datatype: float64}\n"
     "# - {name: y, unit: m, datatype: float64}\n# - {name: z, unit: m, datatype: float64}\n"
     "# - {name: mount, datatype: string}\n",
     u.UnitsError, r"column 'x' is in s, which is not convertible to m"),
    (["A 4075539.5 931735.6 4801629.6 ALTAZ"], None, ValueError, r"station A: .*ALTAZ"),
    (["A 4075539.5 931735.6 4801629.6 AZEL", "B 4075539.5 931735.6 4801629.6 AZEL",
      "a 4075539.5 931735.6 4801629.6 AZEL"], None, ValueError,
     r"station a: the name 'a' is also used by station A"),
])
def test_bad_user_catalogues(rows, header, error, match):
    with pytest.raises(error, match=match):
        read_catalogue(_ecsv(rows, header))


def test_bad_focus_and_velocity_without_epoch():
    table = Table({"name": ["A"], "x": [4075539.5] * u.m, "y": [931735.6] * u.m,
                   "z": [4801629.6] * u.m, "mount": ["AZEL"], "focus": ["coude"]})
    with pytest.raises(ValueError, match=r"station A: unknown focus 'coude'; expected one of "
                       r"prime, cassegrain"):
        StationCatalogue(table)
    table["focus"] = ["nasmyth-left"]
    assert StationCatalogue(table).get_antenna("A").focus == NasmythFocus("left")
    for c in ("vx", "vy", "vz"):
        table[c] = [0.01] * u.m / u.yr
    with pytest.raises(ValueError, match="a velocity needs the epoch"):
        StationCatalogue(table)
    table["epoch"] = [58849.0]
    assert np.isfinite(StationCatalogue(table).location("A", epoch="2025-01-01").x)


def test_unreadable_catalogue_files(tmp_path):
    with pytest.raises(FileNotFoundError):
        read_catalogue(tmp_path / "missing.ecsv")
    bad = tmp_path / "bad.ecsv"
    bad.write_text("this is not ECSV\n")
    with pytest.raises(ValueError, match=r"bad.ecsv: not a readable ECSV table"):
        read_catalogue(bad)


def test_focus_from_name():
    assert focus_from_name("") is None
    assert focus_from_name("BWG-LEFT").handedness == "left"
    with pytest.raises(ValueError, match=r"--focus: unknown focus 'x'"):
        focus_from_name("x", "--focus")


def test_askap_keeps_its_feed_on_the_sky():
    # ASKAP's roll axis turns the feed against the parallactic angle (Hotan et al.
    # 2021): with the catalogue's sky-tracking rotator the feed rotation of a
    # natural source stays at the rotator's angle, 0, all day.
    from astropy.coordinates import SkyCoord
    from astropy.time import Time

    askap = get_antenna("ASKAP")
    assert askap.rotator is not None and askap.rotator.mode == "sky"
    times = Time("2024-06-01T00:00") + np.arange(0, 24, 0.5) * u.hour
    phi = askap.feed_rotation(SkyCoord("13h25m27.6s -43d01m09s"), times)
    assert np.all(np.abs(phi.to_value(u.deg)) < 1e-9)


def test_a_catalogue_rotator_must_be_a_mode(tmp_path):
    table = default_catalogue().table[:2].copy()
    table["rotator"] = ["spin", ""]
    with pytest.raises(ValueError, match="rotator of .* must be 'sky', 'fixed' or empty"):
        StationCatalogue(table).get_antenna(table["name"][0])
