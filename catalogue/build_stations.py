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

HERE = Path(__file__).resolve().parent
SOURCES = HERE / "sources"
ROOT = HERE.parent
OUTPUT = ROOT / "astropy_feedrot" / "data" / "stations.ecsv"
REPORT = HERE / "crosscheck.txt"

SCHED = "SCHED 1.29.1 catalogs/"          # pythonsched 1.29.1 (PyPI)
VPO = "vlbiplanobs 4.9.2 data/stations_catalog.inp"
CASA = "casadata 2025.9.22 geodetic/Observatories"
EHTIM = "eht-imaging arrays/EHT2017.txt (commit 1b5dc2c)"
PAPER = "paper"

#: Common epoch (MJD, 2020 Jan 1) at which two geodetic solutions are compared.
COMPARE_EPOCH = 58849.0

#: Epoch of the paper's simulations (2023 Jan 25, MJD).
PAPER_EPOCH = 59969.0

#: Tolerance of each kind of cross-check (metres), and what it compares.
TOLERANCES = {
    "paper": (0.50, "the paper's Tables 1 and 3 vs SCHED's GSFC position moved to 2023 Jan 25"),
    "geodetic": (0.10, "one GSFC solution vs an older one (2014a, else 2011a, else 2016a), "
                       "both moved to 2020.0"),
    "geodetic-seismic": (1.5, "as geodetic, for stations of eastern Japan whose difference is "
                              "eastward: the 2011 Mar 11 Tohoku earthquake, whose jump and "
                              "post-seismic motion the two solutions model differently"),
    "planner": (150.0, "one telescope in two compiled catalogues (SCHED vs the EVN planner)"),
    "eht": (150.0, "one telescope in SCHED or the EVN planner vs eht-imaging's EHT2017 file"),
    "observatory": (3000.0, "a telescope or connected array vs casacore's observatory "
                            "reference position (array centre, rounded coordinates)"),
}

#: SCHED's MOUNT values and the geodetic codes of astropy_feedrot.labels.
MOUNT_CODES = {"ALTAZ": "AZEL", "EQUAT": "EQUA", "XYEW": "X-YE", "XYNS": "X-YN"}

#: AXISTYPE values of SCHED's locations files (SPAC, a tracking station, has no code here).
AXIS_CODES = {"ALTZ": "AZEL", "ALTAZ": "AZEL", "ALTA": "AZEL", "EQUA": "EQUA",
              "XYEW": "X-YE", "XYNS": "X-YN"}

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
    "ALMA": "ALMA", "ATCA": "ATCA", "GMRT": "GMRT", "SMA": "SMA", "VLA": "VLA",
    "ASKAP": "ASKAP", "MeerKAT": "MEERKAT", "NOEMA": "NOEMA", "APEX": "APEX", "SMT": "SMT",
    "JCMT": "JCMT", "PKS": "PARKES", "MOPRA": "MOPRA", "ARECIBO": "ARECIBO",
    "GBT": "GBT-VLBA", "Effelsberg": "EFLSBERG", "WSRT": "WB_RT1", "NRO": "NOBEY_45",
    "FAST": "FAST", "IRAM_PDB": "PDBURE",
}

#: Connected arrays: the network name given to a station by its name.
CONNECTED = {"VLA": "VLA", "ALMA": "ALMA", "ATCA": "ATCA", "SMA": "SMA", "NOEMA": "NOEMA",
             "PDBURE": "NOEMA", "MEERKAT": "MeerKAT", "GMRT": "GMRT", "ASKAP": "ASKAP",
             "ASKAP32": "ASKAP", "GMRT_C02": "GMRT", "AT_W104": "ATCA"}

#: eht-imaging EHT2017 station names -> SCHED or planner codes (names only).
EHT_NAMES = {"PV": "Pv", "SMT": "Mg", "SMA": "Sw", "LMT": "Lm", "ALMA": "ALMA",
             "APEX": "Ap", "JCMT": "Jc", "SPT": "Sz"}


def _numbers(text, key):
    found = re.search(rf"\b{key}\s*=\s*([-+0-9.eE]+)", text)
    return float(found[1]) if found else None


def sched_blocks(path):
    """(text, first line number) of each ``/``-terminated entry, comments removed."""
    blocks, current, start = [], [], None
    for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
        line = line.split("!")[0]
        if not line.strip():
            continue
        if start is None:
            start = number
        if line.strip() == "/":
            blocks.append((" ".join(current), start))
            current, start = [], None
        else:
            current.append(line)
    return blocks


