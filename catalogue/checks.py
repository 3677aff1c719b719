# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The cross-check of the station catalogue: which sources hold a station, how far apart.

Used by ``build_stations.py`` (which fails on any disagreement not listed here
with its reason) and by the test suite, which runs the same comparison on the
embedded file. A source is named by a tag (`SOURCE_TAGS`) and a record by
``tag:key``.
"""

import math
import re
from pathlib import Path

import numpy as np
from readers import (
    AXIS_CODES,
    MOUNT_CODES,
    read_antenna_info,
    read_casa_sched,
    read_difx_antennas,
    read_eht,
    read_itrf_layout,
    read_locations,
    read_observatories,
    read_planner,
    read_pyuvdata_telescopes,
    read_sites,
    read_sked_antennas,
    read_sked_positions,
)

SOURCES = Path(__file__).resolve().parent / "sources"

SCHED = "SCHED 1.29.1 catalogs/"          # pythonsched 1.29.1 (PyPI)

VPO = "vlbiplanobs 4.9.2 data/stations_catalog.inp"

CASA = "casadata 2025.9.22 geodetic/Observatories"

CASA_SCHED = "casadata 2025.9.22 geodetic/SCHED_locations"

EHTIM = "eht-imaging arrays/EHT2017.txt (commit 1b5dc2c)"

EHT2025 = "eht-imaging arrays/EHT2025.txt (commit 7acf089)"

SITES = "astropy-data coordinates/sites.json (commit 1ec3f59)"

PYUVDATA = "pyuvdata 3.2.8 telescopes.py KNOWN_TELESCOPES"

DIFX = "DiFX libraries/difxio/difxio/antenna_db.c (commit ed8d571)"

ANTINFO = "IVS antenna-info.txt (A. Nothnagel, commit 9ec66be)"

SKED = "sked_catalogs (commit 5aa7e2a) "

SIMMS = "simms simms/observatories/meerkat.itrf.txt (commit e715505)"

#: The MeerKAT dishes of simms's layout: the array's 64 (M000-M063), each
#: within the array's extent (its longest baseline, 8 km) of the catalogue's
#: MEERKAT (SCHED's, a position in the array's core). The build checks both.
MEERKAT_DISHES = [f"M{i:03d}" for i in range(64)]
MEERKAT_EXTENT = 8000.0
MEERKAT_TEXT = ("simms's MeerKAT layout (ratt-ru/simms, 'Update MeerKAT coordinates', 2018) is "
                "the only source used that names the dishes (casadata's meerkat.cfg is the "
                "80-dish design layout, without names); the build checks the array's 64 dishes "
                "and each against the catalogue's MEERKAT (SCHED)")

PAPER = "paper"

#: Common epoch (MJD, 2020 Jan 1) at which two positions are compared, each
#: moved there with its own velocity (positions without one stay as given).
COMPARE_EPOCH = 58849.0

#: Tolerance of each class of comparison (metres), and what it compares.
TOLERANCES = {
    "geodetic": (1.0, "two VLBI solutions (GSFC, USNO, sked's position.cat from GSFC "
                      "2020c, or the paper's Tables 1 and 3), both moved to 2020.0 with "
                      "their velocities (sked's, given without, as they are)"),
    "compiled": (50.0, "a position that only an observatory or a compiled list gives "
                       "(the EVN planner, eht-imaging, casacore's Observatories, "
                       "astropy-data's sites) against any other"),
}

#: What each source is, for the report: tag -> (name, geodetic).
SOURCE_TAGS = {
    "sched": (f"{SCHED}locations.dat / stations.dat", None),
    "gsfc2014a": (f"{SCHED}Master_NRAO/locations.dat.gsfc_2014a", True),
    "gsfc2011a": (f"{SCHED}Master_NRAO/locations.dat.gsfc2011a", True),
    "gsfc2016a": (f"{SCHED}Master_NRAO/locations_gsfc2016aplus.dat", True),
    "casa-sched": (CASA_SCHED, None),
    "planner": (VPO, False),
    "eht2017": (EHTIM, False),
    "eht2025": (EHT2025, False),
    "casa-obs": (CASA, False),
    "sites": (SITES, False),
    "pyuvdata": (PYUVDATA, False),
    "difx": (DIFX, False),
    "antinfo": (ANTINFO, None),  # mounts and foci, no positions
    "sked": (f"{SKED}position.cat", None),
    "sked-ant": (f"{SKED}antenna.cat", None),  # mounts, no positions
    "simms": (SIMMS, None),
}

#: sked position.cat origins that are VLBI solutions (geodetic positions):
#: ``2020c`` the GSFC solution 2020c (epoch 2021 Jan 1, the file's header),
#: ``GLB...`` older GSFC solutions. The file gives no velocities: its position
#: is compared as given (one year of plate motion is under 10 cm).
SKED_GEODETIC = re.compile(r"(2020c|GLB[0-9]+)\b")

#: sked antenna.cat axis types and the catalogue's mount codes (SEST: the
#: SEST's own alt-az slewing model).
SKED_MOUNTS = {"AZEL": "AZEL", "HADC": "EQUA", "XYNS": "X-YN", "XYEW": "X-YE", "SEST": "AZEL"}

#: Stations the catalogue keeps although a single source used here holds
#: their position: name -> the reason. Listed by name in crosscheck.txt and on
#: the docs page.
SINGLE_SOURCE = {
    "NOBEYA45": "casacore's Observatories NRO (latitude 35.9445 deg, the 45 m dish; the same "
                "position as SCHED stations.dat's commented-out NOBEYA45 entry, so not an "
                "independent one) is the only position of the 45 m; sked's NOBEYA45 is 407 m "
                "from it (see the exception)",
    "NYALE13N": "sked's position.cat gives it from the station (an e-mail of 2020 Aug 5); the "
                "GSFC solutions of SCHED 1.29.1 and DiFX's antenna_db lack it; it lies 85 m "
                "from its twin NYALE13S (GSFC solution)",
    "BADRT13V": "DiFX's antenna_db gives it (as BADAR13M, 'to about 1 m, for "
                "identification'); the GSFC solutions of SCHED 1.29.1 and sked's position.cat "
                "lack it; it lies 152 m from the 32 m BADARY (GSFC solution)",
    "ZELRT13V": "DiFX's antenna_db gives it (as ZELEN13M, 'to about 1 m, for "
                "identification'); the GSFC solutions of SCHED 1.29.1 and sked's position.cat "
                "lack it; it lies 120 m from the 32 m ZELENCHK (GSFC solution)",
    **{name: MEERKAT_TEXT for name in MEERKAT_DISHES},
}

TOHOKU_TEXT = ("the 2011 Mar 11 Tohoku earthquake, whose jump and post-seismic motion the "
               "two solutions model differently")

SKED_MOBILE = ("a mobile VLBI site, observed decades before both solutions' epochs: sked's "
               "GSFC 2020c position (epoch 2021.0, no velocity given) and the GSFC 2014a "
               "solution moved to 2020.0 extrapolate it with differently estimated velocities")

OLD_SOLUTION = ("casadata's row is an old solution (USNO 1998-6, or as its FRAME says) at "
                "epoch 1997.0, moved 23 years with its own velocity")

#: Comparisons allowed beyond their tolerance: (station, source tag) ->
#: (largest difference allowed in m, the reason). A station whose difference
#: exceeds both fails the build.
EXCEPTIONS = {
    ("VERAMZSW", "gsfc2014a"): (3.5, TOHOKU_TEXT + " (Mizusawa moved about 3 m)"),
    ("VERAMZSW", "gsfc2011a"): (3.5, TOHOKU_TEXT + " (Mizusawa moved about 3 m)"),
    ("TSUKUB32", "gsfc2014a"): (1.5, TOHOKU_TEXT),
    ("TSUKUB32", "gsfc2011a"): (1.5, TOHOKU_TEXT),
    ("MIZNAO10", "casa-sched"): (1.5, OLD_SOLUTION + ", across " + TOHOKU_TEXT[4:]),
    ("NOBEY_6M", "casa-sched"): (4.0, OLD_SOLUTION + ", across " + TOHOKU_TEXT[4:]),
    ("TIDBIN64", "casa-sched"): (2.0, OLD_SOLUTION),
    ("GGAO7108", "casa-sched"): (1.5, OLD_SOLUTION),
    ("PARKES", "casa-sched"): (5.0, OLD_SOLUTION),
    ("WARK30M", "gsfc2016a"): (3.0, "the 2016a solution holds the 30 m antenna's first few "
                                    "sessions; later solutions moved it by 2.6 m"),
    ("YEBES", "casa-sched"): (250.0, "casadata's YEBES row has the same position (0.4 m at "
                                     "its epoch) with a velocity near 9 m/yr, a unit error; "
                                     "moved to 2020.0 it is 206 m away"),
    ("TSUKUBA", "casa-sched"): (350.0, "casadata's TSUKUBA (code TS, 'coordinates from RCW') "
                                       "is another antenna of the Tsukuba site than the GSFC "
                                       "solution's TSUKUBA (code TS2), 318 m away"),
    ("NOTO", "sites"): (150.0, "astropy-data's Noto is read off a map ('website & google "
                               "maps'); SCHED's is the GSFC VLBI solution"),
    ("FAST", "planner"): (150.0, "two approximate positions of a 500 m dish (SCHED's from "
                                 "the observatory's web page); no geodetic solution holds it"),
    ("WETTZELL", "planner"): (150.0, "the planner's [Wettzell] is 123 m from the 20 m "
                                     "antenna of the GSFC solution: a position of the site"),
    ("HOBART12", "planner"): (400.0, "the planner's [Hobart 12m] is 383 m from the GSFC "
                                     "solution's 12 m antenna: an approximate position"),
    ("DSS63", "planner"): (550.0, "the planner's [Robledo 70] repeats the position of its "
                                  "[Robledo 34] (DSS65), 534 m from the 70 m antenna"),
    ("DSS65A", "planner"): (70.0, "the planner's [Robledo 34] is DSS65's position before the "
                                  "antenna moved about 61 m in July 2005 (SCHED stations.dat)"),
    ("KP12", "eht2025"): (420.0, "eht-imaging's KP row holds the VLBA antenna's position "
                                 "(KP-VLBA, 0.1 m away from it), 402 m from the 12 m"),
    ("LMT", "eht2025"): (100.0, "eht-imaging keeps an older LMT position; SCHED's is the one "
                                "S. Doeleman provided in Feb 2015 (stations.dat comment)"),
    ("LMT", "eht2017"): (100.0, "eht-imaging keeps an older LMT position; SCHED's is the one "
                                "S. Doeleman provided in Feb 2015 (stations.dat comment)"),
    ("APEX", "planner"): (1300.0, "the planner's [APEX] is 1.29 km north (latitude -22.9942 "
                                  "deg); eht-imaging and casacore (-23.0057 deg) agree"),
    ("JCMT", "casa-obs"): (450.0, "casacore's JCMT (1998, whole arcseconds) is 436 m off; "
                                  "eht-imaging and astropy-data's GPS position (R. Tilanus "
                                  "2007) agree"),
    ("ARECIBO", "casa-obs"): (150.0, "casacore's ARECIBO is the observatory's site (rounded "
                                     "to 0.001 deg), not the dish's phase centre"),
    ("GREENLAND", "planner"): (1500.0, "the planner's [Greenland] and eht-imaging's GLT "
                                       "differ by 1.3 km and no third source holds the GLT; "
                                       "1.3 km tilts the vertical by 0.012 deg"),
    ("TSUKUB32", "sked"): (1.5, TOHOKU_TEXT),
    ("MIZNAO10", "sked"): (1.5, TOHOKU_TEXT),
    ("MIZUSGSI", "sked"): (1.5, TOHOKU_TEXT),
    **{(name, "sked"): (1.5, SKED_MOBILE) for name in ("CTVASBAY", "GGAO7108", "OCOTILLO")},
    ("GIFU3", "sked"): (300.0, "sked's GIFU3 has the origin 'GSI' (0.1 m digits, not a VLBI "
                               "solution) and lies 265 m from the GSFC 2014a solution's "
                               "antenna, whose position the catalogue keeps"),
    ("NOBEYA45", "sked"): (420.0, "sked's NOBEYA45 (origin GLB659) lies 2.6 m from its "
                                  "NOBEY_6M (GSFC 2020c): the 6 m antenna's position under "
                                  "the 45 m's name, 407 m from casacore's NRO (the 45 m dish, "
                                  "latitude 35.9445 deg against 35.9409 deg)"),
    ("ARECIBO", "sked"): (55000.0, "sked's ARECIBO (origin 'Other') lies 54.6 km from the dish "
                                   "(latitude 18.23 deg against 18.34 deg): not the antenna's "
                                   "position"),
    ("SPT", "planner"): (1200.0, "the planner places SPT at the pole; DiFX's antenna_db "
                                 "1.16 km from it, at longitude -45 deg"),
    ("SPT", "eht2025"): (1200.0, "eht-imaging places SPT at the pole (0.01, 0.01 m: the "
                                 "EHT's convention), DiFX's antenna_db 1.16 km from it at "
                                 "longitude -45 deg; there the zenith is the celestial pole "
                                 "and the parallactic angle 180 deg for every source: the "
                                 "two positions' feed rotations differ by less than 0.02 deg"),
    ("SPT", "eht2017"): (1200.0, "as in eht-imaging's current file: SPT at the pole"),
}

#: Reference points: (station, source tag) -> what the source's position is
#: a position of. The difference is reported, not held to a tolerance: a
#: connected array's observatory position is its centre, not the pad or dish
#: the catalogue gives.
REFERENCE_POINTS = {
    ("WB_RT1", "casa-obs"): (3000.0, "the Westerbork array's reference point, not the dish RT1"),
    ("WB_RT1", "planner"): (3000.0, "the planner's [WSRT]: the phased array, not the dish RT1"),
    ("MEERKAT", "casa-obs"): (8000.0, "the MeerKAT array's reference point, not SCHED's dish"),
    ("ALMA", "casa-obs"): (16000.0, "the ALMA array's reference point (MMA Memo 261), not the "
                                    "EHT's phased-array reference point"),
    ("ALMA", "sites"): (16000.0, "the ALMA site (0.001 deg), not the EHT's phased-array "
                                 "reference point"),
    ("NOEMA", "casa-obs"): (1700.0, "the NOEMA array's reference point, not the EHT's "
                                    "phased-array reference point"),
    ("SMA", "casa-obs"): (500.0, "casacore's SMA X, Y, Z are 'SMAP' (from a vex file), not "
                                 "the EHT's phased-array reference point"),
    ("SMA", "planner"): (500.0, "the planner's [SMA] is another point of the array"),
    ("SMA", "difx"): (500.0, "DiFX's SMA is 'SMAP' (as casacore's), not the EHT's "
                             "phased-array reference point"),
    ("SMA", "pyuvdata"): (500.0, "pyuvdata's SMA is the array's position of Ho, Moran & Lo "
                                 "2004, not the EHT's phased-array reference point"),
    ("ASKAP32", "casa-obs"): (6000.0, "the ASKAP array's reference point, not the antenna "
                                      "SCHED gives (the phased array's VLBI position)"),
    ("ASKAP32", "sites"): (6000.0, "the ASKAP site (0.001 deg), not SCHED's antenna"),
    ("ASKAP32", "planner"): (6000.0, "the planner's [ASKAP], another point of the array"),
    ("GMRT_C02", "casa-obs"): (25000.0, "the GMRT array's reference point, not the dish C02"),
    ("GMRT_C02", "sites"): (25000.0, "the GMRT site (pulsar timing), not the dish C02"),
    ("GMRT_C02", "planner"): (25000.0, "the planner's [GMRT], the phased array, not C02"),
    ("ATA", "casa-obs"): (300.0, "casacore's ATA and pyuvdata's (D. DeBoer 2024) are two "
                                 "reference points of the array (its antennas span 300 m)"),
    ("HERA", "casa-obs"): (1000.0, "casacore's HERA and pyuvdata's (hera_mc) are two "
                                   "reference points of the array (with its outriggers "
                                   "about 1 km across)"),
}

ALTZ_EVERYWHERE = ("casadata's SCHED_locations, like SCHED's locations.dat.2005f that it "
                   "descends from, writes AXISTYPE 'altz' for this polar or X-Y mount; the "
                   "IVS antenna-info file gives its mount (and the large axis offset of both "
                   "files is that of a polar or X-Y mount)")

#: Mount or focus statements that the catalogue does not follow:
#: (station, source tag) -> the reason.
MOUNT_EXCEPTIONS = {
    **{(name, "casa-sched"): ALTZ_EVERYWHERE for name in (
        "MARPOINT", "NRAO85_1", "NRAO85_3", "SANTIA12", "HATCREEK", "HRAS_085", "KAUAI",
        "MOJAVE12", "RICHMOND")},
    ("APEX", "difx"): "APEX has Nasmyth cabins on both sides; the EHT's receiver is in the "
                      "right-handed one as eht-imaging's current and 2017 files say "
                      "(FR_ELEV_ANGLE +1); DiFX's antenna_db (names and rough positions) "
                      "writes NASL",
    ("HOBART26", "planner"): "Hobart 26 m is an X-Y mount (SCHED stations.dat MOUNT=XYEW and "
                             "the GSFC AXISTYPE agree); the planner writes ALTAZ for it",
}

#: Names of casacore's Observatories rows and the station each one is (by
#: name, no position used).
OBSERVATORY_NAMES = {
    "ALMA": "ALMA", "ATCA": "ATCA", "GMRT": "GMRT_C02", "SMA": "SMA", "VLA": "VLA",
    "ASKAP": "ASKAP32", "MeerKAT": "MEERKAT", "NOEMA": "NOEMA", "APEX": "APEX", "SMT": "SMT",
    "JCMT": "JCMT", "PKS": "PARKES", "MOPRA": "MOPRA", "ARECIBO": "ARECIBO",
    "GBT": "GBT-VLBA", "Effelsberg": "EFLSBERG", "WSRT": "WB_RT1", "NRO": "NOBEYA45",
    "FAST": "FAST", "IRAM_PDB": "NOEMA", "ATA": "ATA", "HERA": "HERA", "OVRO-LWA": "OVRO-LWA",
    "MWA": "MWA",
}

#: astropy-data sites.json keys and the station each one is (by name).
SITE_NAMES = {
    "vla": "VLA", "alma": "ALMA", "gbt": "GBT-VLBA", "ao": "ARECIBO", "jcmt": "JCMT",
    "meerkat": "MEERKAT", "gmrt": "GMRT_C02", "fast": "FAST", "parkes": "PARKES",
    "effelsberg": "EFLSBERG", "askap": "ASKAP32", "medicina": "MEDICINA", "noto": "NOTO",
    "srt": "SARDINIA", "mwa": "MWA",
}

#: DiFX antenna_db names (or IVS names as DiFX spells them) and the
#: catalogue's stations, where DiFX gives no IVS name or spells it otherwise.
DIFX_NAMES = {"Apex": "APEX", "LMT": "LMT", "Pico Veleta": "PICOVEL", "SMA": "SMA",
              "SMT": "SMT", "JCMT": "JCMT", "Kitt Peak 12": "KP12", "South Pole": "SPT",
              "ALMA": "ALMA", "NYALES13S": "NYALE13S", "ONSALS60": "ONSALA60",
              "DSS43": "TIDBIN64", "Badary 13m": "BADRT13V", "Zelenchukskya13": "ZELRT13V"}

#: antenna-info mount codes and the catalogue's.
ANTINFO_MOUNTS = {"MO_AZEL": "AZEL", "MO_EQUA": "EQUA", "MO_XYNO": "X-YN", "MO_XYEA": "X-YE",
                  "MO_RICH": "RICH"}

#: DiFX antenna_db mount strings and the catalogue's codes.
DIFX_MOUNTS = {"NASL": "NASL", "NASR": "NASR", "EQUA": "EQUA", "XYEW": "X-YE", "XYNS": "X-YN",
               "AZEL": "AZEL"}

#: pyuvdata's known telescopes and the catalogue's stations (by name).
PYUVDATA_NAMES = {"ATA": "ATA", "HERA": "HERA", "OVRO-LWA": "OVRO-LWA", "SMA": "SMA"}

#: pyuvdata mount_type values and the mount code and focus each states.
PYUVDATA_MOUNTS = {"alt-az": ("AZEL", None), "alt-az+nasmyth-l": ("NASL", "nasmyth-left"),
                   "fixed": ("GNSS", ""), "phased": ("GNSS", "")}

#: casadata SCHED_locations DBNAMEs that differ from the catalogue's name.
CASA_SCHED_NAMES = {"GBT": "GBT-VLBA", "ATCA_104": "AT_W104"}

#: eht-imaging station names -> catalogue names (names only, no position used).
EHT_NAMES = {"PV": "PICOVEL", "SMT": "SMT", "SMA": "SMA", "LMT": "LMT", "ALMA": "ALMA",
             "APEX": "APEX", "JCMT": "JCMT", "SPT": "SPT", "KP": "KP12", "GLT": "GREENLAND",
             "PDB": "NOEMA"}

#: The EHT array of eht-imaging's current file (arrays/EHT2025.txt) that is
#: the EHT today, and why the file's other rows are not.
EHT_NOT_CURRENT = {"CARMA": "CARMA closed in 2015; the file keeps it for simulations"}


def moved_to(xyz, vel, epoch, to):
    """A position moved from its epoch (MJD) to ``to`` with its velocity (m/yr)."""
    if math.isnan(epoch):
        return np.array(xyz)
    return np.array(xyz) + np.array(vel) * (to - epoch) / 365.25


def load_sources():
    """Every file that positions are compared with, by source tag."""
    sched_dir = SOURCES / "sched"
    return {
        "sched": read_locations(sched_dir / "locations.dat"),
        "gsfc2014a": read_locations(sched_dir / "locations.dat.gsfc_2014a"),
        "gsfc2011a": read_locations(sched_dir / "locations.dat.gsfc2011a"),
        "gsfc2016a": read_locations(sched_dir / "locations_gsfc2016aplus.dat"),
        "casa-sched": {str(r["row"]): r for r in
                       read_casa_sched(SOURCES / "casadata" / "SCHED_locations")},
        "planner": {s["section"]: s for s in
                    read_planner(SOURCES / "vlbiplanobs" / "stations_catalog.inp")},
        "eht2017": read_eht(SOURCES / "eht-imaging" / "EHT2017.txt"),
        "eht2025": read_eht(SOURCES / "eht-imaging" / "EHT2025.txt"),
        "casa-obs": read_observatories(SOURCES / "casadata" / "Observatories"),
        "sites": read_sites(SOURCES / "astropy-data" / "sites.json"),
        "pyuvdata": read_pyuvdata_telescopes(SOURCES / "pyuvdata" / "telescopes.py"),
        "difx": {e["name"]: e for e in read_difx_antennas(SOURCES / "difx" / "antenna_db.c")},
        "antinfo": read_antenna_info(SOURCES / "antenna-info" / "antenna-info.txt"),
        "sked": read_sked_positions(SOURCES / "sked" / "position.cat"),
        "sked-ant": read_sked_antennas(SOURCES / "sked" / "antenna.cat"),
        "simms": {e["name"]: e for e in
                  read_itrf_layout(SOURCES / "simms" / "meerkat.itrf.txt")},
    }


def is_geodetic(position_source):
    """Whether a position_source names a VLBI solution (GSFC, USNO) or the paper's tables."""
    return bool(re.search(r"\((GSFC|USNO)", position_source)) or \
        position_source.startswith(f"{PAPER} Table")


