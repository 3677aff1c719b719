# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Readers of the public station files in ``catalogue/sources`` (used by ``build_stations.py``).

Each reader returns the file's values as they are written (metres, the file's
own names and codes); nothing here chooses, merges or corrects.
"""

import json
import math
import re

from astropy import units as u
from astropy.coordinates import Angle, EarthLocation

#: SCHED's MOUNT values and the geodetic codes of astropy_feedrot.stations.labels.
MOUNT_CODES = {"ALTAZ": "AZEL", "EQUAT": "EQUA", "XYEW": "X-YE", "XYNS": "X-YN"}

#: AXISTYPE values of SCHED's locations files (SPAC, a tracking station, has no code here).
AXIS_CODES = {"ALTZ": "AZEL", "ALTAZ": "AZEL", "ALTA": "AZEL", "EQUA": "EQUA",
              "XYEW": "X-YE", "XYNS": "X-YN"}


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
            if row["Type"] == "ITRF" and math.hypot(row["X"], row["Y"], row["Z"]) > 6e6:
                xyz = [row["X"], row["Y"], row["Z"]]  # geocentric X, Y, Z given
            elif row["Type"] == "ITRF":  # spherical geocentric, Height is the radius
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
    """An eht-imaging array file: name -> position and feed-rotation coefficients."""
    rows = {}
    for number, line in enumerate(path.read_text().splitlines(), 1):
        if line.startswith("#") or not line.strip():
            continue
        parts = line.split()
        rows[parts[0]] = dict(xyz=[float(v) for v in parts[1:4]], line=number,
                              fr_par=float(parts[6]), fr_elev=float(parts[7]),
                              fr_offset=float(parts[8]))
    return rows


def read_casa_sched(path):
    """casadata's ``SCHED_locations`` table (python-casacore): rows in table order."""
    from casacore.tables import table  # optional: python-casacore

    rows = []
    with table(str(path), ack=False) as tab:
        for number, row in enumerate(tab):
            rows.append(dict(code=row["DBCODE"].strip(), name=row["DBNAME"].strip(),
                             axis=row["AXISTYPE"].strip().upper(), row=number,
                             xyz=[row["X"], row["Y"], row["Z"]],
                             vel=[row["DXDT"], row["DYDT"], row["DZDT"]],
                             epoch=float(row["EPOCH"]), frame=row["FRAME"].strip()))
    return rows


def read_sites(path):
    """astropy-data's ``sites.json``: key -> ITRF position (m), names and source."""
    found = {}
    for key, site in json.loads(path.read_text()).items():
        loc = EarthLocation.from_geodetic(site["longitude"] * u.Unit(site["longitude_unit"]),
                                          site["latitude"] * u.Unit(site["latitude_unit"]),
                                          site["elevation"] * u.Unit(site["elevation_unit"]))
        found[key] = dict(xyz=[float(v.to_value(u.m)) for v in (loc.x, loc.y, loc.z)],
                          names=[key, site["name"], *site.get("aliases", [])],
                          source=" ".join(str(site.get("source", "")).split()))
    return found


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


def read_ms_feeds(path):
    """The receptors of a Measurement Set's FEED table (python-casacore).

    Returns the distinct (POLARIZATION_TYPE, RECEPTOR_ANGLE in degrees) of its
    rows, sorted, and the number of antennas they describe.
    """
    from casacore.tables import table  # optional: python-casacore

    with table(str(path), ack=False) as tab:
        found = {(tuple(str(t) for t in row["POLARIZATION_TYPE"]),
                  tuple(round(math.degrees(float(a)), 9) for a in row["RECEPTOR_ANGLE"]))
                 for row in tab}
        return sorted(found), len(set(tab.getcol("ANTENNA_ID").tolist()))


def read_miriad_observatories(path):
    """Miriad's ``observatories.dat``: (observatory, parameter) -> (value text, line)."""
    found = {}
    for number, line in enumerate(path.read_text().splitlines(), 1):
        fields = line.split()
        if fields and not line.startswith("#") and len(fields) >= 3:
            found[(fields[0], fields[1])] = (" ".join(fields[2:]), number)
    return found


def _number(node):
    """The value of a numeric literal such as ``np.pi / 2`` (no code is run)."""
    import ast

    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)):
        return float(node.value)
    if isinstance(node, ast.Attribute) and node.attr == "pi":
        return math.pi
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
        return -_number(node.operand)
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Div, ast.Mult)):
        left, right = _number(node.left), _number(node.right)
        return left / right if isinstance(node.op, ast.Div) else left * right
    raise ValueError(f"not a number: {ast.dump(node)}")