def _word(text, key):
    found = re.search(rf"\b{key}\s*=\s*'([^']*)'|\b{key}\s*=\s*(\S+)", text)
    if not found:
        return None
    return (found[1] if found[1] is not None else found[2]).strip()


def read_locations(path):
    """DBNAME -> the entry valid now (END 100000, latest BEGIN)."""
    entries = {}
    for text, line in sched_blocks(path):
        name = _word(text, "DBNAME")
        x = _numbers(text, "X")
        end = _numbers(text, "END")
        if name is None or x is None or (end is not None and end < 99999):
            continue
        begin = _numbers(text, "BEGIN") or 0
        if name in entries and entries[name]["begin"] > begin:
            continue
        vel = [_numbers(text, k) for k in ("DXDT", "DYDT", "DZDT")]
        entries[name] = dict(
            begin=begin, xyz=[x, _numbers(text, "Y"), _numbers(text, "Z")],
            vel=vel if None not in vel else [0.0, 0.0, 0.0],
            epoch=_numbers(text, "EPOCH") if None not in vel else math.nan,
            frame=_word(text, "FRAME") or "", line=line)
    return entries


def read_axistypes(path):
    """DBNAME -> (AXISTYPE, DBCODE or '', line) of a locations file that gives them."""
    found = {}
    for text, line in sched_blocks(path):
        name, axis = _word(text, "DBNAME"), _word(text, "AXISTYPE")
        if name and axis:
            found.setdefault(name, (axis.upper(), _word(text, "DBCODE") or "", line))
    return found


def validate_axistypes(axistypes, sched):
    """Compare an AXISTYPE column with stations.dat's MOUNT: (agreements, disagreements)."""
    mounts = {}
    for entry in sched:
        if entry["dbname"] and entry["mount"]:
            mounts.setdefault(entry["dbname"], set()).add(
                MOUNT_CODES.get(entry["mount"].upper(), entry["mount"].upper()))
    agree, disagree = 0, []
    for name, (axis, _, line) in sorted(axistypes.items()):
        if name in mounts:
            if AXIS_CODES.get(axis, axis) in mounts[name]:
                agree += 1
            else:
                disagree.append((name, axis, sorted(mounts[name])))
    return agree, disagree


def read_sched_stations(path):
    """SCHED station entries in file order."""
    stations = []
    for text, line in sched_blocks(path):
        name = _word(text, "STATION")
        if name is None:
            continue
        xyz = [_numbers(text, k) for k in ("X", "Y", "Z")]
        vel = [_numbers(text, k) for k in ("DXDT", "DYDT", "DZDT")]
        stations.append(dict(
            station=name, code=_word(text, "STCODE"), dbname=_word(text, "DBNAME"),
            mount=_word(text, "MOUNT"), line=line, frame=_word(text, "FRAME") or "",
            xyz=xyz if None not in xyz else None,
            vel=vel if None not in vel else [0.0, 0.0, 0.0],
            epoch=_numbers(text, "EPOCH") if None not in vel else math.nan))
    return stations


def read_planner(path):
    """The EVN planner's stations: [section] blocks of ``key = value``."""
    stations, current = [], None
    for number, line in enumerate(path.read_text().splitlines(), 1):
        line = line.split("#")[0].rstrip()
        if line.startswith("["):
            current = {"section": line.strip("[]"), "line": number}
            stations.append(current)
        elif "=" in line and current is not None:
            key, value = line.split("=", 1)
            current[key.strip()] = value.strip()
    for station in stations:
        station["xyz"] = [float(v) for v in station["position"].split(",")]
        station["networks"] = [n.strip() for n in station.get("networks", "").split(",")
                               if n.strip()]
    return stations


def read_observatories(path):
    """casacore's Observatories table: name -> ITRF position (m)."""
    from casacore.tables import table  # optional: python-casacore

    found = {}
    with table(str(path), ack=False) as tab:
        for row in tab:
            lon, lat, height = row["Long"], row["Lat"], row["Height"]
            if row["Type"] == "ITRF":  # spherical geocentric, Height is the radius
                if height < 6e6:
                    continue
                lon_r, lat_r = math.radians(lon), math.radians(lat)
                xyz = [height * math.cos(lat_r) * math.cos(lon_r),
                       height * math.cos(lat_r) * math.sin(lon_r), height * math.sin(lat_r)]
            else:
                loc = EarthLocation.from_geodetic(lon * u.deg, lat * u.deg, height * u.m)
                xyz = [float(v.to_value(u.m)) for v in (loc.x, loc.y, loc.z)]
            found.setdefault(row["Name"], xyz)
    return found


