# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Build ``astropy_feedrot/data/stations.ecsv`` from the public files in ``catalogue/sources``.

Run from the repository root::

    python catalogue/build_stations.py            # writes the package's stations.ecsv
    python catalogue/build_stations.py --output X.ecsv --report Y.txt

Nothing here types a coordinate: every position is read from a saved source
file (see ``catalogue/sources/README.rst``), and every position is compared
with a second, independent catalogue; the comparison goes to
``catalogue/crosscheck.txt``. Reading the casacore ``Observatories`` table
needs python-casacore.
"""

import argparse
import math
import re
import sys
from pathlib import Path

import numpy as np
from astropy import units as u
from astropy.coordinates import EarthLocation
from astropy.table import Table
from readers import (
    AXIS_CODES,
    MOUNT_CODES,
    read_axistypes,
    read_casa_sched,
    read_eht,
    read_locations,
    read_antenna_info,
    read_difx_antennas,
    read_ms_mounts,
    read_observatories,
    read_paper,
    read_planner,
    read_pyuvdata_telescopes,
    read_sched_stations,
    read_sites,
    validate_axistypes,
)

HERE = Path(__file__).resolve().parent
SOURCES = HERE / "sources"
ROOT = HERE.parent
OUTPUT = ROOT / "astropy_feedrot" / "data" / "stations.ecsv"
REPORT = HERE / "crosscheck.txt"

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
PAPER = "paper"

#: Common epoch (MJD, 2020 Jan 1) at which two positions are compared, each
#: moved there with its own velocity (positions without one stay as given).
COMPARE_EPOCH = 58849.0

#: Epoch of the paper's simulations (2023 Jan 25, MJD).
PAPER_EPOCH = 59969.0

#: Tolerance of each class of comparison (metres), and what it compares.
TOLERANCES = {
    "geodetic": (1.0, "two VLBI solutions (GSFC, USNO, or the paper's Tables 1 and 3), "
                      "both moved to 2020.0 with their velocities"),
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
}

TOHOKU_TEXT = ("the 2011 Mar 11 Tohoku earthquake, whose jump and post-seismic motion the "
               "two solutions model differently")
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
    ("SPT", "planner"): (1200.0, "the planner places SPT at the pole; DiFX's antenna_db "
                                 "1.16 km from it, at longitude -45 deg"),
    ("SPT", "eht2025"): (1200.0, "eht-imaging places SPT at the pole (0.01, 0.01 m: the "
                                 "EHT's convention); at the pole the longitude is arbitrary "
                                 "and the feed rotation of the two positions differs by a "
                                 "near-constant angle; DiFX's antenna_db places it 1.16 km "
                                 "from the pole at longitude -45 deg"),
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

#: Largest distance (m) at which an EVN planner entry is taken to be the same
#: antenna as a GSFC position, to give it a mount: a nearby but different
#: antenna (a mobile site beside an observatory, 70 m away) must not lend its mount.
SAME_ANTENNA = 10.0

#: Stations of eastern Japan whose two GSFC solutions differ eastward by more
#: than the geodetic tolerance (the 2011 Tohoku earthquake; see crosscheck.txt).
TOHOKU = {"USUDA64", "MIZNAO10", "MIZUSGSI", "KASHIM11", "KOGANEI", "TSUKUB32"}

#: The paper's antennas: name -> (position source, mount, focus, mount source, focus source).
PAPER_FOCUS = {
    "DBR205": ("GNSS", "", "paper Table 1 (GNSS)", "paper Table 1: a GNSS antenna has no focus"),
    "FD-VLBA": ("AZEL", "cassegrain", "paper Table 1 (Az.-El)", "paper Sec. 4.1 (Cassegrain)"),
    "GGAO12M": ("AZEL", "", "paper Table 3 (Az.-El)",
                "assumed: the mount's default (Cassegrain); the paper gives none"),
    "WETTZ13S": ("AZEL", "", "paper Table 3 (Az.-El)",
                 "assumed: the mount's default (Cassegrain); the paper gives none"),
    "YEBES40M": ("NASR", "yebes40m-X", "paper Appendix C.1 (Nasmyth, right-handed)",
                 "paper Appendix C.1 (X-band mirror train)"),
    "WARK30M": ("BWG", "wark30m", "paper Appendix C.2 (beam waveguide)",
                "paper Appendix C.2 (mirror train)"),
    "WARK12M": ("AZEL", "cassegrain", "paper Sec. 4 (az-el)", "paper Sec. 4 (Cassegrain)"),
    "EFLSBERG": ("AZEL", "gregorian", "paper Sec. 4 (az-el)", "paper Sec. 4 (Gregorian)"),
    "PARKES": ("AZEL", "prime", "paper Sec. 4 (az-el)", "paper Sec. 4 (prime focus)"),
}
PAPER_ORDER = list(PAPER_FOCUS)

# Field rotators: ASKAP's antennas have a third (roll) axis that turns the
# phased-array feed to keep it fixed on the sky while tracking.
ROTATORS = {
    "ASKAP32": ("sky", "Hotan et al. 2021, PASA 38, e009 (ASKAP system description): "
                       "three-axis antennas whose roll axis keeps the feed fixed on the sky"),
}
PAPER_ALIASES = {
    "FD-VLBA": ["Fort Davis", "FD", "VLBA_FD"],
    "GGAO12M": ["Goddard 12m", "GGAO", "Gs"],
    "WETTZ13S": ["Wettzell 13S", "Ws"],
    "YEBES40M": ["Yebes", "Yebes 40m", "YS"],
    "WARK30M": ["Warkworth 30m", "WA"],
    "WARK12M": ["Warkworth 12m", "WW"],
    "EFLSBERG": ["Effelsberg", "EF"],
    "PARKES": ["Parkes", "PA"],
}

#: Names of casacore's Observatories rows and the station each one is (by
#: name, no position used).
OBSERVATORY_NAMES = {
    "ALMA": "ALMA", "ATCA": "ATCA", "GMRT": "GMRT_C02", "SMA": "SMA", "VLA": "VLA",
    "ASKAP": "ASKAP32", "MeerKAT": "MEERKAT", "NOEMA": "NOEMA", "APEX": "APEX", "SMT": "SMT",
    "JCMT": "JCMT", "PKS": "PARKES", "MOPRA": "MOPRA", "ARECIBO": "ARECIBO",
    "GBT": "GBT-VLBA", "Effelsberg": "EFLSBERG", "WSRT": "WB_RT1", "NRO": "NOBEY_45",
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

#: Connected arrays of pyuvdata's known telescopes: name -> (catalogue name,
#: the source of the position, why the mount code). A ``fixed`` or ``phased``
#: array's elements are fixed to the ground: the geodetic code GNSS, a
#: stationary antenna (astropy_feedrot.labels reads pyuvdata's ``fixed`` so).
PYUVDATA_ARRAYS = {
    "ATA": ("ATA", "pyuvdata", "AZEL"),
    "HERA": ("HERA", "pyuvdata", "GNSS"),
    "OVRO-LWA": ("OVRO-LWA", "pyuvdata", "GNSS"),
    "MWA": ("MWA", "sites:mwa", "GNSS"),  # pyuvdata takes MWA's location from astropy
}

#: DiFX antenna_db names (or IVS names as DiFX spells them) and the
#: catalogue's stations, where DiFX gives no IVS name or spells it otherwise.
DIFX_NAMES = {"Apex": "APEX", "LMT": "LMT", "Pico Veleta": "PICOVEL", "SMA": "SMA",
              "SMT": "SMT", "JCMT": "JCMT", "Kitt Peak 12": "KP12", "South Pole": "SPT",
              "ALMA": "ALMA", "NYALES13S": "NYALE13S", "ONSALS60": "ONSALA60",
              "DSS43": "TIDBIN64"}

#: Stations whose position the catalogue takes from DiFX's antenna_db (the
#: only source used that holds them off the pole): name -> DiFX name.
DIFX_POSITIONS = {"SPT": "South Pole"}

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

#: Connected arrays: the network name given to a station by its name.
CONNECTED = {"VLA": "VLA", "ALMA": "ALMA", "ATCA": "ATCA", "SMA": "SMA", "NOEMA": "NOEMA",
             "PDBURE": "NOEMA", "MEERKAT": "MeerKAT", "GMRT": "GMRT", "ASKAP": "ASKAP",
             "ASKAP32": "ASKAP", "GMRT_C02": "GMRT", "AT_W104": "ATCA"}

#: eht-imaging station names -> catalogue names (names only, no position used).
EHT_NAMES = {"PV": "PICOVEL", "SMT": "SMT", "SMA": "SMA", "LMT": "LMT", "ALMA": "ALMA",
             "APEX": "APEX", "JCMT": "JCMT", "SPT": "SPT", "KP": "KP12", "GLT": "GREENLAND",
             "PDB": "NOEMA"}

#: The EHT array of eht-imaging's current file (arrays/EHT2025.txt) that is
#: the EHT today, and why the file's other rows are not.
EHT_NOT_CURRENT = {"CARMA": "CARMA closed in 2015; the file keeps it for simulations"}

#: EHT stations whose position the catalogue takes from eht-imaging's current
#: array file: no geodetic solution used here gives them.
EHT_POSITIONS = {"APEX", "JCMT", "SMA", "SPT", "GREENLAND", "SMT", "ALMA", "NOEMA"}

#: Pads of connected arrays in SCHED's locations.dat, by the FRAME of their
#: entries: (network, the SCHED station whose MOUNT the array's antennas share).
PADS = {
    "VLA antenna data Sep. 28, 2011 adjusted to N8 from gsfc2014a.": ("VLA", "VLA27"),
    "Calculated by offset from AT_W104 pad": ("ATCA", "ATCA"),
}

#: Pads whose position SCHED derives from another pad's: confirmed when that
#: pad is (no other source holds them).
DERIVED_FROM = {"Calculated by offset from AT_W104 pad": "AT_W104"}

#: The EVN planner's entries that are not the antenna its code first matches:
#: section -> catalogue name (names only).
PLANNER_STATIONS = {"Robledo 70": "DSS63", "Robledo 34": "DSS65A", "ARO12m": "KP12",
                    "Usuda": "USUDA64", "Tidbinbilla-70": "TIDBIN64", "VLA 27": "VLA"}

#: Other names by which users know a station (the DSN's DSS-NN names come from
#: the station names; these are common names no source file spells).
COMMON_NAMES = {
    "GBT-VLBA": ["GBT", "Green Bank 100m"],
    "DSS63": ["Robledo 70", "Madrid 70m", "DSS-63"],
    "DSS14": ["Goldstone 70m", "Mars"],
    "TIDBIN64": ["Tidbinbilla 70m", "DSS-43"],
    "KP12": ["Kitt Peak 12m", "ARO 12m"],
    "GREENLAND": ["Greenland Telescope"],
    # SCHED's PDBURE repeats NOEMA's position and is left out: its name stays.
    "NOEMA": ["PDBURE", "Plateau de Bure"],
}

#: VGOS stations (names only): the IVS VGOS network as listed by the IVS
#: Coordinating Center's station pages (https://ivscc.gsfc.nasa.gov/stations/),
#: those of them that the catalogue holds.
VGOS = {"GGAO12M", "WETTZ13S", "WETTZ13N", "ISHIOKA", "ONSA13NE", "ONSA13SW", "NYALE13N",
        "NYALE13S", "KOKEE12M", "MACGO12M", "RAEGSMAR", "RAEGYEB", "SEJONG", "AGGO",
        "HOBART12", "KATH12M", "YARRA12M", "WESTFORD"}


# A real ALMA Measurement Set (pyuvdata 3.1.3 test data, written by CASA 5.1.1's
# importasdm from the ASDM): its ANTENNA table gives the mount of ALMA's antennas.
ALMA_MS = ("ALMA Measurement Set X5707_1spw_1scan_10chan_1time_1bl_noatm.ms (pyuvdata 3.1.3 "
           "test data; CASA 5.1.1 importasdm), ANTENNA table")




def _moved(xyz, vel, epoch, to):
    if math.isnan(epoch):
        return np.array(xyz)
    return np.array(xyz) + np.array(vel) * (to - epoch) / 365.25


def build():
    locations = read_locations(SOURCES / "sched" / "locations.dat")
    older = read_locations(SOURCES / "sched" / "locations.dat.gsfc_2014a")
    older_2011 = read_locations(SOURCES / "sched" / "locations.dat.gsfc2011a")
    later_2016 = read_locations(SOURCES / "sched" / "locations_gsfc2016aplus.dat")
    axis_now = read_axistypes(SOURCES / "sched" / "locations.dat")
    axis_2005 = read_axistypes(SOURCES / "sched" / "locations.dat.2005f")
    sched = read_sched_stations(SOURCES / "sched" / "stations.dat")
    planner = read_planner(SOURCES / "vlbiplanobs" / "stations_catalog.inp")
    sources = load_sources()
    eht, eht_now = sources["eht2017"], sources["eht2025"]
    paper = read_paper(SOURCES / "paper" / "tables_1_and_3.txt")

    rows = {}  # name -> row dict

    # 1. SCHED stations, one row per position (DBNAME), in file order.
    for entry in sched:
        name = entry["dbname"] or entry["station"]
        if entry["dbname"] in locations:
            loc = locations[entry["dbname"]]
            xyz, vel, epoch, frame = loc["xyz"], loc["vel"], loc["epoch"], loc["frame"]
            where = f"{SCHED}locations.dat line {loc['line']} ({frame})"
        elif entry["xyz"] is not None:
            xyz, vel, epoch, frame = entry["xyz"], entry["vel"], entry["epoch"], entry["frame"]
            where = f"{SCHED}stations.dat line {entry['line']} ({frame or 'no frame given'})"
        else:
            continue
        code = MOUNT_CODES.get((entry["mount"] or "").upper())
        if code is None:
            continue
        row = rows.get(name)
        if row is None:
            row = rows[name] = dict(
                name=name, aliases=[], networks=set(), xyz=xyz, vel=vel, epoch=epoch,
                mount=code, focus="cassegrain", frame=frame, sched_codes=set(),
                position_source=where,
                mount_source=f"{SCHED}stations.dat line {entry['line']} "
                             f"(MOUNT={entry['mount']})",
                focus_source="", checks=[])
        row["aliases"] += [entry["station"], entry["code"] or ""]
        row["sched_codes"].add((entry["code"] or "").upper())
        if entry["station"].startswith("VLBA_"):
            row["networks"].add("VLBA")
        if entry["station"].startswith("DSS") or name.startswith("DSS"):
            row["networks"].add("DSN")
        if frame.startswith("GSFC"):
            row["networks"].add("IVS")

    # 1b. GSFC geodetic stations that stations.dat does not list (current
    # ones from locations.dat, historical ones from the 2014a solution): the
    # mount from an AXISTYPE column validated against stations.dat
    # (locations.dat, else the 2005f file), else from the EVN planner's entry
    # for the same antenna (within SAME_ANTENNA); no mount, no row.
    no_mount = []
    for file_name, entries in (("locations.dat", locations),
                               ("Master_NRAO/locations.dat.gsfc_2014a", older)):
        for name, loc in entries.items():
            if name in rows or not loc["frame"].startswith("GSFC") or \
                    (entries is older and name in locations):
                continue
            code, mount_source, dbcode, planner_code = None, "", "", None
            # locations.dat's AXISTYPE, else the IVS antenna-info file, else the
            # 2005f AXISTYPE (which writes 'altz' for some polar and X-Y mounts).
            info = sources["antinfo"].get(name)
            for axes, axes_file in ((axis_now, "locations.dat"), (None, "antinfo"),
                                    (axis_2005, "Master_NRAO/locations.dat.2005f")):
                if axes is None and info is not None and info["mount"] in ANTINFO_MOUNTS:
                    code = ANTINFO_MOUNTS[info["mount"]]
                    mount_source = f"{ANTINFO} line {info['line']} ({info['mount']})"
                    dbcode = axis_2005.get(name, ("", "", 0))[1]
                    break
                if axes is not None and name in axes:
                    axis, dbcode, line = axes[name]
                    code = AXIS_CODES.get(axis)
                    mount_source = f"{SCHED}{axes_file} line {line} (AXISTYPE={axis})"
                    break
            if code is None:
                near = [(float(np.linalg.norm(np.subtract(loc["xyz"], p["xyz"]))), i)
                        for i, p in enumerate(planner) if p.get("mount")]
                if near and min(near)[0] < SAME_ANTENNA:
                    station = planner[min(near)[1]]
                    code = MOUNT_CODES.get(station["mount"].upper())
                    planner_code = station["code"].upper()
                    mount_source = (f"{VPO} [{station['section']}] "
                                    f"(mount = {station['mount']})")
            if code is None and name in VGOS:
                code = "AZEL"
                mount_source = ("assumed: alt-az, as every VGOS antenna (the VGOS design: "
                                "fast-slewing 12-13 m alt-az antennas); no source used gives "
                                "its mount")
            if code is None:
                no_mount.append(name)
                continue
            rows[name] = dict(
                name=name, aliases=[dbcode], networks={"IVS"}, xyz=loc["xyz"], vel=loc["vel"],
                epoch=loc["epoch"], mount=code, focus="cassegrain", frame=loc["frame"],
                sched_codes={c for c in (dbcode.upper(), planner_code) if c},
                position_source=f"{SCHED}{file_name} line {loc['line']} ({loc['frame']})",
                mount_source=mount_source, focus_source="", checks=[])

    # 1c. The pads of the VLA and the ATCA in SCHED's locations.dat (the
    # antennas move between them): alt-az antennas, as SCHED's VLA and ATCA
    # stations say.
    station_line = {entry["station"]: entry["line"] for entry in sched}
    by_key = {_key(name): name for name in rows}
    for name, loc in locations.items():
        array = PADS.get(loc["frame"])
        if array is None or name in rows:
            continue
        network, station = array
        if _key(name) in by_key:  # the pad is a geodetic station (VLA-N8): one row
            rows[by_key[_key(name)]]["networks"].add(network)
            continue
        rows[name] = dict(
            name=name, aliases=[], networks={network}, xyz=loc["xyz"], vel=loc["vel"],
            epoch=loc["epoch"], mount="AZEL", focus="cassegrain", frame=loc["frame"],
            sched_codes=set(),
            position_source=f"{SCHED}locations.dat line {loc['line']} ({loc['frame']})",
            mount_source=f"{SCHED}stations.dat line {station_line[station]} ({station}: "
                         f"MOUNT=ALTAZ, the antennas of the {network})",
            focus_source="", checks=[])

    # 2. The EVN planner: networks for SCHED stations (same code, within 5 km),
    # and stations SCHED lacks.
    for station in planner:
        code = station["code"].upper()
        near = []
        for row in rows.values():
            distance = float(np.linalg.norm(np.subtract(row["xyz"], station["xyz"])))
            if distance < 5000 and (code in row["sched_codes"] or code[:2] in row["sched_codes"]):
                near.append((distance, row["name"]))
        if station["section"] in PLANNER_STATIONS and \
                PLANNER_STATIONS[station["section"]] in rows:
            row = rows[PLANNER_STATIONS[station["section"]]]
        elif near:
            row = rows[min(near)[1]]
        else:
            mount = station.get("mount")
            name = station["section"].upper().replace(" ", "")
            if name in rows:
                name = name + "_VPO"
            row = rows[name] = dict(
                name=name, aliases=[], networks=set(), xyz=station["xyz"], vel=[0.0] * 3,
                epoch=math.nan, frame="", sched_codes=set(),
                mount=MOUNT_CODES.get((mount or "").upper(), "AZEL"), focus="cassegrain",
                position_source=f"{VPO} [{station['section']}] (line {station['line']})",
                mount_source=(f"{VPO} [{station['section']}] (mount = {mount})" if mount
                              else "assumed: alt-az, as every telescope of its networks "
                                   "(the planner gives no mount)"),
                focus_source="", checks=[])
        row["planner"] = station
        row["aliases"] += [station["section"], station["code"], station["station"]]
        # The EHT tag comes from eht-imaging's current array file (step 4).
        row["networks"].update(n for n in station["networks"] if n != "EHT")

    # 3. The paper's antennas: positions of its Tables 1 and 3, mounts and
    # focus types of the paper.
    for name in PAPER_ORDER:
        mount, focus, mount_source, focus_source = PAPER_FOCUS[name]
        row = rows.get(name)
        if row is None:
            row = rows[name] = dict(name=name, aliases=[], networks=set(), frame="",
                                    sched_codes=set(), checks=[])
        if name in paper:
            table = "Table 1" if name in ("DBR205", "FD-VLBA") else "Table 3"
            row.update(xyz=paper[name], vel=[0.0] * 3, epoch=math.nan,
                       position_source=f"{PAPER} {table}")
            if table == "Table 3":
                row["networks"].update({"VGOS", "IVS"})
        row.update(mount=mount, focus=focus, mount_source=mount_source,
                   focus_source=focus_source)
        row["aliases"] += PAPER_ALIASES.get(name, [])

    # 3b. Connected arrays of pyuvdata's known telescopes: reference positions
    # and the mount pyuvdata states.
    for key, (name, where, code) in PYUVDATA_ARRAYS.items():
        entry = sources["pyuvdata"][key]
        if where == "pyuvdata":
            xyz, source = entry["xyz"], f"{PYUVDATA} line {entry['line']} ({key}: " \
                f"{entry['citation']})"
        else:
            site = sources["sites"][where.split(":")[1]]
            xyz, source = site["xyz"], f"{SITES} ({where.split(':')[1]}: {site['source']})"
        stationary = code == "GNSS"
        rows[name] = dict(
            name=name, aliases=[key], networks={name}, xyz=xyz, vel=[0.0] * 3,
            epoch=math.nan, frame="", sched_codes=set(), mount=code,
            focus="" if stationary else "cassegrain", position_source=source,
            mount_source=f"{PYUVDATA} line {entry['line']} (mount_type "
                         f"'{entry['mount_type']}'" + ("; elements fixed to the ground)"
                                                       if stationary else ")"),
            focus_source=("none: elements fixed to the ground have no focus that moves"
                          if stationary else
                          "assumed: Cassegrain; pyuvdata gives none (the ATA's offset "
                          "Gregorian optics give the same feed rotation)"),
            checks=[])

    # 4. The EHT: its current array (eht-imaging's EHT2025.txt), positions
    # of the stations no geodetic solution gives, and the focus each file states.
    for eht_name, coeff in eht_now.items():
        if eht_name in EHT_NOT_CURRENT:
            continue
        row = rows[EHT_NAMES[eht_name]]
        row["networks"].add("EHT")
        row["aliases"].append(eht_name)
        if row["name"] in DIFX_POSITIONS:
            entry = sources["difx"][DIFX_POSITIONS[row["name"]]]
            row.update(xyz=entry["xyz"], vel=[0.0] * 3, epoch=math.nan, frame="",
                       position_source=f"{DIFX} line {entry['line']} ({entry['name']})")
        elif row["name"] in EHT_POSITIONS:
            row.update(xyz=coeff["xyz"], vel=[0.0] * 3, epoch=math.nan, frame="",
                       position_source=f"{EHT2025} line {coeff['line']} ({eht_name})")
    for tag, table in (("eht2025", eht_now), ("eht2017", eht)):
        for eht_name, coeff in table.items():
            row = rows.get(EHT_NAMES.get(eht_name, ""))
            if row is None or eht_name in EHT_NOT_CURRENT or not coeff["fr_par"] or \
                    row["focus_source"] or row["name"] in PAPER_FOCUS:
                continue
            label = f"{SOURCE_TAGS[tag][0]} line {coeff['line']} ({eht_name}): " \
                    f"FR_PAR_ANGLE={coeff['fr_par']:+g}, FR_ELEV_ANGLE={coeff['fr_elev']:+g}"
            if coeff["fr_elev"]:
                side = "right" if coeff["fr_elev"] > 0 else "left"
                row["mount"] = "NASR" if side == "right" else "NASL"
                row["focus"] = f"nasmyth-{side}"
                row["mount_source"] += f"; Nasmyth from {label}"
            elif row["mount"] == "AZEL":
                row["focus"] = "cassegrain"
            row["focus_source"] = label
            if coeff["fr_offset"]:
                row["feed_offset"] = coeff["fr_offset"]
                row["feed_offset_source"] = f"{label}, FR_OFFSET={coeff['fr_offset']:g} deg"
    for row in rows.values():
        info = sources["antinfo"].get(row["name"])
        if row["focus_source"] or info is None or row["mount"] in ("NASR", "NASL", "BWG"):
            continue
        if info["focus"] == "FO_PRIM":
            row["focus"] = "prime"
            row["focus_source"] = f"{ANTINFO} line {info['line']} (FO_PRIM: prime focus)"
        elif info["focus"] == "FO_SECN":
            row["focus_source"] = (f"assumed: Cassegrain; {ANTINFO} line {info['line']} gives "
                                   "a secondary focus (FO_SECN), which may also be a Nasmyth "
                                   "or beam-waveguide one")
    for row in rows.values():
        if row["focus_source"]:
            continue
        if "VLBA" in row["networks"]:
            row["focus_source"] = ("assumed: Cassegrain, the feed position of the VLBA antenna "
                                   "design (FD-VLBA, paper Sec. 4.1)")
        elif row["mount"] in ("EQUA", "X-YE", "X-YN"):
            row["focus_source"] = ("assumed: Cassegrain or prime focus on a polar or X-Y "
                                   "mount (both give the same feed rotation)")
        else:
            row["focus_source"] = ("assumed: Cassegrain; no catalogue used gives the focus "
                                   "(a prime or Gregorian focus gives the same feed rotation; "
                                   "a Nasmyth or beam-waveguide focus would not)")

    # 5. Networks and names by name: connected arrays, the DSN, VGOS; the
    # names of the other sources that hold the station.
    for row in rows.values():
        for label in [row["name"], *row["aliases"]]:
            network = CONNECTED.get(str(label).upper().replace(" ", "")) or \
                CONNECTED.get(str(label))
            if network:
                row["networks"].add(network)
        dss = [str(a) for a in [row["name"], *row["aliases"]]
               if re.fullmatch(r"DSS[0-9]+A?", str(a))]
        if dss:
            row["networks"].add("DSN")
            row["aliases"] += [f"DSS-{d[3:].rstrip('A')}" for d in dss]
        if row["name"] in VGOS:
            row["networks"].add("VGOS")
        row["aliases"] += COMMON_NAMES.get(row["name"], [])
        row["refs"] = references(row, sources)
        row["aliases"] += [alias for ref in row["refs"]
                           for alias in source_names(sources, ref)]

    # 6. Cross-checks against every source that holds the station.
    for row in rows.values():
        row["checks"] = crosscheck(row["name"], row["xyz"], row["vel"], row["epoch"],
                                   is_geodetic(row["position_source"]), row["refs"], sources)
        row["mount_checks"] = mount_checks(row, sources)

    # A station is kept if another source confirms its position, or if its
    # position is the current GSFC VLBI solution (the best there is) and no
    # other source used holds it; a kept station must agree with every source.
    confirmed = [row for row in rows.values()
                 if any(c["status"] != "FAIL" for c in row["checks"])
                 or (not row["checks"] and "locations.dat line" in row["position_source"]
                     and row.get("frame", "").startswith("GSFC Jan. 12, 2020"))]
    confirmed += [row for row in rows.values() if row not in confirmed and
                  rows.get(DERIVED_FROM.get(row.get("frame"), "")) in confirmed]
    kept = [row for row in rows.values() if row in confirmed or row["name"] in PAPER_FOCUS]
    left_out = sorted(row["name"] for row in rows.values() if row not in kept)
    axis_checks = {
        "locations.dat": validate_axistypes(axis_now, sched),
        "Master_NRAO/locations.dat.2005f": validate_axistypes(axis_2005, sched),
    }
    return kept, left_out, sorted(no_mount), axis_checks


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
             if station == name and o in sources["casa-obs"]]
    refs += [f"sites:{s}" for s, station in SITE_NAMES.items() if station == name
             and not row["position_source"].startswith(f"{SITES} ({s}:")]
    refs += [f"difx:{k}" for k, e in sources["difx"].items()
             if (DIFX_NAMES.get(k) or DIFX_NAMES.get(e["ivs"]) or
                 next((r for r in (e["ivs"],) if r and _key(r) == _key(name)), None)) in
             (name, _key(name)) and not row["position_source"].startswith(DIFX)]
    refs += [f"pyuvdata:{k}" for k, e in sources["pyuvdata"].items()
             if "xyz" in e and PYUVDATA_NAMES.get(k) == name
             and not row["position_source"].startswith(PYUVDATA)]
    return refs


def source_record(sources, ref):
    """The record of a ``tag:key`` reference."""
    tag, key = ref.split(":", 1)
    record = sources[tag][key]
    if tag == "casa-obs":
        return dict(xyz=record, vel=[0.0] * 3, epoch=math.nan, geodetic=False)
    if tag in ("eht2017", "eht2025", "planner", "sites", "pyuvdata", "difx"):
        return dict(xyz=record["xyz"], vel=[0.0] * 3, epoch=math.nan, geodetic=False)
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
    here = _moved(xyz, vel, epoch, COMPARE_EPOCH)
    checks = []
    for ref in refs:
        other = source_record(sources, ref)
        there = _moved(other["xyz"], other["vel"], other["epoch"], COMPARE_EPOCH)
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


def _key(name):
    return re.sub(r"[^0-9A-Z]", "", str(name).upper())


def _clean_aliases(rows):
    names = {re.sub(r"[^0-9A-Z]", "", row["name"].upper()) for row in rows}
    for row in rows:
        seen, keep = {re.sub(r"[^0-9A-Z]", "", row["name"].upper())}, []
        for alias in row["aliases"]:
            key = re.sub(r"[^0-9A-Z]", "", str(alias).upper())
            if not key or key in seen or key in names:
                continue
            seen.add(key)
            keep.append(str(alias).replace(",", " "))
        row["aliases"] = keep


def largest(row):
    """The largest position difference to a source (reference points aside), or None."""
    checks = [c for c in row["checks"] if c["status"] != "reference point"]
    return max(checks, key=lambda c: c["distance"]) if checks else None


def to_table(rows):
    order = {name: i for i, name in enumerate(PAPER_ORDER)}
    rows = sorted(rows, key=lambda r: (order.get(r["name"], len(order)), r["name"]))
    _clean_aliases(rows)
    worst = [largest(row) for row in rows]
    table = Table()
    table["name"] = [row["name"] for row in rows]
    table["aliases"] = [",".join(row["aliases"]) for row in rows]
    table["networks"] = [",".join(sorted(row["networks"])) for row in rows]
    for i, axis in enumerate("xyz"):
        table[axis] = np.array([row["xyz"][i] for row in rows]) * u.m
    for i, axis in enumerate("xyz"):
        table[f"v{axis}"] = np.array([row["vel"][i] for row in rows]) * u.m / u.yr
    table["epoch"] = [row["epoch"] for row in rows]
    table["mount"] = [row["mount"] for row in rows]
    table["focus"] = [row["focus"] for row in rows]
    table["feed_offset"] = [row.get("feed_offset", 0.0) for row in rows] * u.deg
    table["position_source"] = [row["position_source"] for row in rows]
    table["mount_source"] = [row["mount_source"] for row in rows]
    table["focus_source"] = [row["focus_source"] for row in rows]
    table["feed_offset_source"] = [row.get("feed_offset_source", "") for row in rows]
    table["rotator"] = [ROTATORS.get(row["name"], ("", ""))[0] for row in rows]
    table["rotator_source"] = [ROTATORS.get(row["name"], ("", ""))[1] for row in rows]
    table["crosschecks"] = [",".join(row["refs"]) for row in rows]
    table["largest_difference"] = np.round(
        [w["distance"] if w else math.nan for w in worst], 3) * u.m
    table["largest_difference_source"] = [w["ref"] if w else "" for w in worst]
    descriptions = {
        "name": "IVS eight-character name where one exists (SCHED DBNAME)",
        "aliases": "other names, comma-separated (case and punctuation do not matter)",
        "networks": "networks the station belongs to, comma-separated",
        "x": "ITRF geocentric X at the epoch", "y": "ITRF geocentric Y at the epoch",
        "z": "ITRF geocentric Z at the epoch", "vx": "velocity in X", "vy": "velocity in Y",
        "vz": "velocity in Z", "epoch": "MJD of the position (nan: no velocity model)",
        "mount": "geodetic station-catalogue mount code",
        "focus": "focus type (see astropy_feedrot.stations.FOCUS_NAMES)",
        "feed_offset": "constant angle of the feed a source states (eht-imaging FR_OFFSET), "
                       "0 where none does; not applied by get_antenna",
        "position_source": "file and line, or paper table, of the position",
        "mount_source": "where the mount comes from",
        "focus_source": "where the focus comes from, or 'assumed: <reason>'",
        "feed_offset_source": "where the feed offset comes from",
        "rotator": "field rotator mode (sky: the feed keeps its angle on the sky), or empty",
        "rotator_source": "where the rotator comes from",
        "crosschecks": "the other sources that hold the station (tag:key, comma-separated; "
                       "see catalogue/build_stations.py SOURCE_TAGS)",
        "largest_difference": "largest distance to another source's position at 2020.0 "
                              "(reference points aside)",
        "largest_difference_source": "the source of that largest distance",
    }
    for column, text in descriptions.items():
        table[column].description = text
    table.meta["description"] = (
        "The world's VLBI and millimetre stations and the reference positions of connected "
        "arrays, built by catalogue/build_stations.py from the public files in "
        "catalogue/sources (see its README). The antennas of the paper come first, with "
        "the paper's positions (Tables 1 and 3), mounts and mirror trains (Appendix C).")
    return table


def report(rows, left_out, no_mount, axis_checks):
    lines = ["Cross-check of the station catalogue: each position against every other "
             "source that holds the station, both moved to 2020.0.", "", "Tolerances:"]
    for kind, (tol, what) in TOLERANCES.items():
        lines.append(f"  {kind:9s} {tol:6.1f} m  {what}")
    lines += ["", "Sources (tag: file):"]
    lines += [f"  {tag:10s} {name}" for tag, (name, _) in SOURCE_TAGS.items()]
    lines += ["", summary(rows), "",
              "Exceptions beyond the tolerance (station, source: limit, reason):"]
    lines += [f"  {s:10s} {t:10s} {limit:8.1f} m  {why}"
              for (s, t), (limit, why) in sorted(EXCEPTIONS.items())]
    lines += ["", "Reference points (station, source: what the source's position is):"]
    lines += [f"  {s:10s} {t:10s} {limit:8.0f} m  {why}"
              for (s, t), (limit, why) in sorted(REFERENCE_POINTS.items())]
    lines += ["", "Mount and focus statements not followed (station, source: reason):"]
    lines += [f"  {s:10s} {t:10s} {why}" for (s, t), why in sorted(MOUNT_EXCEPTIONS.items())]
    lines += ["", "Every comparison (station, source, kind, distance in m, status):"]
    for row in sorted(rows, key=lambda r: r["name"]):
        for c in row["checks"]:
            lines.append(f"  {row['name']:12s} {c['ref']:28s} {c['kind']:9s} "
                         f"{c['distance']:12.3f}  {c['status']}")
        for ref, stated, status, _ in row["mount_checks"]:
            lines.append(f"  {row['name']:12s} {ref:28s} {stated:9s} (catalogue: "
                         f"{row['mount']} {row['focus'] or '-'})  {status}")
    single = sorted(row["name"] for row in rows if not row["checks"])
    lines += ["", "Kept with one source (the current GSFC solution, the paper, or an ATCA pad "
              "that SCHED derives from AT_W104; no other source used holds them): "
              + (", ".join(single) or "none")]
    lines += ["", "Left out (no other source confirms the position): "
              + (", ".join(left_out) or "none")]
    lines += ["", "Left out (GSFC geodetic stations whose mount no source gives): "
              + (", ".join(no_mount) or "none")]
    lines += ["", "AXISTYPE columns used for mounts, against stations.dat MOUNT on the stations "
              "both give:"]
    for name, (agree, disagree) in axis_checks.items():
        lines.append(f"  {SCHED}{name}: {agree} agree, {len(disagree)} disagree"
                     + "".join(f"; {n} {a} vs {m}" for n, a, m in disagree))
    return "\n".join(lines) + "\n"


def summary(rows):
    """Stations per source, median and largest difference per class, disagreements."""
    lines = ["Stations per source:"]
    for tag in SOURCE_TAGS:
        n = sum(any(c["ref"].startswith(f"{tag}:") for c in row["checks"]) for row in rows)
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
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default=str(OUTPUT))
    parser.add_argument("--report", default=str(REPORT))
    args = parser.parse_args(argv)
    rows, left_out, no_mount, axis_checks = build()
    mounts = read_ms_mounts(SOURCES / "alma_ms" / "ANTENNA")
    for row in rows:
        if row["name"] == "ALMA" and mounts == ["ALT-AZ"]:
            row["mount"] = "AZEL"
            row["mount_source"] = f"{ALMA_MS}: MOUNT 'ALT-AZ' for its antennas DA41, DA42"
    failed = failures(rows)
    if failed:
        print("Unexplained disagreements (fix the row, or list the reason in "
              "EXCEPTIONS, REFERENCE_POINTS or MOUNT_EXCEPTIONS):\n  " + "\n  ".join(failed),
              file=sys.stderr)
        return 1
    table = to_table(rows)
    table.write(args.output, format="ascii.ecsv", overwrite=True)
    Path(args.report).write_text(report(rows, left_out, no_mount, axis_checks))
    print(summary(rows))
    print(f"{len(table)} stations written to {args.output}; {len(left_out)} left out")
    return 0


if __name__ == "__main__":
    sys.exit(main())