def read_pyuvdata_telescopes(path):
    """pyuvdata's ``KNOWN_TELESCOPES`` (its ``telescopes.py``), read without running it.

    Returns name -> dict with ``lat``, ``lon`` (angle strings as written),
    ``height`` (m) where the entry gives a location, ``mount_type``,
    ``citation``, ``line``, and ``feed_array`` (letters) with ``feed_angle``
    (radians) where the entry gives its feeds.
    """
    import ast

    tree = ast.parse(path.read_text())
    found = {}
    for node in tree.body:
        if not (isinstance(node, ast.Assign) and getattr(node.targets[0], "id", "")
                == "KNOWN_TELESCOPES"):
            continue
        for key, value in zip(node.value.keys, node.value.values):
            entry = {"line": key.lineno}
            for field, item in zip(value.keys, value.values):
                if isinstance(item, ast.Constant):
                    entry[field.value] = item.value
                elif field.value == "feed_array":
                    entry["feed_array"] = [str(e.value) for e in item.elts]
                elif field.value == "feed_angle":
                    entry["feed_angle"] = [_number(e) for e in item.elts]
                elif field.value == "location":
                    for keyword in item.keywords:
                        if keyword.arg in ("lat", "lon"):
                            entry[keyword.arg] = keyword.value.args[0].value
                        elif keyword.arg == "height":
                            entry["height"] = keyword.value.left.value
            if "lat" in entry:
                loc = EarthLocation.from_geodetic(u.Quantity(Angle(entry["lon"]), u.deg),
                                                  u.Quantity(Angle(entry["lat"]), u.deg),
                                                  entry["height"] * u.m)
                entry["xyz"] = [float(v.to_value(u.m)) for v in (loc.x, loc.y, loc.z)]
            found[key.value] = entry
    return found


def read_antenna_info(path):
    """Nothnagel's IVS antenna-info file: IVS name -> focus, mount and line.

    ``focus`` is ``FO_PRIM`` (prime) or ``FO_SECN`` (secondary: Cassegrain,
    Gregorian, and also Nasmyth or beam waveguide, which the file does not
    tell apart), or empty; ``mount`` is ``MO_AZEL``, ``MO_EQUA``, ``MO_XYNO``,
    ``MO_XYEA`` or ``MO_RICH``.
    """
    found = {}
    for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
        if line.startswith("ANTENNA_INFO"):
            name = line[14:22].strip()
            found.setdefault(name, dict(focus=line[24:31].strip(), mount=line[32:39].strip(),
                                        line=number))
    return found


def read_difx_antennas(path):
    """DiFX's ``antenna_db.c`` table: entries in file order.

    Each: ``name``, ``ivs`` (IVS name or empty), ``xyz`` (m), ``mount`` (as
    written: ``NASL``, ``NASR``, ``EQUA``, ``XYEW``... or empty) and ``line``.
    """
    entries = []
    pattern = re.compile(r'^\s*\{\s*"([^"]*)",\s*"([^"]*)",\s*([-0-9.]+),\s*([-0-9.]+),\s*'
                         r'([-0-9.]+),\s*([-0-9.]+)(?:,\s*([-0-9.]+))?(?:,\s*"([^"]*)")?')
    for number, line in enumerate(path.read_text().splitlines(), 1):
        found = pattern.match(line)
        if found and found[1]:
            entries.append(dict(name=found[1], ivs=found[2],
                                xyz=[float(found[i]) for i in (3, 4, 5)],
                                mount=found[8] or "", line=number))
    return entries


def read_sked_positions(path):
    """sked's ``position.cat``: IVS name -> two-letter code, position, origin and line.

    ``origin`` is the file's last column(s): ``2020c`` for the GSFC solution
    2020c (epoch 2021 Jan 1, the file's header says), another solution's name
    (``GLB1069``, ``GLB659``) or a note (``SHAO``, ``email ...``).
    """
    found = {}
    for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
        words = line.split()
        if line.startswith("*") or len(words) < 8:
            continue
        found.setdefault(words[1], dict(code=words[0], xyz=[float(w) for w in words[2:5]],
                                        origin=" ".join(words[8:]), line=number))
    return found


def read_sked_antennas(path):
    """sked's ``antenna.cat``: IVS name -> axis type, diameter (m), two-letter code, line.

    The axis types are ``AZEL``, ``HADC`` (polar), ``XYNS``, ``XYEW`` and
    ``SEST`` (the SEST's own alt-az slewing model).
    """
    found = {}
    for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
        words = line.split()
        if line.startswith("*") or len(words) < 14:
            continue
        found.setdefault(words[1], dict(axis=words[2], diameter=float(words[12]),
                                        code=words[13], line=number))
    return found


def read_itrf_layout(path):
    """An array layout of simms (``*.itrf.txt``): entries in file order.

    Each line: X, Y, Z (ITRF, m), dish diameter (m), antenna name and mount
    (``ALT-AZ``); each entry: ``name``, ``xyz``, ``diameter``, ``mount``, ``line``.
    """
    entries = []
    for number, line in enumerate(path.read_text().splitlines(), 1):
        words = line.split()
        if len(words) == 6 and not line.startswith("#"):
            entries.append(dict(name=words[4], xyz=[float(w) for w in words[:3]],
                                diameter=float(words[3]), mount=words[5], line=number))
    return entries