def read_eht(path):
    rows = {}
    for line in path.read_text().splitlines():
        if line.startswith("#") or not line.strip():
            continue
        parts = line.split()
        rows[parts[0]] = dict(xyz=[float(v) for v in parts[1:4]],
                              fr_par=float(parts[6]), fr_elev=float(parts[7]))
    return rows


def read_paper(path):
    rows = {}
    for line in path.read_text().splitlines():
        parts = [p.strip() for p in line.strip().strip("|").split("|")]
        if len(parts) == 5 and re.fullmatch(r"[-−]?[0-9]+\.[0-9]+", parts[2]):
            rows[parts[0]] = [float(p.replace("−", "-")) for p in parts[2:]]
    return rows


def read_ms_mounts(path):
    """The MOUNT strings of a Measurement Set's ANTENNA table (python-casacore)."""
    from casacore.tables import table  # optional: python-casacore

    with table(str(path), ack=False) as tab:
        return sorted(set(tab.getcol("MOUNT")))


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
    observatories = read_observatories(SOURCES / "casadata" / "Observatories")
    eht = read_eht(SOURCES / "eht-imaging" / "EHT2017.txt")
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
            for axes, axes_file in ((axis_now, "locations.dat"),
                                    (axis_2005, "Master_NRAO/locations.dat.2005f")):
                if name in axes:
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
            if code is None:
                no_mount.append(name)
                continue
            rows[name] = dict(
                name=name, aliases=[dbcode], networks={"IVS"}, xyz=loc["xyz"], vel=loc["vel"],
                epoch=loc["epoch"], mount=code, focus="cassegrain", frame=loc["frame"],
                sched_codes={c for c in (dbcode.upper(), planner_code) if c},
                position_source=f"{SCHED}{file_name} line {loc['line']} ({loc['frame']})",
                mount_source=mount_source, focus_source="", checks=[])

    # 2. The EVN planner: networks for SCHED stations (same code, within 5 km),
    # and stations SCHED lacks.
    for station in planner:
        code = station["code"].upper()
        near = []
        for row in rows.values():
            distance = float(np.linalg.norm(np.subtract(row["xyz"], station["xyz"])))
            if distance < 5000 and (code in row["sched_codes"] or code[:2] in row["sched_codes"]):
                near.append((distance, row["name"]))
        if near:
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
        row["networks"].update(n for n in station["networks"])

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

    # 4. Focus types: eht-imaging's feed-rotation coefficients (Nasmyth
    # stations), else assumed.
    by_code = {}
    for row in rows.values():
        codes = set(row["sched_codes"])
        if "planner" in row:
            codes.add(row["planner"]["code"].upper())
        for code in codes:
            by_code.setdefault(code, []).append(row["name"])
    for eht_name, code in EHT_NAMES.items():
        targets = by_code.get(code.upper(), [])
        if len(targets) != 1 or eht_name not in eht:
            continue
        row = rows[targets[0]]
        coeff = eht[eht_name]
        if coeff["fr_elev"] and row["mount"] == "AZEL":
            side = "right" if coeff["fr_elev"] > 0 else "left"
            row["mount"] = "NASR" if side == "right" else "NASL"
            row["focus"] = f"nasmyth-{side}"
            row["mount_source"] += (f"; Nasmyth from {EHTIM} FR_ELEV_ANGLE="
                                    f"{coeff['fr_elev']:+g}")
            row["focus_source"] = f"{EHTIM}: FR_ELEV_ANGLE={coeff['fr_elev']:+g}"
        row["eht"] = coeff
        row["aliases"].append(eht_name)
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

    # 5. Connected arrays and the DSN by name.
    for row in rows.values():
        for label in [row["name"], *row["aliases"]]:
            network = CONNECTED.get(str(label).upper().replace(" ", "")) or \
                CONNECTED.get(str(label))
            if network:
                row["networks"].add(network)
        if "DSS" in row["name"] or any(str(a).startswith("DSS") for a in row["aliases"]):
            row["networks"].add("DSN")

    # 6. Cross-checks, best second catalogue first.
    observatory_of = {}
    for obs_name, station in OBSERVATORY_NAMES.items():
        observatory_of.setdefault(station, []).append(obs_name)
    for row in rows.values():
        xyz = np.array(row["xyz"], dtype=float)
        if row.get("position_source", "").startswith(PAPER) and row["name"] in locations:
            other = locations[row["name"]]
            there = _moved(other["xyz"], other["vel"], other["epoch"], PAPER_EPOCH)
            row["checks"].append(("paper", float(np.linalg.norm(xyz - there)),
                                  f"{SCHED}locations.dat line {other['line']}"))
        label_set = {str(a).upper() for a in [row["name"], *row["aliases"]]}
        # One other GSFC solution (never a choice among several): 2014a,
        # else 2011a, else 2016a, the first that lists the station from a
        # solution other than the position's own.
        if row["frame"].startswith("GSFC"):
            for other_file, solution in (("locations.dat.gsfc_2014a", older),
                                         ("locations.dat.gsfc2011a", older_2011),
                                         ("locations_gsfc2016aplus.dat", later_2016)):
                other = solution.get(row["name"])
                if other is None or other["frame"] == row["frame"] or \
                        other["frame"].startswith("VLA"):
                    continue
                here = _moved(xyz, row["vel"], row["epoch"], COMPARE_EPOCH)
                there = _moved(other["xyz"], other["vel"], other["epoch"], COMPARE_EPOCH)
                kind = "geodetic-seismic" if row["name"] in TOHOKU else "geodetic"
                row["checks"].append((kind, float(np.linalg.norm(here - there)),
                                      f"{SCHED}Master_NRAO/{other_file} line "
                                      f"{other['line']}"))
                break
        if "planner" in row and not row["position_source"].startswith(VPO):
            row["checks"].append(("planner", float(np.linalg.norm(
                xyz - row["planner"]["xyz"])), f"{VPO} [{row['planner']['section']}]"))
        if "eht" in row and row["eht"]["xyz"][0] != 0.01:
            row["checks"].append(("eht", float(np.linalg.norm(xyz - row["eht"]["xyz"])),
                                  EHTIM))
        for obs_name, station in OBSERVATORY_NAMES.items():
            if station.upper() in label_set and obs_name in observatories:
                row["checks"].append(("observatory", float(np.linalg.norm(
                    xyz - observatories[obs_name])), f"{CASA} ({obs_name})"))

    # Stations whose position no second catalogue confirms are left out.
    # The paper's antennas are kept with the paper as their source even where
    # no catalogue used here lists them (DBR205, a GNSS antenna; GGAO12M and
    # WETTZ13S, whose SCHED names differ).
    kept = [row for row in rows.values() if _best(row) is not None or row["name"] in PAPER_FOCUS]
    left_out = sorted(row["name"] for row in rows.values()
                      if _best(row) is None and row["name"] not in PAPER_FOCUS)
    mount_checks = {
        "locations.dat": validate_axistypes(axis_now, sched),
        "Master_NRAO/locations.dat.2005f": validate_axistypes(axis_2005, sched),
    }
    return kept, left_out, sorted(no_mount), mount_checks


