# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Mount labels of other software, both directions.

References: the expected mount and focus of every label are written out here
from the source code of each program (the files named in the docstring of
``astropy_feedrot.stations.labels``): casacore ``FitsIDItoMS.cc``,
``MSFitsInput.cc``/``MSFitsOutput.cc`` and ``MSDerivedValues.cc``; DiFX
``difx_input.h``, ``difx_antenna.c`` and ``fitsAG.c``; the VEX readers of
vex2difx and HOPS; pyuvdata ``utils/antenna.py`` and ``telescopes.py``; VTD
``vtd_load_stadesc.f`` and ``vtd_axof.f``. The physics tests compare feed
rotations with casacore's ``MSDerivedValues::parAngle`` formulas, with azimuth
and elevation from astropy's `AltAz` and hour angle and declination from its
`HADec` (independent of this package's vectors).
"""

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import AltAz, HADec, SkyCoord
from astropy.time import Time
from helpers import MAS, SITES, angle_spread, max_angle_difference, sky_grid

from astropy_feedrot import (
    AltAzMount,
    Antenna,
    BeamWaveguideFocus,
    CassegrainFocus,
    EquatorialMount,
    FixedAxisMount,
    Focus,
    GregorianFocus,
    MirrorTrain,
    Mount,
    NasmythFocus,
    PrimeFocus,
    StationaryMount,
    XYMount,
)
from astropy_feedrot.stations.labels import (
    KNOWN_LABELS,
    SOFTWARE,
    known_labels,
    label_from_mount,
    mount_from_label,
)

ALTAZ = AltAzMount()
EQUA = EquatorialMount()
XYN = XYMount("north")
XYE = XYMount("east")
NAS_R = NasmythFocus("right")
NAS_L = NasmythFocus("left")
BWG_R = BeamWaveguideFocus("right")
BWG_L = BeamWaveguideFocus("left")
FIXED = StationaryMount()

# VTD's 'RICH' fixed axis (vtd_axof.f): up = sin(39d03m36s),
# east = cos(39d03m36s) sin(-0d07m12s), north = cos(39d03m36s) cos(-0d07m12s).
RICH_LAT = np.radians(39 + 3 / 60 + 36 / 3600)
RICH_LNG = np.radians(-(7 / 60 + 12 / 3600))
RICH_ENU = [np.cos(RICH_LAT) * np.sin(RICH_LNG), np.cos(RICH_LAT) * np.cos(RICH_LNG),
            np.sin(RICH_LAT)]

# (software, label, mount, focus): every label with a model, as each program
# reads it.
READ = [
    # casacore FitsIDItoMS.cc: MNTSTA -> MOUNT.
    ("fits-idi:casacore", 0, ALTAZ, None),
    ("fits-idi:casacore", 1, EQUA, None),
    ("fits-idi:casacore", 3, XYE, None),
    ("fits-idi:casacore", 4, ALTAZ, NAS_R),
    ("fits-idi:casacore", 5, ALTAZ, NAS_L),
    ("fits-idi:casacore", 6, ALTAZ, BWG_R),
    ("fits-idi:casacore", 7, ALTAZ, BWG_L),
    # casacore 3.2-3.6 (MSFitsOutput.cc after 21dd9c182, before d08694031).
    ("fits-idi:casacore<3.7", 0, ALTAZ, None),
    ("fits-idi:casacore<3.7", 1, EQUA, None),
    ("fits-idi:casacore<3.7", 3, XYE, None),
    ("fits-idi:casacore<3.7", 4, ALTAZ, NAS_R),
    ("fits-idi:casacore<3.7", 5, ALTAZ, NAS_L),
    # casacore 2.0-3.1 (MSFitsOutput.cc after a490fd0a6, before 21dd9c182).
    ("fits-idi:casacore<3.2", 0, ALTAZ, None),
    ("fits-idi:casacore<3.2", 1, EQUA, None),
    ("fits-idi:casacore<3.2", 3, XYE, None),
    # DiFX enum AntennaMountType, written as MNTSTA by difx2fits.
    ("fits-idi:difx", 0, ALTAZ, None),
    ("fits-idi:difx", 1, EQUA, None),
    ("fits-idi:difx", 3, XYE, None),
    ("fits-idi:difx", 4, ALTAZ, NAS_R),
    ("fits-idi:difx", 5, ALTAZ, NAS_L),
    ("fits-idi:difx", 6, XYN, None),
    # pyuvdata MOUNT_NUM2STR_DICT.
    ("fits-idi:pyuvdata", 0, ALTAZ, None),
    ("fits-idi:pyuvdata", 1, EQUA, None),
    ("fits-idi:pyuvdata", 3, XYE, None),
    ("fits-idi:pyuvdata", 4, ALTAZ, NAS_R),
    ("fits-idi:pyuvdata", 5, ALTAZ, NAS_L),
    ("fits-idi:pyuvdata", 7, FIXED, None),
    # casacore MSDerivedValues::setAntennaMount.
    ("casacore", "ALT-AZ", ALTAZ, None),
    ("casacore", "", ALTAZ, None),
    ("casacore", "ALT-AZ+ROTATOR", ALTAZ, None),
    ("casacore", "EQUATORIAL", EQUA, None),
    ("casacore", "X-Y", XYE, None),
    ("casacore", "ALT-AZ+NASMYTH-R", ALTAZ, NAS_R),
    ("casacore", "ALT-AZ+NASMYTH-L", ALTAZ, NAS_L),
    ("casacore", "ALT-AZ+BWG-R", ALTAZ, BWG_R),
    ("casacore", "ALT-AZ+BWG-L", ALTAZ, BWG_L),
    # DiFX stringToMountType.
    ("difx", "AZEL", ALTAZ, None),
    ("difx", "ALTAZ", ALTAZ, None),
    ("difx", "ALTZ", ALTAZ, None),
    ("difx", "EQUA", EQUA, None),
    ("difx", "EQUAT", EQUA, None),
    ("difx", "EQUATORIAL", EQUA, None),
    ("difx", "HADEC", EQUA, None),
    ("difx", "XYEW", XYE, None),
    ("difx", "NASR", ALTAZ, NAS_R),
    ("difx", "NASMYTH-R", ALTAZ, NAS_R),
    ("difx", "NASMYTHR", ALTAZ, NAS_R),
    ("difx", "NASL", ALTAZ, NAS_L),
    ("difx", "NASMYTH-L", ALTAZ, NAS_L),
    ("difx", "NASMYTHL", ALTAZ, NAS_L),
    ("difx", "XYNS", XYN, None),
    # VEX axis_type (HOPS do_antenna.c, vex2difx vexload.cpp).
    ("vex", "az:el", ALTAZ, None),
    ("vex", "ha:dec", EQUA, None),
    ("vex", "x:yew", XYE, None),
    ("vex", "x:yns", XYN, None),
    # pyuvdata Telescope.mount_type acceptable values.
    ("pyuvdata", "alt-az", ALTAZ, None),
    ("pyuvdata", "equatorial", EQUA, None),
    ("pyuvdata", "x-y", XYE, None),
    ("pyuvdata", "alt-az+nasmyth-r", ALTAZ, NAS_R),
    ("pyuvdata", "alt-az+nasmyth-l", ALTAZ, NAS_L),
    ("pyuvdata", "fixed", FIXED, None),
    # VTD vtd_load_stadesc.f / vtd_axof.f / vtd_delay.f.
    ("geodetic", "AZEL", ALTAZ, None),
    ("geodetic", "EQUA", EQUA, None),
    ("geodetic", "X-YN", XYN, None),
    ("geodetic", "X-YE", XYE, None),
    ("geodetic", "NASR", ALTAZ, NAS_R),
    ("geodetic", "NASP", ALTAZ, NAS_R),
    ("geodetic", "NASL", ALTAZ, NAS_L),
    ("geodetic", "NASM", ALTAZ, NAS_L),
    ("geodetic", "BWG", ALTAZ, BWG_R),
    ("geodetic", "GNSS", FIXED, None),
]

# (software, label, reason): known labels with no feed-rotation model.
NO_MODEL = [
    ("fits-idi:casacore", 2, "attitude model"),
    ("fits-idi:casacore", 8, "unknown or unusual"),
    ("fits-idi:casacore", 9, "SPACE-HALCA"),
    ("fits-idi:casacore<3.7", 2, "attitude model"),
    ("fits-idi:casacore<3.7", 6, "'BIZARRE' mount, not for a beam waveguide"),
    ("fits-idi:casacore<3.7", 7, "SPACE-HALCA.*beam waveguides included"),
    ("fits-idi:casacore<3.2", 2, "attitude model"),
    ("fits-idi:casacore<3.2", 4, "'BIZARRE' mount"),
    ("fits-idi:casacore<3.2", 5, "'BIZARRE' mount"),
    ("fits-idi:casacore<3.2", 6, "'BIZARRE' mount"),
    ("fits-idi:casacore<3.2", 7, "SPACE-HALCA"),
    ("fits-idi:difx", 2, "attitude model"),
    ("fits-idi:difx", 7, "unknown or unusual"),
    ("fits-idi:pyuvdata", 2, "attitude model"),
    ("fits-idi:pyuvdata", 6, "phased array.*that of its elements"),
    ("fits-idi:pyuvdata", 8, "unknown or unusual"),
    ("casacore", "ORBITING", "attitude model"),
    ("casacore", "SPACE-HALCA", "attitude model"),
    ("casacore", "SPACE_HALCA", "attitude model"),
    ("casacore", "BIZARRE", "unknown or unusual"),
    ("casacore", "UNKNOWN", "unknown or unusual"),
    ("difx", "SPACE", "attitude model"),
    ("difx", "SPAC", "attitude model"),
    ("difx", "ORBIT", "attitude model"),
    ("difx", "ORBI", "attitude model"),
    ("difx", "ORBITING", "attitude model"),
    ("difx", "OTHER", "unknown or unusual"),
    ("pyuvdata", "orbiting", "attitude model"),
    ("pyuvdata", "phased", "phased array"),
    ("pyuvdata", "other", "unknown or unusual"),
    ("pyuvdata", "bizarre", "unknown or unusual"),
]

# (software, mount, focus, label): what each program writes.
WRITE = [
    ("fits-idi:casacore", ALTAZ, None, 0),
    ("fits-idi:casacore", EQUA, None, 1),
    ("fits-idi:casacore", XYE, None, 3),
    ("fits-idi:casacore", ALTAZ, NAS_R, 4),
    ("fits-idi:casacore", ALTAZ, NAS_L, 5),
    ("fits-idi:casacore", ALTAZ, BWG_R, 6),
    ("fits-idi:casacore", ALTAZ, BWG_L, 7),
    ("fits-idi:difx", ALTAZ, None, 0),
    ("fits-idi:difx", EQUA, None, 1),
    ("fits-idi:difx", XYE, None, 3),
    ("fits-idi:difx", ALTAZ, NAS_R, 4),
    ("fits-idi:difx", ALTAZ, NAS_L, 5),
    ("fits-idi:difx", XYN, None, 6),
    ("fits-idi:pyuvdata", ALTAZ, None, 0),
    ("fits-idi:pyuvdata", EQUA, None, 1),
    ("fits-idi:pyuvdata", XYE, None, 3),
    ("fits-idi:pyuvdata", ALTAZ, NAS_R, 4),
    ("fits-idi:pyuvdata", ALTAZ, NAS_L, 5),
    ("fits-idi:pyuvdata", FIXED, None, 7),
    ("casacore", ALTAZ, None, "ALT-AZ"),
    ("casacore", EQUA, None, "EQUATORIAL"),
    ("casacore", XYE, None, "X-Y"),
    ("casacore", ALTAZ, NAS_R, "ALT-AZ+NASMYTH-R"),
    ("casacore", ALTAZ, NAS_L, "ALT-AZ+NASMYTH-L"),
    ("casacore", ALTAZ, BWG_R, "ALT-AZ+BWG-R"),
    ("casacore", ALTAZ, BWG_L, "ALT-AZ+BWG-L"),
    ("difx", ALTAZ, None, "AZEL"),
    ("difx", EQUA, None, "EQUA"),
    ("difx", XYE, None, "XYEW"),
    ("difx", ALTAZ, NAS_R, "NASR"),
    ("difx", ALTAZ, NAS_L, "NASL"),
    ("difx", XYN, None, "XYNS"),
    ("vex", ALTAZ, None, ("az:el", None)),
    ("vex", EQUA, None, ("ha:dec", None)),
    ("vex", XYE, None, ("x:yew", None)),
    ("vex", XYN, None, ("x:yns", None)),
    ("vex", ALTAZ, NAS_R, ("az:el", "right")),
    ("vex", ALTAZ, NAS_L, ("az:el", "left")),
    ("pyuvdata", ALTAZ, None, "alt-az"),
    ("pyuvdata", EQUA, None, "equatorial"),
    ("pyuvdata", XYE, None, "x-y"),
    ("pyuvdata", ALTAZ, NAS_R, "alt-az+nasmyth-r"),
    ("pyuvdata", ALTAZ, NAS_L, "alt-az+nasmyth-l"),
    ("pyuvdata", FIXED, None, "fixed"),
    ("geodetic", ALTAZ, None, "AZEL"),
    ("geodetic", EQUA, None, "EQUA"),
    ("geodetic", XYN, None, "X-YN"),
    ("geodetic", XYE, None, "X-YE"),
    ("geodetic", ALTAZ, NAS_R, "NASR"),
    ("geodetic", ALTAZ, NAS_L, "NASL"),
    ("geodetic", ALTAZ, BWG_R, "BWG"),
    ("geodetic", FIXED, None, "GNSS"),
]

# (software, mount, focus, what the message must say): what a convention
# cannot express.
CANNOT_WRITE = [
    ("fits-idi:casacore", XYN, None, r"east-west form.*fits-idi:difx \(6\)"),
    ("fits-idi:casacore", FIXED, None, r"fits-idi:pyuvdata \(7\)"),
    ("fits-idi:casacore<3.7", XYN, None, r"east-west form.*fits-idi:difx \(6\)"),
    ("fits-idi:casacore<3.7", FIXED, None, r"fits-idi:pyuvdata \(7\)"),
    ("fits-idi:casacore<3.7", ALTAZ, BWG_R, r"before 3.7 wrote it as 0.*fits-idi:casacore \(6\)"),
    ("fits-idi:casacore<3.7", ALTAZ, BWG_L, r"before 3.7 wrote it as 0.*fits-idi:casacore \(7\)"),
    ("fits-idi:casacore<3.2", XYN, None, r"east-west form.*fits-idi:difx \(6\)"),
    ("fits-idi:casacore<3.2", FIXED, None, r"fits-idi:pyuvdata \(7\)"),
    ("fits-idi:casacore<3.2", ALTAZ, NAS_R, r"before 3.2 wrote it as 0.*fits-idi:casacore \(4\)"),
    ("fits-idi:casacore<3.2", ALTAZ, NAS_L, r"before 3.2 wrote it as 0.*fits-idi:casacore \(5\)"),
    ("fits-idi:casacore<3.2", ALTAZ, BWG_R, r"before 3.7 wrote it as 0"),
    ("fits-idi:casacore<3.2", ALTAZ, BWG_L, r"before 3.7 wrote it as 0"),
    ("fits-idi:difx", ALTAZ, BWG_R, r"fits-idi:casacore \(6\)"),
    ("fits-idi:difx", ALTAZ, BWG_L, r"fits-idi:casacore \(7\)"),
    ("fits-idi:difx", FIXED, None, r"pyuvdata \('fixed'\)"),
    ("fits-idi:pyuvdata", XYN, None, r"east-west form.*fits-idi:difx \(6\)"),
    ("fits-idi:pyuvdata", ALTAZ, BWG_R, r"casacore \('ALT-AZ\+BWG-R'\)"),
    ("fits-idi:pyuvdata", ALTAZ, BWG_L, r"casacore \('ALT-AZ\+BWG-L'\)"),
    ("casacore", XYN, None, r"'X-Y' is the east-west form.*difx \('XYNS'\)"),
    ("casacore", FIXED, None, r"geodetic \('GNSS'\)"),
    ("difx", ALTAZ, BWG_R, r"geodetic \('BWG'\)"),
    ("difx", ALTAZ, BWG_L, r"casacore \('ALT-AZ\+BWG-L'\)"),
    ("difx", FIXED, None, r"fits-idi:pyuvdata \(7\)"),
    ("vex", ALTAZ, BWG_R, r"casacore \('ALT-AZ\+BWG-R'\)"),
    ("vex", ALTAZ, BWG_L, r"fits-idi:casacore \(7\)"),
    ("vex", FIXED, None, r"geodetic \('GNSS'\)"),
    ("pyuvdata", XYN, None, r"'x-y' is the east-west form.*vex \(axis_type 'x:yns'\)"),
    ("pyuvdata", ALTAZ, BWG_R, r"fits-idi:casacore \(6\)"),
    ("pyuvdata", ALTAZ, BWG_L, r"fits-idi:casacore \(7\)"),
    ("geodetic", ALTAZ, BWG_L, r"'BWG' is the right-handed form.*'ALT-AZ\+BWG-L'"),
]


def _id(case):
    return f"{case[0]}-{case[1]!r}"


@pytest.mark.parametrize(("software", "label", "mount", "focus"), READ, ids=map(_id, READ))
def test_read(software, label, mount, focus):
    assert mount_from_label(label, software) == (mount, focus)


@pytest.mark.parametrize(("software", "label", "reason"), NO_MODEL, ids=map(_id, NO_MODEL))
def test_labels_without_a_model(software, label, reason):
    with pytest.raises(ValueError, match=f"no feed-rotation model here: .*{reason}"):
        mount_from_label(label, software)


@pytest.mark.parametrize(("software", "mount", "focus", "label"), WRITE,
                         ids=[f"{c[0]}-{c[3]!r}" for c in WRITE])
def test_write(software, mount, focus, label):
    written = label_from_mount(mount, focus, software=software)
    assert written == label
    assert type(written) is type(label)


@pytest.mark.parametrize(("software", "mount", "focus", "match"), CANNOT_WRITE,
                         ids=[f"{c[0]}-{c[1]!r}-{c[2]!r}" for c in CANNOT_WRITE])
def test_write_what_cannot_be_expressed(software, mount, focus, match):
    with pytest.raises(ValueError, match=f"{software} has no mount label for .*{match}"):
        label_from_mount(mount, focus, software=software)


def test_geodetic_rich_is_the_vtd_axis():
    mount, focus = mount_from_label("RICH", "geodetic")
    assert focus is None
    assert isinstance(mount, FixedAxisMount) and mount.frame == "enu"
    np.testing.assert_allclose(mount.axis, RICH_ENU, rtol=0, atol=1e-15)
    # Written back from a mount built independently.
    assert label_from_mount(FixedAxisMount(RICH_ENU, frame="enu"), software="geodetic") == "RICH"
    with pytest.raises(ValueError, match=r"difx has no mount label for the fixed axis of the "
                                         r"Richmond antenna.*geodetic \('RICH'\)"):
        label_from_mount(mount, software="difx")


def test_every_table_is_covered_here():
    # The literal tables above list every known label of every convention.
    listed = {(s, lab) for s, lab, *_ in READ + NO_MODEL} | {("geodetic", "RICH")}
    assert listed == {(s, lab) for s in SOFTWARE for lab in known_labels(s)}
    assert set(KNOWN_LABELS) == set(SOFTWARE)


@pytest.mark.parametrize("focus", [None, PrimeFocus(), CassegrainFocus(), GregorianFocus()])
@pytest.mark.parametrize(("mount", "expected"), [
    (ALTAZ, {"casacore": "ALT-AZ", "difx": "AZEL", "vex": ("az:el", None), "geodetic": "AZEL",
             "pyuvdata": "alt-az", "fits-idi:difx": 0}),
    (EQUA, {"casacore": "EQUATORIAL", "vex": ("ha:dec", None), "fits-idi:casacore": 1}),
    (XYN, {"difx": "XYNS", "geodetic": "X-YN", "fits-idi:difx": 6}),
])
def test_conventional_foci_write_the_plain_label(mount, expected, focus):
    for software, label in expected.items():
        assert label_from_mount(mount, focus, software) == label


@pytest.mark.parametrize(("mount", "label"), [
    (FixedAxisMount([0, 0, 3.0], frame="enu"), "AZEL"),
    (FixedAxisMount([0, 0, 1.0], frame="itrs"), "EQUA"),
    (FixedAxisMount([0, 2.0, 0], frame="enu"), "X-YN"),
    (FixedAxisMount([1.0, 0, 0], frame="enu"), "X-YE"),
])
def test_fixed_axis_mounts_of_named_axes(mount, label):
    # The same physics as the named mounts (test_natural.py), so the same label.
    assert label_from_mount(mount, None, "geodetic") == label


# ---------------------------------------------------------------- round trips


def _modelled(software):
    for label in known_labels(software):
        try:
            yield label, mount_from_label(label, software)
        except ValueError:
            pass


@pytest.mark.parametrize("software", SOFTWARE)
def test_round_trip_from_labels(software):
    for label, (mount, focus) in _modelled(software):
        written = label_from_mount(mount, focus, software=software)
        if software == "vex":
            axis_type, nasmyth = written
            again = mount_from_label(axis_type, software, nasmyth=nasmyth)
        else:
            again = mount_from_label(written, software)
        assert again == (mount, focus), label


@pytest.mark.parametrize("software", SOFTWARE)
def test_round_trip_from_mounts(software):
    # Every mount and focus with a label comes back; the others are exactly
    # those of CANNOT_WRITE.
    cannot = set()
    for mount, focus in [(ALTAZ, None), (EQUA, None), (XYN, None), (XYE, None),
                         (ALTAZ, NAS_R), (ALTAZ, NAS_L), (ALTAZ, BWG_R), (ALTAZ, BWG_L),
                         (FIXED, None)]:
        try:
            label = label_from_mount(mount, focus, software=software)
        except ValueError:
            cannot.add((mount, focus))
            continue
        if software == "vex":
            assert mount_from_label(label[0], software, nasmyth=label[1]) == (mount, focus)
        else:
            assert mount_from_label(label, software) == (mount, focus)
    assert cannot == {(m, f) for s, m, f, _ in CANNOT_WRITE if s == software}


def test_vex_nasmyth_round_trip_with_vex2difx_mount():
    # vex2difx turns az:el + nasmyth into NASR/NASL; both routes agree.
    for nasmyth, difx in [("right", "NASR"), ("left", "NASL")]:
        assert (mount_from_label("az:el", "vex", nasmyth=nasmyth)
                == mount_from_label(difx, "difx"))


# ------------------------------------------------------------------ leniency


@pytest.mark.parametrize(("label", "software", "mount", "focus"), [
    ("alt-az+nasmyth-r", "casacore", ALTAZ, NAS_R),
    ("Alt-Az+BWG-l", "casacore", ALTAZ, BWG_L),
    ("  x-y ", "casacore", XYE, None),
    ("   ", "casacore", ALTAZ, None),
    (b"ALT-AZ+BWG-R", "casacore", ALTAZ, BWG_R),
    (np.str_("EQUATORIAL"), "casacore", EQUA, None),
    (np.array("X-Y"), "casacore", XYE, None),
    (" nasr ", "difx", ALTAZ, NAS_R),
    ("xyns", "difx", XYN, None),
    ("ALT-AZ+NASMYTH-L", "pyuvdata", ALTAZ, NAS_L),
    ("Fixed", "pyuvdata", FIXED, None),
    ("BWG ", "geodetic", ALTAZ, BWG_R),
    ("gnss", "geodetic", FIXED, None),
    ("AZ:EL", "vex", ALTAZ, None),
    (" x : yns ", "vex", XYN, None),
    ("Ha :Dec", "vex", EQUA, None),
])
def test_strings_are_matched_leniently(label, software, mount, focus):
    assert mount_from_label(label, software) == (mount, focus)


@pytest.mark.parametrize("code", [
    4, np.int16(4), np.int32(4), np.int64(4), np.uint8(4), "4", " 4 ", b"4", 4.0,
    np.float32(4.0), "4.0", np.array(4),
])
@pytest.mark.parametrize("software", ["fits-idi:casacore", "fits-idi:difx", "fits-idi:pyuvdata"])
def test_codes_of_every_integer_kind(code, software):
    assert mount_from_label(code, software) == (ALTAZ, NAS_R)


@pytest.mark.parametrize(("label", "software"), [
    ("ALT-AZ+NASMYTH-R", " CASACORE"), ("NASR", "DiFX"), (4, "Fits-IDI:DiFX "),
])
def test_software_names_are_matched_leniently(label, software):
    assert mount_from_label(label, software) == (ALTAZ, NAS_R)
    assert label_from_mount(ALTAZ, NAS_R, software) == label


@pytest.mark.parametrize(("nasmyth", "focus"), [
    (None, None), ("none", None), ("NONE", None), ("right", NAS_R), (" Right ", NAS_R),
    ("left", NAS_L), (b"left", NAS_L),
])
def test_vex_nasmyth(nasmyth, focus):
    assert mount_from_label("az:el", "vex", nasmyth=nasmyth) == (ALTAZ, focus)


@pytest.mark.parametrize("axis_type", ["ha:dec", "x:yew", "x:yns"])
def test_vex_nasmyth_none_on_other_axes(axis_type):
    assert mount_from_label(axis_type, "vex", nasmyth="none")[1] is None


# ---------------------------------------------------------------- error paths


@pytest.mark.parametrize("software", ["casa", "ms", "", "fits-idi:aips"])
def test_unknown_software(software):
    with pytest.raises(ValueError, match=r"unknown software .*expected one of "
                                         r"\('fits-idi:casacore', 'fits-idi:difx'"):
        mount_from_label("ALT-AZ", software)
    with pytest.raises(ValueError, match="unknown software"):
        label_from_mount(ALTAZ, None, software)
    with pytest.raises(ValueError, match="unknown software"):
        known_labels(software)


@pytest.mark.parametrize("software", ["fits-idi", "UVFITS", "mntsta"])
def test_unqualified_fits_idi_explains_codes_6_and_7(software):
    with pytest.raises(ValueError, match=r"codes 6 and 7 mean different mounts.*"
                                         r"'fits-idi:casacore', 'fits-idi:difx' or "
                                         r"'fits-idi:pyuvdata'"):
        mount_from_label(6, software)


def test_software_of_the_wrong_type():
    with pytest.raises(TypeError, match="software must be a string"):
        mount_from_label("AZEL", 3)


def test_software_is_required_to_write():
    with pytest.raises(ValueError, match="software is required: one of"):
        label_from_mount(ALTAZ)


@pytest.mark.parametrize(("software", "label", "listing"), [
    ("casacore", "AZ-EL", r"The casacore labels are 'ALT-AZ', '', 'ALT-AZ\+ROTATOR'"),
    ("difx", "ALT-AZ-NASMYTH", r"The difx labels are 'AZEL', 'ALTAZ'.*'XYNS', 'OTHER'$"),
    ("vex", "az:az", r"axis_type 'az:az'. The vex labels are 'az:el', 'ha:dec', "
                     r"'x:yew', 'x:yns'$"),
    ("vex", "az:el:0", "The vex labels are 'az:el'"),
    ("pyuvdata", "nasmyth", r"The pyuvdata labels are 'alt-az', .*'bizarre'$"),
    ("geodetic", "XYEW-N", r"The geodetic labels are 'AZEL', .*'GNSS'$"),
    ("fits-idi:difx", 12, r"mount label 12. The fits-idi:difx labels "
                          r"are 0, 1, 2, 3, 4, 5, 6, 7$"),
    ("fits-idi:casacore", -1, "labels are 0, 1, 2, 3, 4, 5, 6, 7, 8, 9$"),
    ("fits-idi:pyuvdata", 9, "labels are 0, 1, 2, 3, 4, 5, 6, 7, 8$"),
])
def test_unknown_labels_list_the_known_ones(software, label, listing):
    with pytest.raises(ValueError, match=f"unknown {software} .*{listing}"):
        mount_from_label(label, software)


@pytest.mark.parametrize(("label", "software", "hint"), [
    ("NASP", "difx", "'NASP' is a geodetic label; use software='geodetic'"),
    ("NASM", "casacore", "'NASM' is a geodetic label; use software='geodetic'"),
    ("AZEL", "casacore", "'AZEL' is a difx and geodetic label; use software='difx' or "
                         "software='geodetic'"),
    ("azel", "vex", "'azel' is a difx and geodetic label"),
    ("ALT-AZ+BWG-R", "pyuvdata", "'ALT-AZ\\+BWG-R' is a casacore label; use "
                                 "software='casacore'"),
    ("x-y", "difx", "'x-y' is a casacore and pyuvdata label"),
    ("x:yns", "geodetic", "'x:yns' is a vex label; use software='vex'"),
    ("fixed", "geodetic", "'fixed' is a pyuvdata label"),
    ("GNSS", "pyuvdata", "'GNSS' is a geodetic label"),
    ("4", "casacore", "'4' is a fits-idi:casacore, fits-idi:difx and fits-idi:pyuvdata label"),
])
def test_labels_of_another_software_are_named(label, software, hint):
    with pytest.raises(ValueError, match=f"unknown {software} .*{hint}"):
        mount_from_label(label, software)


@pytest.mark.parametrize(("label", "software", "hint"), [
    (4, "casacore", "4 is not a casacore mount label: 4 is a fits-idi:casacore, "
                    "fits-idi:difx and fits-idi:pyuvdata label"),
    (6, "difx", r"6 is a .* label; use .* \(codes 6 and 7 mean different mounts to each\)"),
    (np.int32(1), "pyuvdata", "^1 is not a pyuvdata mount label: 1 is a fits-idi:casacore"),
    (8, "fits-idi:difx", "unknown fits-idi:difx mount label 8; 8 is a fits-idi:casacore and "
                         "fits-idi:pyuvdata label"),
    ("NASR", "fits-idi:difx", "'NASR' is not a fits-idi:difx mount label: 'NASR' is a difx "
                              "and geodetic label"),
    ("ALT-AZ", "fits-idi:casacore", "'ALT-AZ' is a casacore and pyuvdata label; use "
                                    "software='casacore' or software='pyuvdata'"),
])
def test_codes_and_strings_swapped(label, software, hint):
    with pytest.raises(ValueError, match=hint):
        mount_from_label(label, software)


@pytest.mark.parametrize("code", [4.5, "4.5", np.float64(6.25), float("nan"), float("inf"),
                                  "nan"])
def test_codes_must_be_whole_numbers(code):
    with pytest.raises(ValueError, match="a MNTSTA code is a whole number"):
        mount_from_label(code, "fits-idi:difx")


@pytest.mark.parametrize("code", ["NASR-ish", "four", "0x4"])
def test_codes_must_be_numbers(code):
    with pytest.raises(ValueError, match="a MNTSTA code is an integer"):
        mount_from_label(code, "fits-idi:casacore")


@pytest.mark.parametrize("code", [True, np.bool_(False)])
def test_bools_are_not_codes(code):
    with pytest.raises(TypeError, match="a MNTSTA code is an integer, got the bool"):
        mount_from_label(code, "fits-idi:pyuvdata")


@pytest.mark.parametrize(("label", "software", "match"), [
    (None, "fits-idi:casacore", "a MNTSTA code is an integer, got NoneType"),
    ([[4]], "fits-idi:casacore", r"labels\[0\] is itself a sequence"),
    (np.array([[4, 5]]), "fits-idi:difx", r"a column of labels is 1-d.*shape \(1, 2\)"),
    (None, "casacore", "a mount label is a string, got NoneType"),
    (4.5, "difx", "a mount label is a string, got float"),
    (["AZEL", 4.5], "difx", r"labels\[1\]: a mount label is a string, got float"),
])
def test_labels_of_the_wrong_type(label, software, match):
    with pytest.raises(TypeError, match=match):
        mount_from_label(label, software)


@pytest.mark.parametrize("nasmyth", ["up", "r", "", "nasmyth-right"])
def test_vex_bad_nasmyth(nasmyth):
    with pytest.raises(ValueError, match=r"VEX nasmyth must be one of \('none', 'right', "
                                         r"'left'\) or None, got"):
        mount_from_label("az:el", "vex", nasmyth=nasmyth)


@pytest.mark.parametrize("nasmyth", [1, True, ["right"]])
def test_vex_nasmyth_of_the_wrong_type(nasmyth):
    with pytest.raises(TypeError, match="VEX nasmyth must be a string"):
        mount_from_label("az:el", "vex", nasmyth=nasmyth)


@pytest.mark.parametrize("axis_type", ["ha:dec", "x:yew", "x:yns"])
def test_vex_nasmyth_needs_az_el(axis_type):
    with pytest.raises(ValueError, match=f"nasmyth = left needs axis_type az:el.*"
                                         f"{axis_type}.*MirrorTrain"):
        mount_from_label(axis_type, "vex", nasmyth="left")


@pytest.mark.parametrize("software", ["difx", "casacore", "fits-idi:difx"])
def test_nasmyth_is_for_vex_only(software):
    with pytest.raises(ValueError, match="nasmyth is the VEX 2 per-band value, for "
                                         "software='vex' only"):
        mount_from_label("AZEL" if software == "difx" else 0, software, nasmyth="right")


def test_write_a_mirror_train():
    for train in (MirrorTrain.yebes40m("S"), MirrorTrain.wark30m()):
        with pytest.raises(ValueError, match=r"no software labels a MirrorTrain.*"
                                             r"NasmythFocus\('right'\).*"
                                             r"BeamWaveguideFocus\('right'\)"):
            label_from_mount(ALTAZ, train, software="casacore")


@pytest.mark.parametrize("mount", [
    FixedAxisMount([1.0, 1.0, 0.0], frame="enu"),
    FixedAxisMount([0.0, 1.0, 0.0], frame="itrs"),
    FixedAxisMount([0.0, 1e-3, 1.0], frame="enu"),
])
def test_write_an_arbitrary_fixed_axis(mount):
    with pytest.raises(ValueError, match=r"no software labels the fixed axis of FixedAxisMount.*"
                                         r"pass the FixedAxisMount to Antenna directly"):
        label_from_mount(mount, software="geodetic")


@pytest.mark.parametrize("mount", [EQUA, XYN, XYE, FixedAxisMount(RICH_ENU, frame="enu")])
@pytest.mark.parametrize("focus", [NAS_R, BWG_L])
def test_write_handed_focus_on_another_mount(mount, focus):
    with pytest.raises(ValueError, match=f"{type(focus).__name__} is defined for an "
                                         "AltAzMount.*no software labels that combination"):
        label_from_mount(mount, focus, software="casacore")


@pytest.mark.parametrize("focus", [NAS_L, BWG_R])
def test_write_stationary_with_optics(focus):
    with pytest.raises(ValueError, match="a StationaryMount has no optics"):
        label_from_mount(FIXED, focus, software="geodetic")


def test_write_unknown_mount_and_focus_subclasses():
    class Turntable(Mount):
        pass

    class Periscope(Focus):
        pass

    with pytest.raises(ValueError, match=r"no software labels the mount Turntable\(\)"):
        label_from_mount(Turntable(), software="difx")
    with pytest.raises(ValueError, match=r"no software labels the focus Periscope\(\)"):
        label_from_mount(ALTAZ, Periscope(), software="difx")


@pytest.mark.parametrize(("mount", "focus", "match"), [
    (AltAzMount, None, r"mount must be an instance; did you mean AltAzMount\(\)\?"),
    ("AZEL", None, "mount must be a Mount instance"),
    (ALTAZ, NasmythFocus, r"focus must be an instance; did you mean NasmythFocus\(\)\?"),
    (ALTAZ, "right", "focus must be a Focus instance"),
])
def test_write_objects_of_the_wrong_type(mount, focus, match):
    with pytest.raises(TypeError, match=match):
        label_from_mount(mount, focus, software="casacore")


def test_known_labels_is_a_fresh_list():
    labels = known_labels("vex")
    assert labels == ["az:el", "ha:dec", "x:yew", "x:yns"]
    labels.append("x:y")
    assert known_labels("vex") == ["az:el", "ha:dec", "x:yew", "x:yns"]
    with pytest.raises(TypeError):
        KNOWN_LABELS["vex"] = ()


# ------------------------------------------------------------------- physics

TIMES = Time("2023-01-25T00:00") + np.arange(0, 24, 3) * u.hour
SOURCES = sky_grid(24)[:, np.newaxis]


def _antenna(site, label, software):
    mount, focus = mount_from_label(label, software)
    return Antenna(SITES[site], mount, focus)


@pytest.mark.parametrize(("label", "el_sign", "az_sign"), [
    ("ALT-AZ", 0, 0),
    ("ALT-AZ+NASMYTH-R", 1, 0),
    ("ALT-AZ+NASMYTH-L", -1, 0),
    ("ALT-AZ+BWG-R", 1, -1),
    ("ALT-AZ+BWG-L", -1, 1),
])
@pytest.mark.parametrize("site", ["WARKWORTH", "YEBES"])
def test_casacore_labels_give_casacore_par_angle(label, el_sign, az_sign, site):
    # MSDerivedValues::parAngle: pa (+/-) El (-/+) Az, with Az, El from AltAz.
    antenna = _antenna(site, label, "casacore")
    altaz = SOURCES.transform_to(AltAz(obstime=TIMES, location=SITES[site]))
    psi = antenna.parallactic_angle(SOURCES, TIMES).rad
    expected = psi + el_sign * altaz.alt.rad + az_sign * altaz.az.rad
    phi = antenna.feed_rotation(SOURCES, TIMES)
    assert phi.shape == (24, 8)
    assert max_angle_difference(phi.rad, expected) < 1 * MAS


def test_bwg_r_is_parallactic_angle_plus_elevation_minus_azimuth():
    # casacore's ALT-AZ+BWG-R at Warkworth, at a few epochs.
    site = SITES["WARKWORTH"]
    source = SkyCoord("05h42m36.1s +49d51m07s")
    times = Time(["2023-01-25T08:00", "2023-01-25T10:30", "2023-01-25T13:00"])
    antenna = _antenna("WARKWORTH", "ALT-AZ+BWG-R", "casacore")
    altaz = source.transform_to(AltAz(obstime=times, location=site))
    expected = (antenna.parallactic_angle(source, times).rad + altaz.alt.rad - altaz.az.rad)
    assert max_angle_difference(antenna.feed_rotation(source, times).rad, expected) < 1 * MAS
    # The same antenna from every convention that has the label.
    for label, software in [(6, "fits-idi:casacore"), ("BWG", "geodetic")]:
        other = Antenna(site, *mount_from_label(label, software))
        assert max_angle_difference(other.feed_rotation(source, times).rad,
                                    antenna.feed_rotation(source, times).rad) < 1e-9 * MAS


@pytest.mark.parametrize(("label", "software"), [
    ("X-Y", "casacore"), ("x-y", "pyuvdata"), (3, "fits-idi:casacore"), ("XYEW", "difx"),
    ("X-YE", "geodetic"), ("x:yew", "vex"),
])
def test_x_y_without_direction_is_casacore_east_west_form(label, software):
    # MSDerivedValues::parAngle for X-Y: atan2(-cos h, -sin h sin dec), which is
    # the east-west X-Y form plus 180 deg (a constant, absorbed by the clock).
    site = SITES["WETTZ13S"]
    hadec = SOURCES.transform_to(HADec(obstime=TIMES, location=site))
    h, dec = hadec.ha.rad, hadec.dec.rad
    casacore = np.arctan2(-np.cos(h), -np.sin(h) * np.sin(dec))
    phi = _antenna("WETTZ13S", label, software).feed_rotation(SOURCES, TIMES).rad
    spread, constant = angle_spread(phi, casacore)
    assert spread < 1 * MAS
    assert abs(abs(constant) - np.pi) < 1 * MAS


def test_x_y_north_south_is_not_the_casacore_form():
    # The test above can fail: XYNS differs from casacore's X-Y by more than a constant.
    site = SITES["WETTZ13S"]
    hadec = SOURCES.transform_to(HADec(obstime=TIMES, location=site))
    casacore = np.arctan2(-np.cos(hadec.ha.rad), -np.sin(hadec.ha.rad) * np.sin(hadec.dec.rad))
    phi = _antenna("WETTZ13S", "XYNS", "difx").feed_rotation(SOURCES, TIMES).rad
    assert angle_spread(phi, casacore)[0] > 0.1


def test_gnss_and_fixed_are_stationary_antennas():
    site = SITES["DBR205"]
    reference = Antenna(site, StationaryMount()).feed_rotation(SOURCES, TIMES)
    for label, software in [("GNSS", "geodetic"), ("fixed", "pyuvdata"),
                            (7, "fits-idi:pyuvdata")]:
        antenna = _antenna("DBR205", label, software)
        assert max_angle_difference(antenna.feed_rotation(SOURCES, TIMES).rad,
                                    reference.rad) == 0


# ---------------------------------------------------------------- columns of labels


@pytest.mark.parametrize("column", [
    [0, 4, 6],
    (0, 4, 6),
    np.array([0, 4, 6], dtype=np.int32),
    np.array(["0", "4", "6"]),
    np.array([b"0", b"4", b"6"]),
])
def test_a_column_gives_one_pair_per_label(column):
    # Each row as the scalar call reads it (the READ table above, DiFX codes).
    assert mount_from_label(column, "fits-idi:difx") == [
        (ALTAZ, None), (ALTAZ, NAS_R), (XYN, None)]


def test_a_column_of_strings_and_an_empty_one():
    assert mount_from_label(np.array(["ALT-AZ", "alt-az+nasmyth-l"]), "casacore") == [
        (ALTAZ, None), (ALTAZ, NAS_L)]
    assert mount_from_label([], "casacore") == []
    # A scalar stays a pair, also as a 0-d array.
    assert mount_from_label(np.array(4), "fits-idi:difx") == (ALTAZ, NAS_R)


def test_a_column_with_vex_nasmyth_applies_it_to_every_row():
    assert mount_from_label(["az:el", "az:el"], "vex", nasmyth="left") == [
        (ALTAZ, NAS_L), (ALTAZ, NAS_L)]


def test_errors_in_a_column_name_the_row():
    with pytest.raises(ValueError, match=r"labels\[2\]: 6 \(fits-idi:casacore<3.7\) has no "
                                         r"feed-rotation model"):
        mount_from_label([0, 4, 6], "fits-idi:casacore<3.7")
    with pytest.raises(ValueError, match=r"labels\[1\]: unknown casacore mount label 'ALTAZ'"):
        mount_from_label(["ALT-AZ", "ALTAZ"], "casacore")


def test_casacore_eras_never_read_6_or_7_as_beam_waveguides():
    # MSFitsOutput.cc: BWG codes exist only from d08694031 (casacore 3.7.0).
    for software in ("fits-idi:casacore<3.7", "fits-idi:casacore<3.2"):
        for code in (6, 7):
            with pytest.raises(ValueError, match="no feed-rotation model"):
                mount_from_label(code, software)
    assert mount_from_label([6, 7], "fits-idi:casacore") == [(ALTAZ, BWG_R), (ALTAZ, BWG_L)]