def references(row, sources):
    """The source records that hold a station, by name: ``tag:key`` strings."""
    name, refs = row["name"], []
    if row["position_source"].startswith(PAPER) and name in sources["sched"]:
        refs.append(f"sched:{name}")
    if row.get("frame", "").startswith("GSFC"):
        for tag in ("gsfc2014a", "gsfc2011a", "gsfc2016a"):
            other = sources[tag].get(name)
            if other is not None and other["frame"] != row["frame"] and \
                    not other["frame"].startswith("VLA"):
                refs.append(f"{tag}:{name}")
    for key, record in sources["casa-sched"].items():
        if CASA_SCHED_NAMES.get(record["name"], record["name"]) == name:
            refs.append(f"casa-sched:{key}")
    if "planner" in row and not row["position_source"].startswith(VPO):
        refs.append(f"planner:{row['planner']['section']}")
    for tag in ("eht2025", "eht2017"):
        refs += [f"{tag}:{e}" for e in sources[tag]
                 if EHT_NAMES.get(e) == name and e not in EHT_NOT_CURRENT
                 and not row["position_source"].startswith(SOURCE_TAGS[tag][0])]
    refs += [f"casa-obs:{o}" for o, station in OBSERVATORY_NAMES.items()
             if station == name and o in sources["casa-obs"]
             and not row["position_source"].startswith(f"{CASA} ({o})")]
    refs += [f"sites:{s}" for s, station in SITE_NAMES.items() if station == name
             and not row["position_source"].startswith(f"{SITES} ({s}:")]
    refs += [f"difx:{k}" for k, e in sources["difx"].items()
             if (DIFX_NAMES.get(k) or DIFX_NAMES.get(e["ivs"]) or
                 next((r for r in (e["ivs"],) if r and name_key(r) == name_key(name)), None)) in
             (name, name_key(name)) and not row["position_source"].startswith(DIFX)]
    refs += [f"pyuvdata:{k}" for k, e in sources["pyuvdata"].items()
             if "xyz" in e and PYUVDATA_NAMES.get(k) == name
             and not row["position_source"].startswith(PYUVDATA)]
    if name in sources["sked"] and not row["position_source"].startswith(SKED):
        refs.append(f"sked:{name}")
    return refs