def _best(row):
    """The first comparison, in the order of TOLERANCES, within its tolerance."""
    within = [c for c in row["checks"] if c[1] <= TOLERANCES[c[0]][0]]
    if not within:
        return None
    return min(within, key=lambda c: list(TOLERANCES).index(c[0]))


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


def to_table(rows):
    order = {name: i for i, name in enumerate(PAPER_ORDER)}
    rows = sorted(rows, key=lambda r: (order.get(r["name"], len(order)), r["name"]))
    _clean_aliases(rows)
    best = [_best(row) or ("none", math.nan, "none: the paper is the only source")
            for row in rows]
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
    table["position_source"] = [row["position_source"] for row in rows]
    table["mount_source"] = [row["mount_source"] for row in rows]
    table["focus_source"] = [row["focus_source"] for row in rows]
    table["rotator"] = [ROTATORS.get(row["name"], ("", ""))[0] for row in rows]
    table["rotator_source"] = [ROTATORS.get(row["name"], ("", ""))[1] for row in rows]
    table["check_kind"] = [c[0] for c in best]
    table["check_distance"] = np.round([c[1] for c in best], 4) * u.m
    table["check_tolerance"] = [TOLERANCES.get(c[0], (math.nan,))[0] for c in best] * u.m
    table["check_source"] = [c[2] for c in best]
    descriptions = {
        "name": "IVS eight-character name where one exists (SCHED DBNAME)",
        "aliases": "other names, comma-separated (case and punctuation do not matter)",
        "networks": "networks the station belongs to, comma-separated",
        "x": "ITRF geocentric X at the epoch", "y": "ITRF geocentric Y at the epoch",
        "z": "ITRF geocentric Z at the epoch", "vx": "velocity in X", "vy": "velocity in Y",
        "vz": "velocity in Z", "epoch": "MJD of the position (nan: no velocity model)",
        "mount": "geodetic station-catalogue mount code",
        "focus": "focus type (see astropy_feedrot.stations.FOCUS_NAMES)",
        "position_source": "file and line, or paper table, of the position",
        "mount_source": "where the mount comes from",
        "focus_source": "where the focus comes from, or 'assumed: <reason>'",
        "rotator": "field rotator mode (sky: the feed keeps its angle on the sky), or empty",
        "rotator_source": "where the rotator comes from",
        "check_kind": "kind of the second, independent catalogue position",
        "check_distance": "distance to the second catalogue's position",
        "check_tolerance": "tolerance of that kind of comparison",
        "check_source": "the second catalogue",
    }
    for column, text in descriptions.items():
        table[column].description = text
    table.meta["description"] = (
        "The world's VLBI and millimetre stations and the reference positions of connected "
        "arrays, built by catalogue/build_stations.py from the public files in "
        "catalogue/sources (see its README). The antennas of the paper come first, with "
        "the paper's positions (Tables 1 and 3), mounts and mirror trains (Appendix C).")
    return table


