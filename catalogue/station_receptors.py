# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The receptors of the catalogue's stations, where a public source states them.

Used by ``build_stations.py``. Each statement gives a station its receptors in
the text of ``astropy_feedrot.Receptors.from_text`` (``'R:0,L:0'``,
``'X:45,Y:135'``: the receptor letters and their angles in the antenna, 0 a
dipole along the vertical of an alt-az antenna, 90 deg a horizontal one) and
cites its source. Where no source used states them, the station has none: no
receptor is assumed from a network, a band or a country. Two statements that
disagree on one station stop the build.

Left out, with the reason:

* ALMA: the FEED table of the ALMA Measurement Set in ``sources/alma_ms``'s
  origin gives X at -10 deg and Y at 80 deg for its one spectral window
  (Band 3, 111 GHz); no source used gives the angles of the other bands.
* MeerKAT, the EVN, the IVS and the EHT: no source used states their
  receptors. SCHED 1.29.1's ``catalogs/freq.dat`` (not kept here) writes RCP
  and LCP for every station, including setups it notes as "native linear" or
  "dummy dual-pol", so it is not read as a statement of the feeds.
"""

from readers import read_miriad_observatories, read_ms_feeds

#: The VLBA's receptors: circular at every band.
VLBA_OSS = ("VLBA Observational Status Summary 2018A, Introduction "
            "(https://science.nrao.edu/facilities/vlba/docs/manuals/oss2018A): "
            "simultaneous dual circular polarizations from any single receiver")

#: Why circular receptors are written at 0 deg where a source states none.
CIRCULAR_ZERO = ("R and L at 0 deg: a circular receptor's angle only sets the phase of RL "
                 "and LR, and AIPS and CASA write 0 (POLAA, RECEPTOR_ANGLE)")

#: The VLA's receptors: circular.
VLA_GUIDE = ("VLBI at the VLA guide, Polarizations "
             "(http://www.vla.nrao.edu/astro/guides/vlbivla/current/node9.html): the VLA's IFs "
             "A and B are right circularly polarized, C and D left")

#: The VLA Measurement Set whose FEED table ``sources/vla_ms/FEED`` is.
VLA_MS = ("VLA Measurement Set day2_TDEM0003_10s_norx_1src_1spw.ms (pyuvdata 3.1.3 test "
          "data; telescope EVLA), FEED table")

#: Miriad's table of observatories, and where Miriad's ATCA loader departs from it.
MIRIAD = "Miriad cat/observatories.dat (csiro/miriad commit d4110d5)"
ATLOD_7MM = ("not at 7 mm, where Miriad's atlod turns the feed 90 deg further (src/prog/"
             "atlod.for, commit d4110d5: chi = parallactic angle + pi/4, + pi/2 for qband)")


def _text(types, angles):
    return ",".join(f"{t}:{a:g}" for t, a in zip(types, angles))


def receptor_statements(rows, sources_dir, pyuvdata, pyuvdata_arrays, pyuvdata_label):
    """Each station's receptors: name -> (text, source), for the stations a source states.

    Parameters
    ----------
    rows : iterable of dict
        The catalogue's rows (``name``, ``networks``).
    sources_dir : pathlib.Path
        ``catalogue/sources``.
    pyuvdata : dict
        pyuvdata's known telescopes (``readers.read_pyuvdata_telescopes``).
    pyuvdata_arrays : dict
        ``build_stations.PYUVDATA_ARRAYS``: pyuvdata name -> (catalogue name,
        position source, mount code).
    pyuvdata_label : str
        The citation of pyuvdata's file.

    Returns
    -------
    statements : dict
        name -> (text, source).
    failed : list of str
        Disagreements between statements, and sources that no longer say
        what the build expects.
    """
    by_network, failed = {}, []
    by_network["VLBA"] = ("R:0,L:0", f"{VLBA_OSS}; {CIRCULAR_ZERO}")

    feeds, antennas = read_ms_feeds(sources_dir / "vla_ms" / "FEED")
    if len(feeds) == 1:
        (types, angles), = feeds
        by_network["VLA"] = (_text(types, angles),
                             f"{VLA_GUIDE}; {VLA_MS}: {', '.join(types)} at RECEPTOR_ANGLE "
                             f"{', '.join(f'{a:g}' for a in angles)} deg for its {antennas} "
                             "antennas")
    else:
        failed.append(f"{VLA_MS}: the rows disagree ({feeds}); no VLA receptors")

    evector = read_miriad_observatories(sources_dir / "miriad" / "observatories.dat")
    value, line = evector[("atca", "evector")]
    alpha = float(value)
    by_network["ATCA"] = (_text("XY", (alpha, alpha + 90)),
                          f"{MIRIAD} line {line} (atca evector {value}: the X feed's angle "
                          "from the local vertical; Y 90 deg on, as Miriad takes it); "
                          f"{ATLOD_7MM}")

    statements = {}
    for row in rows:
        for network in sorted(row["networks"]):
            if network in by_network:
                _add(statements, failed, row["name"], *by_network[network])

    # pyuvdata's known telescopes that give their feeds. pyuvdata's angle of a
    # feed fixed to the ground is its azimuth (0 north, 90 deg east); the
    # catalogue's is counted from the east dipole of a stationary mount
    # (astropy_feedrot.visibilities.uvdata reads pyuvdata the same way).
    for key, (name, _, code) in pyuvdata_arrays.items():
        entry = pyuvdata.get(key, {})
        if "feed_array" not in entry:
            continue
        degrees = [a * 180 / 3.141592653589793 - (90.0 if code == "GNSS" else 0.0)
                   for a in entry["feed_angle"]]
        letters = "".join(f.upper() for f in entry["feed_array"])
        _add(statements, failed, name, _text(letters, [round(d, 9) for d in degrees]),
             f"{pyuvdata_label} line {entry['line']} ({key}: feed_array "
             f"{entry['feed_array']}, feed_angle {entry['feed_angle']} rad" +
             ("; azimuths of feeds fixed to the ground, here from the east dipole)"
              if code == "GNSS" else ")"))
    return statements, failed


def _add(statements, failed, name, text, source):
    if name not in statements:
        statements[name] = (text, source)
    elif statements[name][0] == text:
        statements[name] = (text, f"{statements[name][1]}; also {source}")
    else:
        failed.append(f"{name}: receptors {statements[name][0]} ({statements[name][1]}) "
                      f"but {text} ({source})")