def source_record(sources, ref):
    """The record of a ``tag:key`` reference."""
    tag, key = ref.split(":", 1)
    record = sources[tag][key]
    if tag == "casa-obs":
        return dict(xyz=record, vel=[0.0] * 3, epoch=math.nan, geodetic=False)
    if tag in ("eht2017", "eht2025", "planner", "sites", "pyuvdata", "difx"):
        return dict(xyz=record["xyz"], vel=[0.0] * 3, epoch=math.nan, geodetic=False)
    if tag == "sked":
        return dict(xyz=record["xyz"], vel=[0.0] * 3, epoch=math.nan,
                    geodetic=bool(SKED_GEODETIC.match(record["origin"])))
    frame = record["frame"]
    return dict(xyz=record["xyz"], vel=record["vel"], epoch=record["epoch"],
                geodetic=bool(re.match(r"(GSFC|USNO)", frame)))


def source_names(sources, ref):
    """The names a source gives the station (aliases of the catalogue's row)."""
    tag, key = ref.split(":", 1)
    record = sources[tag][key]
    if tag == "casa-sched":
        return [record["code"], record["name"]]
    if tag == "sites":
        return record["names"]
    if tag in ("casa-obs", "eht2025", "eht2017", "pyuvdata"):
        return [key]
    return []