def report(rows, left_out, no_mount, mount_checks):
    lines = ["Cross-check of the station catalogue: each position against a second, "
             "independent catalogue.", "", "Tolerances:"]
    for kind, (tol, what) in TOLERANCES.items():
        lines.append(f"  {kind:16s} {tol:8.2f} m  {what}")
    lines.append("")
    for kind in TOLERANCES:
        d = np.array([c[1] for row in rows for c in row["checks"] if c[0] == kind])
        if d.size:
            lines.append(f"{kind:16s} n={d.size:4d}  median {np.median(d):10.3f} m  "
                         f"max {d.max():10.3f} m  over tolerance "
                         f"{int(np.sum(d > TOLERANCES[kind][0]))}")
    lines += ["", "Every comparison (station, kind, distance in m, within tolerance):"]
    for row in sorted(rows, key=lambda r: r["name"]):
        for kind, distance, where in row["checks"]:
            ok = "ok" if distance <= TOLERANCES[kind][0] else "OVER"
            lines.append(f"  {row['name']:12s} {kind:16s} {distance:12.3f}  {ok:4s}  {where}")
    lines += ["", "Left out (no second catalogue confirms the position within tolerance): "
              + (", ".join(left_out) or "none")]
    lines += ["", "Left out (GSFC geodetic stations whose mount no source gives): "
              + (", ".join(no_mount) or "none")]
    lines += ["", "AXISTYPE columns used for mounts, against stations.dat MOUNT on the stations "
              "both give:"]
    for name, (agree, disagree) in mount_checks.items():
        lines.append(f"  {SCHED}{name}: {agree} agree, {len(disagree)} disagree"
                     + "".join(f"; {n} {a} vs {m}" for n, a, m in disagree))
    return "\n".join(lines) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default=str(OUTPUT))
    parser.add_argument("--report", default=str(REPORT))
    args = parser.parse_args(argv)
    rows, left_out, no_mount, mount_checks = build()
    mounts = read_ms_mounts(SOURCES / "alma_ms" / "ANTENNA")
    for row in rows:
        if row["name"] == "ALMA" and mounts == ["ALT-AZ"]:
            row["mount"] = "AZEL"
            row["mount_source"] = f"{ALMA_MS}: MOUNT 'ALT-AZ' for its antennas DA41, DA42"
    table = to_table(rows)
    table.write(args.output, format="ascii.ecsv", overwrite=True)
    Path(args.report).write_text(report(rows, left_out, no_mount, mount_checks))
    print(f"{len(table)} stations written to {args.output}; {len(left_out)} left out",
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
