# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Build ``astropy_feedrot/data/stations.ecsv`` from the public files in ``catalogue/sources``.

Run from the repository root::

    python catalogue/build_stations.py            # writes the package's stations.ecsv
    python catalogue/build_stations.py --output X.ecsv --report Y.txt

Nothing here types a coordinate: every position is read from a saved source
file (see ``catalogue/sources/README.rst``), and every position, mount and
focus is compared with every other source that holds the station
(``checks.py``); the comparison goes to ``catalogue/crosscheck.txt`` and a
summary to the terminal. Any disagreement that ``checks.py`` does not list
with its reason stops the build (exit status 1, nothing written). Reading
casacore's tables needs python-casacore.
"""

import argparse
import math
import re
import sys
from pathlib import Path

import numpy as np
from astropy import units as u
from astropy.table import Table
from checks import (
    ANTINFO,
    ANTINFO_MOUNTS,
    CASA,
    DIFX,
    EHT2025,
    EHT_NAMES,
    EHT_NOT_CURRENT,
    EXCEPTIONS,
    MEERKAT_DISHES,
    MEERKAT_EXTENT,
    MOUNT_EXCEPTIONS,
    PAPER,
    PYUVDATA,
    REFERENCE_POINTS,
    SCHED,
    SIMMS,
    SINGLE_SOURCE,
    SITES,
    SKED,
    SKED_GEODETIC,
    SKED_MOUNTS,
    SOURCE_TAGS,
    SOURCES,
    TOLERANCES,
    VPO,
    crosscheck,
    failures,
    is_geodetic,
    load_sources,
    mount_checks,
    name_key,
    references,
    source_names,
    summary,
)
from readers import (
    AXIS_CODES,
    MOUNT_CODES,
    read_axistypes,
    read_locations,
    read_ms_mounts,
    read_paper,
    read_planner,
    read_pyuvdata_telescopes,
    read_sched_stations,
    validate_axistypes,
)
from station_receptors import receptor_statements

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
OUTPUT = ROOT / "astropy_feedrot" / "data" / "stations.ecsv"
REPORT = HERE / "crosscheck.txt"


#: Epoch of the paper's simulations (2023 Jan 25, MJD).
PAPER_EPOCH = 59969.0


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


#: Connected arrays of pyuvdata's known telescopes: name -> (catalogue name,
#: the source of the position, why the mount code). A ``fixed`` or ``phased``
#: array's elements are fixed to the ground: the geodetic code GNSS, a
#: stationary antenna (astropy_feedrot.stations.labels reads pyuvdata's ``fixed`` so).
PYUVDATA_ARRAYS = {
    "ATA": ("ATA", "pyuvdata", "AZEL"),
    "HERA": ("HERA", "pyuvdata", "GNSS"),
    "OVRO-LWA": ("OVRO-LWA", "pyuvdata", "GNSS"),
    "MWA": ("MWA", "sites:mwa", "GNSS"),  # pyuvdata takes MWA's location from astropy
}


#: Stations whose position the catalogue takes from DiFX's antenna_db (the
#: only source used that holds them off the pole): name -> DiFX name.
DIFX_POSITIONS = {"SPT": "South Pole"}


#: Connected arrays: the network name given to a station by its name.
CONNECTED = {"VLA": "VLA", "ALMA": "ALMA", "ATCA": "ATCA", "SMA": "SMA", "NOEMA": "NOEMA",
             "PDBURE": "NOEMA", "MEERKAT": "MeerKAT", "GMRT": "GMRT", "ASKAP": "ASKAP",
             "ASKAP32": "ASKAP", "GMRT_C02": "GMRT", "AT_W104": "ATCA"}


#: EHT stations whose position the catalogue takes from eht-imaging's current
#: array file: no geodetic solution used here gives them.
EHT_POSITIONS = {"APEX", "JCMT", "SMA", "SPT", "GREENLAND", "SMT", "ALMA", "NOEMA"}

#: Stations the catalogue must hold: the EHT's current array and the DSN's
#: 70 m antennas. The build fails if the cross-check leaves one out.
REQUIRED = {*(name for code, name in EHT_NAMES.items() if code not in EHT_NOT_CURRENT),
            "DSS14", "TIDBIN64", "DSS63"}

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
    "KOKEE12M": ["Kokee 12m"],
    "MACGO12M": ["McDonald 12m", "MGO 12m"],
    "ONSA13SW": ["Onsala 13SW", "Onsala twin SW"],
    "ONSA13NE": ["Onsala 13NE", "Onsala twin NE"],
    "NYALE13N": ["Ny-Alesund 13N"],
    "NYALE13S": ["Ny-Alesund 13S"],
    "SESHAN13": ["Sheshan 13m", "Seshan 13m"],
    "TIANMA13": ["Tianma 13m"],
    "NOBEYA45": ["Nobeyama 45m", "NRO 45m", "NRO"],
    "BADRT13V": ["BADAR13M", "Badary 13m"],
    "ZELRT13V": ["ZELEN13M", "Zelenchukskaya 13m"],
}

#: Stations that SCHED's files lack, and the source of their position:
#: name -> (source tag, key). sked's position.cat (the IVS scheduling
#: catalogue) holds the VGOS antennas, casacore's Observatories Nobeyama's 45 m
#: (sked's NOBEYA45 is the 6 m antenna's position: see checks.py), DiFX's antenna_db
#: the Russian 13 m VGOS antennas (under their DiFX names BADAR13M and
#: ZELEN13M; the IVS names are antenna-info's). Their mounts come from sked's
#: antenna.cat, else from antenna-info.
OTHER_POSITIONS = {
    "KOKEE12M": ("sked", "KOKEE12M"), "MACGO12M": ("sked", "MACGO12M"),
    "ONSA13SW": ("sked", "ONSA13SW"), "NYALE13N": ("sked", "NYALE13N"),
    "SESHAN13": ("sked", "SESHAN13"), "TIANMA13": ("sked", "TIANMA13"),
    "NOBEYA45": ("casa-obs", "NRO"),
    "BADRT13V": ("difx", "Badary 13m"), "ZELRT13V": ("difx", "Zelenchukskya13"),
}

#: VGOS stations (names only, their IVS names; no source used here lists the
#: network): the broadband antennas of the IVS's VGOS network that the
#: catalogue holds. AGGO (6 m) and SEJONG (22 m; antenna-info gives both) are
#: S/X antennas, not VGOS ones, and are not tagged.
VGOS = {"GGAO12M", "WETTZ13S", "WETTZ13N", "ISHIOKA", "ONSA13NE", "ONSA13SW", "NYALE13N",
        "NYALE13S", "KOKEE12M", "MACGO12M", "RAEGSMAR", "RAEGYEB", "HOBART12", "KATH12M",
        "YARRA12M", "WESTFORD", "SESHAN13", "TIANMA13", "BADRT13V", "ZELRT13V"}


# A real ALMA Measurement Set (pyuvdata 3.1.3 test data, written by CASA 5.1.1's
# importasdm from the ASDM): its ANTENNA table gives the mount of ALMA's antennas.
ALMA_MS = ("ALMA Measurement Set X5707_1spw_1scan_10chan_1time_1bl_noatm.ms (pyuvdata 3.1.3 "
           "test data; CASA 5.1.1 importasdm), ANTENNA table")


def build():
    locations = read_locations(SOURCES / "sched" / "locations.dat")
    older = read_locations(SOURCES / "sched" / "locations.dat.gsfc_2014a")
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
    by_key = {name_key(name): name for name in rows}
    for name, loc in locations.items():
        array = PADS.get(loc["frame"])
        if array is None:
            continue
        network, station = array
        # A pad that is also a station (VLA_E8, SCHED's VLA1; VLA-N8, a geodetic
        # station): one row, in the array's network too.
        if name in rows or name_key(name) in by_key:
            rows[name if name in rows else by_key[name_key(name)]]["networks"].add(network)
            continue
        rows[name] = dict(
            name=name, aliases=[], networks={network}, xyz=loc["xyz"], vel=loc["vel"],
            epoch=loc["epoch"], mount="AZEL", focus="cassegrain", frame=loc["frame"],
            sched_codes=set(),
            position_source=f"{SCHED}locations.dat line {loc['line']} ({loc['frame']})",
            mount_source=f"{SCHED}stations.dat line {station_line[station]} ({station}: "
                         f"MOUNT=ALTAZ, the antennas of the {network})",
            focus_source="", checks=[])

    # 1d. Stations SCHED's files lack (OTHER_POSITIONS): the position from
    # sked's position.cat or DiFX's antenna_db, the mount from sked's
    # antenna.cat or the IVS antenna-info file.
    for name, (tag, key) in OTHER_POSITIONS.items():
        if name in rows:
            continue
        entry = sources[tag][key]
        if tag == "sked":
            origin = entry["origin"]
            solution = SKED_GEODETIC.match(origin)
            if solution:
                epoch = ", epoch 2021.0" if solution[1] == "2020c" else ""
                frame = f"GSFC solution {solution[1]}{epoch}"
            else:
                frame = origin
            where = f"{SKED}position.cat line {entry['line']} ({frame})"
            codes = {entry["code"].upper()}
        elif tag == "casa-obs":
            entry = dict(xyz=entry)
            where = f"{CASA} ({key})"
            codes = set()
        else:
            where = f"{DIFX} line {entry['line']} ({entry['name']})"
            codes = set()
        antenna, info = sources["sked-ant"].get(name), sources["antinfo"].get(name)
        if antenna is not None and antenna["axis"] in SKED_MOUNTS:
            code = SKED_MOUNTS[antenna["axis"]]
            mount_source = f"{SKED}antenna.cat line {antenna['line']} ({antenna['axis']})"
        else:
            code = ANTINFO_MOUNTS[info["mount"]]
            mount_source = f"{ANTINFO} line {info['line']} ({info['mount']})"
        rows[name] = dict(
            name=name, aliases=[entry["code"]] if tag == "sked" else [], networks={"IVS"},
            xyz=entry["xyz"], vel=[0.0] * 3, epoch=math.nan, mount=code, focus="cassegrain",
            frame="", sched_codes=codes, position_source=where, mount_source=mount_source,
            focus_source="", checks=[])

    # 1e. The dishes of MeerKAT (simms's layout): alt-az, as the file says.
    for name, entry in sources["simms"].items():
        rows[name] = dict(
            name=name, aliases=[], networks={"MeerKAT"}, xyz=entry["xyz"], vel=[0.0] * 3,
            epoch=math.nan, mount=MOUNT_CODES.get(entry["mount"].replace("-", "")),
            focus="cassegrain", frame="", sched_codes=set(),
            position_source=f"{SIMMS} line {entry['line']} ({name})",
            mount_source=f"{SIMMS} line {entry['line']} ({entry['mount']})",
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
        if row["name"] in SINGLE_SOURCE:
            row["position_source"] += f"; single source: {SINGLE_SOURCE[row['name']]}"
        if row["name"] in MEERKAT_DISHES:
            row["array_distance"] = float(np.linalg.norm(
                np.subtract(row["xyz"], rows["MEERKAT"]["xyz"])))
            row["position_source"] += f" ({row['array_distance']:.0f} m from MEERKAT)"

    # A station is kept if another source confirms its position, or if its
    # position is the current GSFC VLBI solution (the best there is) and no
    # other source used holds it; a kept station must agree with every source.
    confirmed = [row for row in rows.values()
                 if any(c["status"] != "FAIL" for c in row["checks"]) and
                 row["name"] not in SINGLE_SOURCE
                 or (not row["checks"] and "locations.dat line" in row["position_source"]
                     and row.get("frame", "").startswith("GSFC Jan. 12, 2020"))]
    confirmed += [row for row in rows.values() if row not in confirmed and
                  rows.get(DERIVED_FROM.get(row.get("frame"), "")) in confirmed]
    kept = [row for row in rows.values() if row in confirmed or row["name"] in PAPER_FOCUS
            or row["name"] in SINGLE_SOURCE]
    left_out = sorted(row["name"] for row in rows.values() if row not in kept)
    axis_checks = {
        "locations.dat": validate_axistypes(axis_now, sched),
        "Master_NRAO/locations.dat.2005f": validate_axistypes(axis_2005, sched),
    }
    return kept, left_out, sorted(no_mount), axis_checks


def array_failures(rows):
    """The MeerKAT dishes against the array: its 64 dishes, each within its extent."""
    dishes = {row["name"]: row["array_distance"] for row in rows if "array_distance" in row}
    failed = [f"MeerKAT: {len(dishes)} dishes, the array has {len(MEERKAT_DISHES)} "
              f"({', '.join(sorted(set(MEERKAT_DISHES) ^ set(dishes)))})"] \
        if set(dishes) != set(MEERKAT_DISHES) else []
    return failed + [f"{name}: {distance:.0f} m from MEERKAT, beyond the array's extent "
                     f"({MEERKAT_EXTENT:g} m)" for name, distance in sorted(dishes.items())
                     if distance > MEERKAT_EXTENT]


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
    table["receptors"] = [row.get("receptors", "") for row in rows]
    table["receptors_source"] = [row.get("receptors_source", "") for row in rows]
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
                       "0 where none does; get_antenna adds it as a fixed rotator",
        "position_source": "file and line, or paper table, of the position",
        "mount_source": "where the mount comes from",
        "focus_source": "where the focus comes from, or 'assumed: <reason>'",
        "feed_offset_source": "where the feed offset comes from",
        "rotator": "field rotator mode (sky: the feed keeps its angle on the sky), or empty",
        "rotator_source": "where the rotator comes from",
        "receptors": "the receptors and their angles in the antenna (deg), as "
                     "Receptors.from_text reads them ('R:0,L:0'); empty where no source "
                     "states them",
        "receptors_source": "where the receptors come from",
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
    lines += ["", "Receptors (receptors: stations; source):"]
    stated = {}
    for row in rows:
        if row.get("receptors"):
            stated.setdefault((row["receptors"], row["receptors_source"]), []).append(row["name"])
    lines += [f"  {text}: {len(names)} stations ({', '.join(sorted(names)[:6])}"
              f"{', ...' if len(names) > 6 else ''}); {source}"
              for (text, source), names in sorted(stated.items())]
    lines += ["", "Every comparison (station, source, kind, distance in m, status):"]
    for row in sorted(rows, key=lambda r: r["name"]):
        for c in row["checks"]:
            lines.append(f"  {row['name']:12s} {c['ref']:28s} {c['kind']:9s} "
                         f"{c['distance']:12.3f}  {c['status']}")
        for ref, stated, status, _ in row["mount_checks"]:
            lines.append(f"  {row['name']:12s} {ref:28s} {stated:9s} (catalogue: "
                         f"{row['mount']} {row['focus'] or '-'})  {status}")
    single = sorted(row["name"] for row in rows
                    if not row["checks"] and row["name"] not in SINGLE_SOURCE)
    lines += ["", "Kept with one source (the current GSFC solution, the paper, or an ATCA pad "
              "that SCHED derives from AT_W104; no other source used holds them): "
              + (", ".join(single) or "none")]
    lines += ["", "Kept with one source, each with its reason (no other source used holds "
              "the position; listed in checks.py SINGLE_SOURCE):"]
    lines += [f"  {name:10s} {why}" for name, why in sorted(SINGLE_SOURCE.items())
              if name not in MEERKAT_DISHES]
    distances = [row["array_distance"] for row in rows if "array_distance" in row]
    lines += [f"  M000-M063  {SINGLE_SOURCE[MEERKAT_DISHES[0]]}: {len(distances)} dishes, "
              f"{min(distances):.0f} m to {max(distances):.0f} m from MEERKAT (the array's "
              f"extent: {MEERKAT_EXTENT:g} m)"]
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
    statements, disagree = receptor_statements(
        rows, SOURCES, read_pyuvdata_telescopes(SOURCES / "pyuvdata" / "telescopes.py"),
        PYUVDATA_ARRAYS, PYUVDATA)
    failed += disagree
    for row in rows:
        row["receptors"], row["receptors_source"] = statements.get(row["name"], ("", ""))
    kept = {row["name"] for row in rows}
    failed += [f"{name}: left out, but the catalogue must hold it (REQUIRED)"
               for name in sorted(REQUIRED - kept)]
    failed += array_failures(rows)
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