def crosscheck(name, xyz, vel, epoch, geodetic, refs, sources):
    """Compare a station's position with each referenced source, both moved to 2020.0.

    Returns one dict per reference: ``ref``, ``distance`` (m), ``kind``
    (``geodetic`` or ``compiled``), ``limit`` (m) and ``status`` (``ok``,
    ``exception``, ``reference point`` or ``FAIL``) with ``reason``.
    """
    here = moved_to(xyz, vel, epoch, COMPARE_EPOCH)
    checks = []
    for ref in refs:
        other = source_record(sources, ref)
        there = moved_to(other["xyz"], other["vel"], other["epoch"], COMPARE_EPOCH)
        distance = float(np.linalg.norm(here - there))
        kind = "geodetic" if geodetic and other["geodetic"] else "compiled"
        tag = ref.split(":", 1)[0]
        limit, status, reason = TOLERANCES[kind][0], "ok", ""
        if distance <= limit:
            pass
        elif (name, tag) in REFERENCE_POINTS:
            limit, reason = REFERENCE_POINTS[(name, tag)]
            status = "reference point" if distance <= limit else "FAIL"
        elif (name, tag) in EXCEPTIONS:
            limit, reason = EXCEPTIONS[(name, tag)]
            status = "exception" if distance <= limit else "FAIL"
        else:
            status = "FAIL"
        checks.append(dict(ref=ref, distance=distance, kind=kind, limit=limit,
                           status=status, reason=reason))
    return checks


