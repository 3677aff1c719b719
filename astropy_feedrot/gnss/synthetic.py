# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Synthetic GNSS files: SP3 orbits and RINEX observations of simulated constellations.

For tests, benchmarks and the shipped samples: circular orbits with the
planes, heights and phasing of GPS, Galileo, GLONASS and BeiDou MEO
satellites (propagated with SGP4 from `~astropy_feedrot.TLEOrbit.from_elements`),
written as an SP3-d file, and RINEX observation files (2.11, 3.04, 4.01)
whose observations are made-up numbers in the right places, with the
loss-of-lock indicators and events a test asks for. Nothing here is a
measurement.
"""

import numpy as np
from astropy import units as u
from astropy.time import Time

from ..transmitters.orbits import Orbit, TLEOrbit

__all__ = ["CONSTELLATIONS", "constellation", "write_sp3", "write_rinex"]

#: Orbit planes, inclination, revolutions per sidereal day... of each system:
#: (planes, inclination deg, mean motion rev/day, satellites per plane).
#: GPS: 6 planes at 55 deg, 2 rev/sidereal day (IS-GPS-200); Galileo: 3 planes
#: at 56 deg, 17 revolutions in 10 days (Galileo OS SIS ICD); GLONASS: 3
#: planes at 64.8 deg, 17 revolutions in 8 days (GLONASS ICD); BeiDou MEO: 3
#: planes at 55 deg, 13 revolutions in 7 days (BDS-SIS-ICD).
CONSTELLATIONS = {
    "G": (6, 55.0, 2.0056, 4),
    "E": (3, 56.0, 1.7047, 8),
    "R": (3, 64.8, 2.1310, 8),
    "C": (3, 55.0, 1.8622, 8),
}


def constellation(epoch, counts):
    """Circular orbits of simulated satellites, named by PRN.

    Parameters
    ----------
    epoch : `~astropy.time.Time`
        Epoch of the elements.
    counts : dict of str to int
        Satellites per system, e.g. ``{'G': 12, 'E': 8}`` (at most the
        planes times the satellites per plane of `CONSTELLATIONS`).

    Returns
    -------
    dict of str to `~astropy_feedrot.TLEOrbit`

    Examples
    --------
    >>> from astropy.time import Time
    >>> from astropy_feedrot.gnss.synthetic import constellation
    >>> sorted(constellation(Time("2023-01-25"), {"G": 2, "E": 1}))
    ['E01', 'G01', 'G02']
    """
    orbits = {}
    number = 1
    for system, count in counts.items():
        planes, inclination, motion, per_plane = CONSTELLATIONS[system]
        for k in range(count):
            plane, slot = k % planes, k // planes
            orbits[f"{system}{k + 1:02d}"] = TLEOrbit.from_elements(
                epoch, inclination=inclination * u.deg, raan=plane * 360.0 / planes * u.deg,
                mean_motion=motion * u.cycle / u.day,
                mean_anomaly=(slot * 360.0 / per_plane + plane * 15.0) * u.deg,
                satnum=number)
            number += 1
    return orbits


def _gps_calendar(times):
    """Calendar fields of GPS time (TAI - 19 s)."""
    gps = Time(times.tai.jd1, times.tai.jd2 - 19.0 / 86400, format="jd", scale="tai")
    return gps.to_value("ymdhms")


def write_sp3(path, orbits, start, epochs, interval=900.0):
    """Write the orbits as an SP3-d file in GPS time, positions only.

    Parameters
    ----------
    path : str or path-like
    orbits : dict of str to `~astropy_feedrot.transmitters.orbits.Orbit`
    start : `~astropy.time.Time`
        First epoch (a GPS-time instant on the interval's grid).
    epochs : int
    interval : float
        Seconds.

    Examples
    --------
    >>> import os, tempfile
    >>> from astropy.time import Time
    >>> from astropy_feedrot.gnss.synthetic import constellation, write_sp3
    >>> from astropy_feedrot.io import read_sp3
    >>> t0 = Time("2023-01-25T00:00:19", scale="tai")  # 00:00 GPS time
    >>> name = os.path.join(tempfile.mkdtemp(), "sim.sp3")
    >>> write_sp3(name, constellation(t0, {"G": 2}), t0, 4)
    >>> read_sp3(name)
    <SP3Data version='d' time_system='GPS' coordinate_system='IGS20' 2 satellites, 4 epochs>
    """
    times = start + np.arange(epochs) * interval * u.s
    names = list(orbits)
    xyz = Orbit.positions([orbits[n] for n in names], times) / 1e3
    cal = _gps_calendar(times)
    lines = [f"#dP{cal[0]['year']:4d} {cal[0]['month']:2d} {cal[0]['day']:2d} "
             f"{cal[0]['hour']:2d} {cal[0]['minute']:2d} {cal[0]['second']:11.8f} "
             f"{epochs:7d} ORBIT IGS20 FIT  SIM",
             f"## 2246      0.00000000 {interval:14.8f} 59969 0.0000000000000"]
    ids = names + ["  0"] * (-len(names) % 17 or 0)
    for k in range(0, max(len(ids), 17), 17):
        head = f"+  {len(names):3d}   " if k == 0 else "+        "
        lines.append(head + "".join(ids[k:k + 17]))
        lines.append("++       " + "  0" * 17)
    lines += ["%c M  cc GPS ccc cccc cccc cccc cccc ccccc ccccc ccccc ccccc",
              "%c cc cc ccc ccc cccc cccc cccc cccc ccccc ccccc ccccc ccccc",
              "%f  1.2500000  1.025000000  0.00000000000  0.000000000000000",
              "%f  0.0000000  0.000000000  0.00000000000  0.000000000000000",
              "%i    0    0    0    0      0      0      0      0         0",
              "%i    0    0    0    0      0      0      0      0         0",
              "/* SYNTHETIC ORBITS (astropy_feedrot.gnss.synthetic), NOT A PRODUCT"]
    for t, c in enumerate(cal):
        lines.append(f"*  {c['year']:4d} {c['month']:2d} {c['day']:2d} {c['hour']:2d} "
                     f"{c['minute']:2d} {c['second']:11.8f}")
        for s, name in enumerate(names):
            x, y, z = xyz[s, t]
            lines.append(f"P{name}{x:14.6f}{y:14.6f}{z:14.6f}{0.0:14.6f}")
    lines.append("EOF")
    with open(path, "w") as fh:
        fh.write("\n".join(lines) + "\n")


def _header_3(version, types, position, zero_direction, interval, first, system):
    def label(text, name):
        return f"{text:<60}{name}\n"
    lines = [label(f"{version:>9}           OBSERVATION DATA    {system:<20}",
                   "RINEX VERSION / TYPE"),
             label("feedrot synthetic   astropy_feedrot     20230126 000000 UTC",
                   "PGM / RUN BY / DATE"),
             label("SYNTHETIC OBSERVATIONS, NOT A MEASUREMENT", "COMMENT"),
             label("SIM1", "MARKER NAME"),
             label("".join(f"{v:14.4f}" for v in position), "APPROX POSITION XYZ")]
    if zero_direction is not None:
        lines.append(label(f"{zero_direction:14.4f}", "ANTENNA: ZERODIR AZI"))
    for code, codes in types.items():
        for k in range(0, len(codes), 13):
            head = f"{code}  {len(codes):3d}" if k == 0 else "      "
            lines.append(label(head + "".join(f" {c}" for c in codes[k:k + 13]),
                               "SYS / # / OBS TYPES"))
    lines.append(label(f"{interval:10.3f}", "INTERVAL"))
    c = first
    lines.append(label(f"{c['year']:6d}{c['month']:6d}{c['day']:6d}{c['hour']:6d}"
                       f"{c['minute']:6d}{c['second']:13.7f}     GPS", "TIME OF FIRST OBS"))
    lines.append(label("", "END OF HEADER"))
    return lines


def _header_2(types, position, zero_direction, interval, first):
    def label(text, name):
        return f"{text:<60}{name}\n"
    lines = [label("     2.11           OBSERVATION DATA    M (MIXED)", "RINEX VERSION / TYPE"),
             label("SYNTHETIC OBSERVATIONS, NOT A MEASUREMENT", "COMMENT"),
             label("".join(f"{v:14.4f}" for v in position), "APPROX POSITION XYZ")]
    if zero_direction is not None:
        lines.append(label(f"{zero_direction:14.4f}", "ANTENNA: ZERODIR AZI"))
    for k in range(0, len(types), 9):
        head = f"{len(types):6d}" if k == 0 else "      "
        lines.append(label(head + "".join(f"    {c}" for c in types[k:k + 9]),
                           "# / TYPES OF OBSERV"))
    lines.append(label(f"{interval:10.3f}", "INTERVAL"))
    c = first
    lines.append(label(f"{c['year']:6d}{c['month']:6d}{c['day']:6d}{c['hour']:6d}"
                       f"{c['minute']:6d}{c['second']:13.7f}     GPS", "TIME OF FIRST OBS"))
    lines.append(label("", "END OF HEADER"))
    return lines


def _value(t, s, k, code):
    """A made-up observation: pseudoranges ~2e7 m, phases ~1e8 cycles, SNR ~45."""
    if code[0] == "C" or code[0] == "P":
        return 2.0e7 + 1000.0 * s + 10.0 * t + k
    if code[0] == "L":
        return 1.0e8 + 1.0e6 * s + 1000.123 * t + 0.25 * k
    if code[0] == "D":
        return -1000.0 + s
    return 45.0 + (s % 5)


def write_rinex(path, version, types, sats, start, epochs, interval=30.0, *,
                position=(1130730.179, -4831245.954, 3994228.241), zero_direction=None,
                lli=None, missing=None, events=None):
    """Write a synthetic RINEX observation file.

    Parameters
    ----------
    path : str or path-like
    version : {'2.11', '3.04', '4.01'}
    types : dict of str to tuple of str
        Observation types per system (RINEX 2: the same types for all, give
        one tuple under any key).
    sats : sequence of str
        PRNs observed at every epoch (all of them at all epochs).
    start : `~astropy.time.Time`
        First epoch.
    epochs : int
    interval : float
        Seconds.
    position : sequence of 3 float, optional
        ``APPROX POSITION XYZ`` (default GGAO12M of the paper's Table 3).
    zero_direction : float, optional
        ``ANTENNA: ZERODIR AZI`` in degrees, written if given.
    lli : dict of (int, str) or (int, str, str) to int, optional
        Loss-of-lock indicators of the phases of a satellite at an epoch
        index, e.g. ``{(10, 'G05'): 1}``, or of one of its phases,
        ``{(10, 'G05', 'L2W'): 1}``.
    missing : set of (int, str), optional
        (epoch, PRN) pairs not observed.
    events : dict of int to list of str, optional
        Event records (flag 4, header lines) written before an epoch index.

    Examples
    --------
    >>> import os, tempfile
    >>> from astropy.time import Time
    >>> from astropy_feedrot.gnss import read_rinex_header
    >>> from astropy_feedrot.gnss.synthetic import write_rinex
    >>> name = os.path.join(tempfile.mkdtemp(), "sim.rnx")
    >>> write_rinex(name, "3.04", {"G": ("C1C", "L1C")}, ["G01"],
    ...             Time("2023-01-25T00:00:19", scale="tai"), 2)
    >>> read_rinex_header(name).obs_types
    {'G': ('C1C', 'L1C')}
    """
    lli = lli or {}
    missing = missing or set()
    events = events or {}
    times = start + np.arange(epochs) * interval * u.s
    cal = _gps_calendar(times)
    v2 = version.startswith("2")
    if v2:
        codes = next(iter(types.values()))
        lines = _header_2(codes, position, zero_direction, interval, cal[0])
    else:
        systems = {s[0] for s in sats}
        lines = _header_3(version, {k: v for k, v in types.items() if k in systems},
                          position, zero_direction, interval, cal[0],
                          "M" if len(systems) > 1 else sats[0][0])
    with open(path, "w") as fh:  # epoch by epoch: a day at 1 s never sits in memory
        fh.writelines(lines)
        for t, c in enumerate(cal):
            fh.writelines(_epoch_lines(t, c, sats, types, v2, lli, missing, events))


def _epoch_lines(t, c, sats, types, v2, lli, missing, events):
    """The lines of epoch ``t`` (calendar ``c``) of `write_rinex`, events first."""
    lines = []
    for text in events.get(t, []):
        if v2:
            lines.append(f"{'':26}  4{len([text]):3d}\n")
        else:
            lines.append(f">{'':30}4{1:3d}\n")
        lines.append(f"{text:<60}COMMENT\n")
    seen = [s for s in sats if (t, s) not in missing]
    if v2:
        head = (f" {c['year'] % 100:02d} {c['month']:2d} {c['day']:2d} {c['hour']:2d} "
                f"{c['minute']:2d}{c['second']:11.7f}  0{len(seen):3d}")
        for k in range(0, len(seen), 12):
            prefix = head if k == 0 else " " * 32
            lines.append(prefix + "".join(seen[k:k + 12]) + "\n")
    else:
        lines.append(f"> {c['year']:4d} {c['month']:02d} {c['day']:02d} {c['hour']:02d} "
                     f"{c['minute']:02d}{c['second']:11.7f}  0{len(seen):3d}\n")
    for s_index, sat in enumerate(sats):
        if sat not in seen:
            continue
        codes = next(iter(types.values())) if v2 else types[sat[0]]
        fields = []
        for k, code in enumerate(codes):
            flag = lli.get((t, sat, code), lli.get((t, sat), 0)) if code[0] == "L" else 0
            ssi = "7" if code[0] in "LC" else " "
            fields.append(f"{_value(t, s_index, k, code):14.3f}"
                          f"{flag if flag else ' '}{ssi}")
        if v2:
            for k in range(0, len(fields), 5):
                lines.append("".join(fields[k:k + 5]).rstrip() + "\n")
        else:
            lines.append(sat + "".join(fields).rstrip() + "\n")
    return lines