def _axis_family(code):
    return "AZEL" if code in ("AZEL", "NASR", "NASL", "BWG") else code


def mount_checks(row, sources):
    """Mount and focus statements of the other sources: (ref, stated, status, reason)."""
    found = []
    refs = list(row["refs"])
    if row["name"] in sources["antinfo"]:
        refs.append(f"antinfo:{row['name']}")
    if row["name"] in sources["sked-ant"] and not row["mount_source"].startswith(SKED):
        refs.append(f"sked-ant:{row['name']}")
    for ref in refs:
        tag, key = ref.split(":", 1)
        record = sources[tag][key]
        stated = None
        if tag == "antinfo":
            stated = ANTINFO_MOUNTS.get(record["mount"])
            if stated is not None:
                agree = _axis_family(stated) == _axis_family(row["mount"])
                found.append((ref, f"mount {stated}", "agree" if agree else "disagree"))
            if record["focus"] == "FO_PRIM":
                agree = row["focus"] == "prime"
                found.append((ref, "focus prime", "agree" if agree else "disagree"))
            elif record["focus"] == "FO_SECN":
                agree = row["focus"] != "prime" and not (row["focus"] == "" and
                                                         row["mount"] == "GNSS")
                found.append((ref, "focus secondary", "agree" if agree else "disagree"))
            continue
        if tag == "sked-ant":
            stated = SKED_MOUNTS.get(record["axis"])
            agree = _axis_family(stated) == _axis_family(row["mount"])
            found.append((ref, f"mount {stated}", "agree" if agree else "disagree"))
            continue
        if tag == "difx" and record["mount"]:
            stated = DIFX_MOUNTS.get(record["mount"])
            agree = _axis_family(stated) == _axis_family(row["mount"]) and (
                stated not in ("NASL", "NASR") or stated == row["mount"])
            found.append((ref, f"mount {stated}", "agree" if agree else "disagree"))
            continue
        if tag == "casa-sched":
            stated = AXIS_CODES.get(record["axis"].upper())
            if stated is not None and _axis_family(stated) != _axis_family(row["mount"]):
                found.append((ref, f"mount {stated}", "disagree"))
            elif stated is not None:
                found.append((ref, f"mount {stated}", "agree"))
        elif tag == "planner" and record.get("mount"):
            stated = MOUNT_CODES.get(record["mount"].upper())
            agree = _axis_family(stated) == _axis_family(row["mount"])
            found.append((ref, f"mount {stated}", "agree" if agree else "disagree"))
        elif tag == "pyuvdata" and record.get("mount_type") in PYUVDATA_MOUNTS:
            code, focus = PYUVDATA_MOUNTS[record["mount_type"]]
            agree = _axis_family(code) == _axis_family(row["mount"]) and \
                (focus is None or focus == row["focus"])
            found.append((ref, f"mount {record['mount_type']}", "agree" if agree else "disagree"))
        elif tag in ("eht2017", "eht2025") and record["fr_par"]:
            side = {1: "nasmyth-right", -1: "nasmyth-left"}.get(int(record["fr_elev"]))
            if side is None:
                agree = not row["focus"].startswith(("nasmyth", "bwg"))
                stated = "not Nasmyth"
            else:
                agree, stated = row["focus"] == side, side
            found.append((ref, f"focus {stated}", "agree" if agree else "disagree"))
    return [(ref, stated, "exception" if status == "disagree" and
             (row["name"], ref.split(":")[0]) in MOUNT_EXCEPTIONS else status,
             MOUNT_EXCEPTIONS.get((row["name"], ref.split(":")[0]), ""))
            for ref, stated, status in found]


def failures(rows):
    """Every unexplained disagreement among the kept rows, one line each, and every
    listed exception or reference point that no comparison needs (a stale reason)."""
    used = {(row["name"], c["ref"].split(":")[0]) for row in rows for c in row["checks"]
            if c["status"] in ("exception", "reference point")}
    used |= {(row["name"], m[0].split(":")[0]) for row in rows for m in row["mount_checks"]
             if m[2] == "exception"}
    lines = [f"{name}: the listed reason for {tag} is not needed (no such difference)"
             for name, tag in sorted({**EXCEPTIONS, **REFERENCE_POINTS, **MOUNT_EXCEPTIONS})
             if (name, tag) not in used]
    lines += [f"{row['name']}: listed as single-source, but {c['ref']} confirms it (within "
              f"{c['limit']:g} m): remove it from SINGLE_SOURCE"
              for row in rows if row["name"] in SINGLE_SOURCE
              for c in row["checks"] if c["status"] == "ok"]
    for row in rows:
        for check in row["checks"]:
            if check["status"] == "FAIL":
                lines.append(f"{row['name']}: {check['distance']:.3f} m from {check['ref']} "
                             f"(tolerance {check['limit']:g} m, {check['kind']})")
        for ref, stated, status, _ in row["mount_checks"]:
            if status == "disagree":
                lines.append(f"{row['name']}: {ref} states {stated}; the catalogue has "
                             f"mount {row['mount']}, focus {row['focus'] or 'default'}")
    return lines


def name_key(name):
    return re.sub(r"[^0-9A-Z]", "", str(name).upper())


def summary(rows):
    """Stations per source, median and largest difference per class, disagreements."""
    lines = ["Stations per source (positions compared; antinfo: mounts and foci):"]
    for tag in SOURCE_TAGS:
        n = sum(any(c["ref"].startswith(f"{tag}:") for c in row["checks"]) or
                any(m[0].startswith(f"{tag}:") for m in row["mount_checks"]) for row in rows)
        if n:
            lines.append(f"  {tag:10s} {n:4d}")
    lines.append("Position differences per class (reference points aside):")
    for kind in TOLERANCES:
        d = np.array([c["distance"] for row in rows for c in row["checks"]
                      if c["kind"] == kind and c["status"] != "reference point"])
        if d.size:
            beyond = int(np.sum(d > TOLERANCES[kind][0]))
            lines.append(f"  {kind:9s} n={d.size:4d}  median {np.median(d):9.3f} m  "
                         f"max {d.max():9.3f} m  beyond tolerance {beyond} (each a listed "
                         "exception)")
    mounts = [m for row in rows for m in row["mount_checks"]]
    lines.append(f"Mount and focus statements: {len(mounts)}, "
                 f"{sum(m[2] == 'agree' for m in mounts)} agree, "
                 f"{sum(m[2] == 'exception' for m in mounts)} listed exceptions")
    lines.append("Disagreements beyond tolerance (each with its reason in checks.py):")
    for row in sorted(rows, key=lambda r: r["name"]):
        for c in row["checks"]:
            if c["status"] in ("exception", "reference point"):
                lines.append(f"  {row['name']:10s} {c['ref']:24s} {c['distance']:10.3f} m  "
                             f"({c['status']})")
        for ref, stated, status, _ in row["mount_checks"]:
            if status == "exception":
                lines.append(f"  {row['name']:10s} {ref:24s} states {stated}; catalogue "
                             f"{row['mount']} {row['focus'] or '-'}")
    return "\n".join(lines)
