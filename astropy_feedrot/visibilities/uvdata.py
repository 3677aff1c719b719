# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Feed rotation of pyuvdata's `~pyuvdata.UVData` objects, and its removal.

`antennas_from_uvdata` turns the telescope of a `~pyuvdata.UVData` object
(positions, ``mount_type``, ``feed_array`` and ``feed_angle``) into
`~astropy_feedrot.Antenna` objects; `feed_rotation_uvdata` gives the
position angle on the sky of both antennas' receptors for every
baseline-time, whatever the phase centre (sidereal, ephemeris, drift scan or
unprojected); `correct_uvdata` removes the feed rotation from the
visibilities, so that the receptors are fixed on the sky. Reading and
writing the files pyuvdata knows, offline, is `~astropy_feedrot.visibilities.uvdata_files`.

pyuvdata is an optional dependency, of the ``uvdata`` extra (``python -m pip
install pyuvdata``), imported when a function here is called. The conventions (pyuvdata's
conjugation, feed angles, the vertical of CASA) are in ``docs/uvdata.rst``.
"""

from types import SimpleNamespace

import numpy as np
from astropy import units as u
from astropy.coordinates import Angle, EarthLocation
from astropy.time import Time

from ..antennas.mounts import AltAzMount
from ..antennas.receptors import PRODUCT_CODES, RECEPTOR_TYPES, Receptors, basis_of
from ..applied.correction import correct_receptor_visibilities
from ..core.exceptions import DegenerateGeometryWarning, warn_caller
from ..core.progress import progress_steps
from ..earth.eop import iers_context
from ..earth.frames import VERTICALS
from ..engine.antenna import Antenna
from ..stations.labels import is_orbiting, mount_from_label
from .catalogue import catalogue_receptors
from .correction import Correction
from .faraday import (
    correct_rows,
    lambda_squared,
    rotation_measure_rows,
    row_places,
)
from .history import history_entry
from .phase_centres import phase_centre_sources
from .receptors import receptor_position_angles, warn_unusual_angles, with_receptors
from .unusable import (
    UnusableAntenna,
    check_unusable,
    given_feeds,
    orbiting_reason,
    usable_antennas,
    warn_skipped,
)
from .uvdata_files import check_uvdata

__all__ = [
    "antennas_from_uvdata",
    "feed_rotation_uvdata",
    "correct_uvdata",
]

__doctest_requires__ = {("*",): ["pyuvdata"]}

# pyuvdata polarization codes of correlation products (AIPS Memo 117); the
# first letter is the receptor of ant_1.
_STOKES = {1: "pI", 2: "pQ", 3: "pU", 4: "pV"}


def _check_vertical(vertical):
    if vertical not in VERTICALS:
        raise ValueError(f"vertical must be one of {VERTICALS}, got {vertical!r}")


# --- antennas -------------------------------------------------------------------


def _receptors(feeds, angles, stationary):
    """Receptors of one antenna from pyuvdata's feeds and feed angles (radians)."""
    types = [str(f).strip().upper() for f in feeds]
    alpha = list(np.degrees(np.asarray(angles, dtype=float)))
    if stationary:
        # pyuvdata: 0 = north, 90 deg = east; here alpha = 0 is the aligned
        # (east) dipole of StationaryMount, so alpha = feed_angle - 90 deg.
        alpha = [a - 90.0 for a in alpha]
    if len(types) == 2 and types[1] in ("", "?"):
        types = types[:1]
    if len(types) == 1:
        # One feed listed (UVFITS files whose POLTYB is blank, '?' of SFXC): the
        # other receptor of the pair (Receptors.paired).
        return Receptors.paired(types[0], alpha[0] * u.deg)
    return Receptors("".join(types), alpha * u.deg)


def _antennas(uv, vertical, numbers=None, keep=False):
    """{antenna number: Antenna} of the telescope (only ``numbers`` if given); ``keep``:
    antennas that cannot be described as UnusableAntenna instead of an error."""
    _check_vertical(vertical)
    tel = uv.telescope
    if tel.mount_type is None:
        raise ValueError(
            "the data do not say how the antennas are mounted (telescope.mount_type is "
            "None); set it, e.g. uv.telescope.mount_type = ['alt-az'] * uv.telescope.Nants, "
            "or pass antennas={number: Antenna}")
    if not isinstance(tel.location, EarthLocation):
        raise ValueError(f"the telescope location must be on the Earth (an EarthLocation), "
                         f"got {type(tel.location).__name__}")
    centre = np.array([tel.location.x.to_value(u.m), tel.location.y.to_value(u.m),
                       tel.location.z.to_value(u.m)])
    all_numbers = [int(n) for n in tel.antenna_numbers]
    wanted = set(all_numbers if numbers is None else (int(n) for n in numbers))
    antennas = {}
    for k, number in enumerate(all_numbers):
        if number not in wanted:
            continue
        name = str(tel.antenna_names[k])
        label = tel.mount_type[k]
        xyz = centre + np.asarray(tel.antenna_positions[k], dtype=float)
        location = EarthLocation.from_geocentric(*xyz, unit=u.m)
        try:
            mount, focus = mount_from_label(label, "pyuvdata")
        except ValueError as err:
            reason = (f"{err}. If you know the mount, set uv.telescope.mount_type, or pass "
                      "antennas={number: Antenna}")
            if not keep:
                raise ValueError(f"antenna {name} (number {number}): {reason}") from None
            problem = "mount"
            if is_orbiting(label, "pyuvdata"):
                problem, reason = "orbiting", orbiting_reason(f"mount_type {label!r}")
            antennas[number] = UnusableAntenna(location, name, problem, reason, label=label,
                                               vertical=vertical)
            continue
        receptors = None
        if tel.feed_array is not None and tel.feed_angle is not None:
            try:
                receptors = _receptors(tel.feed_array[k], tel.feed_angle[k], not mount.tracks)
            except ValueError as err:
                reason = (f"{err}. Files often give 0 for both linear receptors; if you know "
                          "the angles, set uv.telescope.feed_angle (radians, e.g. [0, pi/2] "
                          "for x and y), or give the feeds (feeds=, --feeds X:90,Y:0)")
                if not keep:
                    raise ValueError(f"antenna {name} (number {number}): {reason}") from None
                antennas[number] = UnusableAntenna(location, name, "receptors", reason,
                                                   label=label, mount=mount, focus=focus,
                                                   vertical=vertical)
                continue
        antennas[number] = Antenna(location, mount, focus, name=name, vertical=vertical,
                                   receptors=receptors)
    return antennas


def antennas_from_uvdata(uv, *, vertical="geodetic", unusable="raise"):
    """The antennas of a `~pyuvdata.UVData` object as `~astropy_feedrot.Antenna` objects.

    Parameters
    ----------
    uv : `~pyuvdata.UVData`
        The data; its ``telescope`` gives the location, the antenna
        positions, names and numbers, ``mount_type``, ``feed_array`` and
        ``feed_angle``.
    vertical : {'geodetic', 'geocentric'}, optional
        The local vertical of every antenna (`~astropy_feedrot.Antenna`).
        ``'geocentric'`` reproduces CASA and casacore, whose parallactic
        angles use the geocentric vertical.
    unusable : {'raise', 'keep'}, optional
        What to do with an antenna that cannot be described (a
        ``mount_type`` with no model, such as ``'orbiting'``; linear
        receptors at one angle): raise (default), or keep it as an
        `~astropy_feedrot.visibilities.UnusableAntenna` with the reason.

    Returns
    -------
    dict
        ``{antenna number: Antenna}`` for every antenna of the telescope, at
        its absolute position (``telescope.location`` plus
        ``antenna_positions``), with the mount and focus of its
        ``mount_type`` (`~astropy_feedrot.stations.labels.mount_from_label`, convention
        ``'pyuvdata'``) and its receptors (`~astropy_feedrot.antennas.receptors.Receptors`).

    Raises
    ------
    ImportError
        If pyuvdata is not installed.
    TypeError
        If ``uv`` is not a `~pyuvdata.UVData` object.
    ValueError
        If ``telescope.mount_type`` is missing, names a mount without a
        feed-rotation model (``'phased'``, ``'other'``, ``'orbiting'``), the
        telescope is not on the Earth, or for an unknown ``vertical``.

    Notes
    -----
    Receptor angles :math:`\\alpha` (`~astropy_feedrot.antennas.receptors`) come from
    ``feed_angle``: for steerable mounts pyuvdata's 0 is the direction toward
    the zenith, as here, so :math:`\\alpha` = ``feed_angle``. For ``'fixed'``
    antennas (a `~astropy_feedrot.StationaryMount`, whose reference dipole
    points east) pyuvdata's 0 is north and 90 deg east, so :math:`\\alpha` =
    ``feed_angle`` - 90 deg. When the file lists one feed (UVFITS files with
    a blank ``POLTYB``), the other receptor is added at the same angle for
    circular feeds and 90 deg further (``Y`` after ``X``) for linear ones.
    Without ``feed_array`` the antennas have no receptors.

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.coordinates import EarthLocation
    >>> from pyuvdata import Telescope
    >>> from astropy_feedrot.visibilities.uvdata import antennas_from_uvdata
    >>> from pyuvdata import UVData
    >>> site = EarthLocation.from_geodetic(-107.6184 * u.deg, 34.0790 * u.deg, 2124 * u.m)
    >>> tel = Telescope.new(name="TEST", instrument="TEST", location=site,
    ...                     antenna_positions={0: [0.0, 0, 0], 1: [100.0, 0, 0]},
    ...                     feed_array=["x", "y"], feed_angle=[np.pi / 2, 0.0],
    ...                     mount_type="alt-az")
    >>> uv = UVData.new(freq_array=np.array([1.4e9]), channel_width=np.array([1e6]),
    ...                 polarization_array=["xx", "yy", "xy", "yx"], times=np.array([2460000.9]),
    ...                 integration_time=np.array([10.0]), telescope=tel,
    ...                 antpairs=[(0, 1)], do_blt_outer=True, empty=True)
    >>> antennas = antennas_from_uvdata(uv)
    >>> antennas[1].mount, antennas[1].receptors
    (AltAzMount(), Receptors('XY', [90.0, 0.0] * u.deg))
    """
    check_uvdata(uv)
    return _antennas(uv, vertical, keep=check_unusable(unusable) == "keep")


# --- position angles of the receptors ----------------------------------------------


def _position_angles(uv, antennas, frame, vertical, note="", skip=(), warn=False):
    """Sky position angles (deg) of the receptors of ant_1 and ant_2, (Nblts, 2) each.

    Returns (theta1, theta2, basis, undefined) with the last axis in the order
    (R, L) or (X, Y); ``undefined`` counts the rows with NaN. The degenerate
    rows are not warned about here. Rows on baselines to the antennas ``skip``
    get 0 (the caller leaves them as they are).
    """
    ant1 = np.asarray(uv.ant_1_array, dtype=int)
    ant2 = np.asarray(uv.ant_2_array, dtype=int)
    if len(skip):
        kept = ~(np.isin(ant1, skip) | np.isin(ant2, skip))
        theta1, theta2 = np.zeros((ant1.size, 2)), np.zeros((ant1.size, 2))
        if kept.any():
            # The rows kept, as _position_angles reads them.
            rows = SimpleNamespace(
                ant_1_array=ant1[kept], ant_2_array=ant2[kept],
                time_array=np.asarray(uv.time_array)[kept],
                phase_center_id_array=np.asarray(uv.phase_center_id_array)[kept],
                phase_center_catalog=uv.phase_center_catalog, telescope=uv.telescope)
            out = _position_angles(rows, antennas, frame, vertical, note, warn=warn)
            theta1[kept], theta2[kept] = out[0], out[1]
            return theta1, theta2, out[2], out[3]
        return theta1, theta2, None, 0
    used = np.unique(np.concatenate([ant1, ant2]))
    if antennas is None:
        antennas = _antennas(uv, vertical, used)
    elif not hasattr(antennas, "keys"):
        raise TypeError(f"antennas must be a mapping {{antenna number: Antenna}}, got "
                        f"{type(antennas).__name__}")
    missing = [int(n) for n in used if int(n) not in antennas]
    if missing:
        raise ValueError(f"the data use antenna numbers {missing[:10]} that antennas lacks")
    bases = set()
    for n in used:
        if isinstance(antennas[int(n)], Antenna) and antennas[int(n)].receptors is not None:
            bases.add(antennas[int(n)].receptors.basis)
    if len(bases) > 1:
        raise ValueError("the antennas mix circular and linear feeds; a baseline between a "
                         "linear and a circular feed is not supported")
    basis = bases.pop() if bases else "circular"
    if warn:
        warn_unusual_angles({int(n): antennas[int(n)] for n in used}, "these data")
    products = [letter * 2 for letter in RECEPTOR_TYPES[basis]]
    sources, unprojected = phase_centre_sources(uv)
    theta1, theta2 = receptor_position_angles(
        antennas, ant1, ant2, Time(uv.time_array, format="jd", scale="utc"), sources,
        np.asarray(uv.phase_center_id_array), products=products, frame=frame,
        hint="the data give no telescope.feed_array/feed_angle; set them, or pass "
             "antennas= with Receptors (or feeds=, --feeds R,L on the command line)"
             + (f"; {note}" if note else ""))
    if unprojected:
        # An alt-az antenna pointing at the zenith has no defined orientation.
        altaz = np.array([isinstance(antennas[int(n)].mount, AltAzMount) for n in used])
        pos1, pos2 = np.searchsorted(used, ant1), np.searchsorted(used, ant2)
        rows = np.isin(uv.phase_center_id_array, list(unprojected))
        theta1[rows & altaz[pos1]] = np.nan
        theta2[rows & altaz[pos2]] = np.nan
    undefined = int(np.count_nonzero(np.isnan(theta1).any(-1) | np.isnan(theta2).any(-1)))
    return theta1, theta2, basis, undefined


def _faraday(uv, antennas, vertical, skip, ionosphere):
    """RM (rad m^-2) of the lines of sight of ant_1 and ant_2 (Nblts,) each (0 on the
    baselines to the antennas ``skip``), and lambda^2 (m^2) of the channels."""
    ant1 = np.asarray(uv.ant_1_array, dtype=int)
    ant2 = np.asarray(uv.ant_2_array, dtype=int)
    kept = ~(np.isin(ant1, skip) | np.isin(ant2, skip))
    used = np.unique(np.concatenate([ant1[kept], ant2[kept]]))
    if antennas is None:
        antennas = _antennas(uv, vertical, used)
    lambda2 = lambda_squared(np.ravel(uv.freq_array), "the data (freq_array)")
    rm = np.zeros((2, ant1.size))
    if kept.any():
        sources, _ = phase_centre_sources(uv)
        time = Time(np.tile(np.asarray(uv.time_array)[kept], 2), format="jd", scale="utc")
        centre = np.tile(np.asarray(uv.phase_center_id_array)[kept], 2)
        values = rotation_measure_rows(ionosphere, antennas,
                                       np.concatenate([ant1[kept], ant2[kept]]), time,
                                       sources, centre)
        rm[:, kept] = values.reshape(2, -1)
    return rm[0], rm[1], lambda2


def _frame_text(frame):
    return frame if isinstance(frame, str) else getattr(frame, "name", type(frame).__name__)


@iers_context()
def feed_rotation_uvdata(uv, *, frame="apparent", vertical="geodetic", antennas=None):
    """Position angle on the sky of both antennas' feeds, for every baseline-time.

    Parameters
    ----------
    uv : `~pyuvdata.UVData`
        The data.
    frame : str or `~astropy.coordinates.BaseCoordinateFrame`, optional
        North of reference: ``'apparent'`` (default, the true pole of date)
        or a celestial frame such as ``'icrs'`` (see
        `~astropy_feedrot.visibilities.frame_position_angle`; compare pyuvdata's
        ``phase_center_frame_pa``).
    vertical : {'geodetic', 'geocentric'}, optional
        Local vertical of the antennas made from ``uv``; ``'geocentric'``
        reproduces CASA. Ignored with ``antennas``.
    antennas : mapping, optional
        ``{antenna number: Antenna}`` (with receptors) to use instead of the
        telescope of ``uv``.

    Returns
    -------
    `~astropy.coordinates.Angle`
        Shape (Nblts, 2), degrees: for ``ant_1`` and ``ant_2`` of each row,
        the position angle :math:`\\theta = \\Phi + \\alpha` (north through
        east) of the antenna's R receptor (circular feeds) or X receptor
        (linear feeds), i.e. its feed rotation plus that receptor's angle.
        For a linear dipole fixed to the ground it is the position angle of
        the dipole's projection on the sky. NaN where undefined.

    Raises
    ------
    ImportError
        If pyuvdata is not installed.
    TypeError
        If ``uv`` is not a `~pyuvdata.UVData` object or ``antennas`` not a
        mapping of `~astropy_feedrot.Antenna`.
    ValueError
        As `antennas_from_uvdata`; for antennas without receptors, feeds
        mixing circular and linear, a ``near_field`` phase centre, epochs
        outside an ephemeris, or an unknown ``frame``.

    Warns
    -----
    DegenerateGeometryWarning
        Once, with the number of rows, if some angles are undefined (an
        alt-az antenna at the zenith: unprojected data, or a drift scan at
        the zenith).

    Notes
    -----
    Each phase centre of ``phase_center_catalog`` is followed as it moves:
    ``sidereal`` in its ``cat_frame`` (``icrs``, ``fk5`` with a Julian
    ``cat_epoch`` as equinox, ``fk4`` with a Besselian one) with proper
    motion (pyuvdata's ``cat_pm_ra`` is dRA/dt relative to J2000.0) and
    distance; ``ephem`` interpolated in ``cat_frame`` at ``cat_times`` (RA
    unwrapped; linear below four points, a cubic spline from four, as
    pyuvdata), refusing epochs outside the ephemeris; ``driftscan`` a fixed
    azimuth and elevation at the telescope location; ``unprojected`` the
    telescope's zenith, where fixed antennas are defined and alt-az ones are
    not (NaN).

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.coordinates import EarthLocation
    >>> from pyuvdata import Telescope, UVData
    >>> from astropy_feedrot.visibilities.uvdata import feed_rotation_uvdata
    >>> site = EarthLocation.from_geodetic(-107.6184 * u.deg, 34.0790 * u.deg, 2124 * u.m)
    >>> tel = Telescope.new(name="TEST", instrument="TEST", location=site,
    ...                     antenna_positions={0: [0.0, 0, 0], 1: [100.0, 0, 0]},
    ...                     feed_array=["r", "l"], feed_angle=[0.0, 0.0],
    ...                     mount_type="alt-az")
    >>> centre = {0: dict(cat_name="3C286", cat_type="sidereal", cat_lon=np.radians(202.78),
    ...                   cat_lat=np.radians(30.51), cat_frame="icrs", cat_epoch=2000.0)}
    >>> uv = UVData.new(freq_array=np.array([1.4e9]), channel_width=np.array([1e6]),
    ...                 polarization_array=["rr", "ll", "rl", "lr"], times=np.array([2460000.9]),
    ...                 integration_time=np.array([10.0]), telescope=tel,
    ...                 antpairs=[(0, 1)], do_blt_outer=True, empty=True,
    ...                 phase_center_catalog=centre)  # doctest: +IGNORE_WARNINGS
    >>> feed_rotation_uvdata(uv)  # doctest: +FLOAT_CMP
    <Angle [[-66.44957886, -66.44738958]] deg>
    """
    check_uvdata(uv)
    theta1, theta2, _, undefined = _position_angles(uv, antennas, frame, vertical)
    if undefined:
        warn_caller(f"the feed rotation is undefined in {undefined} of {uv.Nblts} "
                    "baseline-times (an alt-az antenna pointing at the zenith); they are NaN",
                    DegenerateGeometryWarning)
    return Angle(np.stack([theta1[:, 0], theta2[:, 0]], axis=-1), u.deg)


# --- correcting the visibilities ----------------------------------------------------


def _product_names(uv):
    if getattr(uv, "flex_spw_polarization_array", None) is not None:
        raise ValueError("data with a polarization per spectral window "
                         "(flex_spw_polarization_array) are not supported; call "
                         "uv.remove_flex_pol() first")
    codes = [int(c) for c in uv.polarization_array]
    stokes = [_STOKES.get(c, str(c)) for c in codes if c not in PRODUCT_CODES]
    if stokes:
        raise ValueError(
            f"the data hold Stokes or pseudo-Stokes products {stokes}: feed rotation acts on "
            "the correlations of receptors (RR, LL, RL, LR or XX, XY, YX, YY), which those "
            "have already mixed; correct the data before forming Stokes parameters")
    names = [PRODUCT_CODES[c] for c in codes]
    try:
        basis = basis_of(names)
    except ValueError:
        raise ValueError(f"the data mix circular and linear products {names}; correct data "
                         "of one basis at a time") from None
    if basis == "linear" and not {"XX", "XY", "YX", "YY"} <= set(names):
        raise ValueError(
            f"the data hold the linear products {names} only: the feed rotation of linear "
            "feeds mixes XX, XY, YX and YY, so it cannot be removed visibility by "
            "visibility without all four. Image Stokes Q and U instead and rotate Q + iU "
            "by minus twice the angle of feed_rotation_uvdata")
    return names, basis


def _chunk_rows(uv):
    """Baseline-times per chunk: the temporaries stay below data_array.nbytes / 8."""
    data = uv.data_array
    # A chunk costs about three times its rows in complex128 (the linear case
    # forms four products and four results, one polarization each).
    row_bytes = 3 * 16 * int(np.prod(data.shape[1:]))
    return max(1, int(data.nbytes // 8 // row_bytes))


@iers_context()
def _resolved(correction, uv, antennas):
    """The antennas the rows use (the data's, resolved, unless given), the orbiting
    ones, every antenna, and what the catalogue's receptors note says."""
    note, skip, antennas_all = "", [], antennas
    if (correction.feeds is not None or correction.catalogue is not False) and \
            (antennas is None or hasattr(antennas, "items")):
        used = np.unique(np.concatenate([uv.ant_1_array, uv.ant_2_array]))
        if antennas is None:  # the data's antennas, compared with the catalogue's
            antennas = correction.resolve(_antennas(uv, correction.vertical, used, keep=True),
                                          uv.telescope.name, "the data", numbers=used)
        antennas_all = antennas
        antennas, skip = usable_antennas(given_feeds(antennas, correction.feeds), used,
                                         "the data")
        if correction.feeds is not None:
            antennas = with_receptors(antennas, correction.feeds)
        antennas, note = catalogue_receptors(antennas, correction.catalogue, numbers=used,
                                             telescope=uv.telescope.name)
    return antennas, skip, antennas_all, note


def _turn(target, names, basis, theta1, theta2, faraday, direction, progress):
    """The data turned in place, a chunk of baseline-times at a time."""
    data = target.data_array
    if faraday is None:
        theta1 = theta1[:, np.newaxis, :] * u.deg  # (Nblts, 1, 2): one angle per frequency
        theta2 = theta2[:, np.newaxis, :] * u.deg
    else:  # per frequency, from the angles and RM of each place
        rm1, rm2, lambda2 = faraday
        place1, place2 = row_places(target.time_array, target.phase_center_id_array,
                                    target.ant_1_array, target.ant_2_array)
        table = np.empty((int(max(place1.max(), place2.max())) + 1, 3))
        table[place1] = np.column_stack([theta1, rm1])
        table[place2] = np.column_stack([theta2, rm2])
        angles, rm = table[:, :2], table[:, 2]
    auto = np.asarray(target.ant_1_array) == np.asarray(target.ant_2_array)
    parallel = [k for k, name in enumerate(names) if name[0] == name[1]]
    n_rows = data.shape[0]
    step = _chunk_rows(target)
    starts = range(0, n_rows, step)
    with progress_steps(progress, len(starts)) as done_step:
        for start in starts:
            chunk = slice(start, min(start + step, n_rows))
            block = data[chunk]
            if faraday is not None:
                correct_rows(block, angles, rm, place1[chunk], place2[chunk], names,
                             lambda2=lambda2, conjugate=True, direction=direction)
            else:
                with np.errstate(invalid="ignore"):  # NaN in the data stay NaN
                    correct_receptor_visibilities(block, theta1[chunk], theta2[chunk], names,
                                                  conjugate=True, out=block,
                                                  direction=direction)
            if basis == "linear":
                for row in np.flatnonzero(auto[chunk]):
                    for k in parallel:
                        block[row, ..., k].imag = 0
            done_step()


def _flag_undefined(target, theta1, theta2, faraday, undefined):
    """The baseline-times whose angles are undefined set to NaN and flagged, said once."""
    n_rows = target.data_array.shape[0]
    bad = np.isnan(theta1).any(axis=-1) | np.isnan(theta2).any(axis=-1)
    bad = bad.reshape(n_rows, -1).any(axis=1)
    if faraday is not None:
        bad |= np.isnan(faraday[0]) | np.isnan(faraday[1])
    target.data_array[bad] = np.nan
    target.flag_array[bad] = True
    warn_caller(f"the feed rotation is undefined in {undefined} of {n_rows} "
                "baseline-times (an alt-az antenna pointing at the zenith): their data "
                "are NaN and flagged", DegenerateGeometryWarning)


def _record(target, correction, skip):
    """``feed_angle`` set to the sky-fixed receptors' (removed), the history line."""
    tel = target.telescope
    if correction.direction == "remove" and tel.feed_array is not None:
        sky = {"x": 0.0, "y": np.pi / 2, "r": 0.0, "l": 0.0}
        angles = np.vectorize(lambda f: sky[str(f).lower()], otypes=[float])(tel.feed_array)
        untouched = np.isin(tel.antenna_numbers, skip)  # orbiting: as they were
        angles[untouched] = np.asarray(tel.feed_angle, dtype=float)[untouched]
        tel.feed_angle = angles
    what = "data_array" + ("; feed_angle set to match" if correction.direction == "remove"
                           else "")
    if skip:
        what += f" (not the baselines to the orbiting antennas {', '.join(map(str, skip))})"
    what += correction.ionosphere_text(" ")
    target.history += " " + history_entry(correction.direction, what,
                                          frame=_frame_text(correction.frame),
                                          vertical=correction.vertical) + "."


def correct_uvdata(uv, *, inplace=False, antennas=None, progress=False, correction=None,
                   **options):
    """Remove the feed rotation from the visibilities of a `~pyuvdata.UVData` object.

    Parameters
    ----------
    uv : `~pyuvdata.UVData`
        The data: circular products (any subset of RR, LL, RL, LR, any
        order) or all four linear ones (XX, XY, YX, YY, any order), with
        ``telescope.mount_type``, ``feed_array`` and ``feed_angle``.
    inplace : bool, optional
        False (default): return a corrected copy and leave ``uv`` as it was.
        True: correct ``uv`` itself, in chunks of baseline-times whose
        temporaries stay below a quarter of ``data_array``'s size, and
        return it.
    antennas : mapping, optional
        ``{antenna number: Antenna}`` to use instead of the telescope of ``uv``.
    progress : bool or callable, optional
        True shows astropy's `~astropy.utils.console.ProgressBar` over the
        chunks; a callable is called as ``progress(done, total)`` after each.
    correction : `~astropy_feedrot.visibilities.Correction`, optional
        The correction's options (direction, frame, convention, vertical,
        pole, feeds, mounts, catalogue, ionosphere, redo), made once...
    **options
        ...or given here, as `~astropy_feedrot.visibilities.Correction`
        takes them. With ``direction='apply'``, ``feed_angle`` is left as
        it is; the catalogue also gives receptors by ``telescope.name``;
        ``mounts`` is not for ``antennas`` given (those are used as given);
        with an ionosphere, lambda^2 comes from ``freq_array``.

    Returns
    -------
    `~pyuvdata.UVData`
        The corrected data: receptors fixed on the sky, circular R and L, or
        linear X toward the north and Y toward the east of ``frame``.
        ``telescope.feed_angle`` is set to 0 for X, R and L and 90 deg for Y
        (for every mount this is how pyuvdata reads a feed at those position
        angles with no rotation left), and one line is appended to the
        history.

    Raises
    ------
    ImportError
        If pyuvdata is not installed.
    TypeError
        If ``uv`` is not a `~pyuvdata.UVData` object, or ``progress`` is
        neither a bool nor a callable.
    IonosphereError, ValueError
        As every correction (`~astropy_feedrot.visibilities.Correction`),
        ``uv`` unchanged; and for Stokes or pseudo-Stokes data, linear data
        without all four products (parallel hands only: rotate Stokes Q + iU
        after imaging), products or feeds mixing circular and linear, no
        data_array, and as `feed_rotation_uvdata`.

    Warns
    -----
    DegenerateGeometryWarning, CatalogueMountWarning, UncorrectedBaselinesWarning
        As every correction (`~astropy_feedrot.visibilities.Correction`):
        baseline-times whose feed rotation is undefined are NaN and flagged;
        those on baselines to an orbiting antenna are left as they were (and
        its ``feed_angle``).

    Notes
    -----
    The visibilities follow pyuvdata's convention, the complex conjugate of
    :math:`\\langle v_1 v_2^* \\rangle`
    (`~astropy_feedrot.applied.correction.correct_receptor_visibilities` with
    ``conjugate=True``). Autocorrelations are corrected as any row: RR and LL
    do not change, RL and LR turn by twice the feed rotation, and for linear
    feeds the parallel hands are set exactly real (the corrected coherency is
    Hermitian; only rounding made them complex).

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.coordinates import EarthLocation
    >>> from pyuvdata import Telescope, UVData
    >>> from astropy_feedrot.visibilities.uvdata import correct_uvdata, feed_rotation_uvdata
    >>> site = EarthLocation.from_geodetic(-107.6184 * u.deg, 34.0790 * u.deg, 2124 * u.m)
    >>> tel = Telescope.new(name="TEST", instrument="TEST", location=site,
    ...                     antenna_positions={0: [0.0, 0, 0], 1: [100.0, 0, 0]},
    ...                     feed_array=["r", "l"], feed_angle=[0.0, 0.0],
    ...                     mount_type="alt-az")
    >>> centre = {0: dict(cat_name="3C286", cat_type="sidereal", cat_lon=np.radians(202.78),
    ...                   cat_lat=np.radians(30.51), cat_frame="icrs", cat_epoch=2000.0)}
    >>> uv = UVData.new(freq_array=np.array([1.4e9]), channel_width=np.array([1e6]),
    ...                 polarization_array=["rr", "ll", "rl", "lr"], times=np.array([2460000.9]),
    ...                 integration_time=np.array([10.0]), telescope=tel,
    ...                 antpairs=[(0, 1)], do_blt_outer=True, empty=True,
    ...                 phase_center_catalog=centre)  # doctest: +IGNORE_WARNINGS
    >>> uv.data_array[:] = 1.0
    >>> fixed = correct_uvdata(uv)
    >>> theta = feed_rotation_uvdata(uv)[0].to_value(u.rad)
    >>> rl = fixed.data_array[0, 0, 2]  # conj(RL) turned by theta_1 + theta_2
    >>> bool(np.isclose(rl, np.exp(-1j * (theta[0] + theta[1]))))
    True
    >>> float(np.abs(uv.data_array[0, 0, 2] - 1))  # uv itself is unchanged
    0.0
    """
    correction = Correction.of(correction, **options)
    check_uvdata(uv)
    if antennas is None:  # the data's own antennas: an aperture array's are refused first
        correction.refuse_aperture_array(uv.telescope.name, "the data")
    names, basis = _product_names(uv)
    correction.check_history(uv.history, "these data")
    if uv.data_array is None:
        raise ValueError("uv has no data_array (metadata only); read the data too")
    antennas, skip, antennas_all, note = _resolved(correction, uv, antennas)
    with correction.pole_context():
        theta1, theta2, basis_feeds, undefined = _position_angles(
            uv, antennas, correction.frame, correction.vertical, note, skip, warn=True)
    if basis_feeds is not None and basis_feeds != basis:
        raise ValueError(f"the data hold {basis} products {names} but the feeds are "
                         f"{basis_feeds}")
    faraday = None if correction.ionosphere is None else \
        _faraday(uv, antennas, correction.vertical, skip, correction.ionosphere)
    target = uv if inplace else uv.copy()
    data = target.data_array
    # Rows on baselines to an orbiting antenna: kept as they are.
    skipped = np.flatnonzero(np.isin(target.ant_1_array, skip) |
                             np.isin(target.ant_2_array, skip)) if skip else np.zeros(0, int)
    kept_rows = data[skipped].copy()
    if faraday is not None:  # per frequency, a chunk at a time
        undefined = int(np.count_nonzero(np.isnan(theta1).any(-1) | np.isnan(theta2).any(-1)
                                         | np.isnan(faraday[0]) | np.isnan(faraday[1])))
    _turn(target, names, basis, theta1, theta2, faraday, correction.direction, progress)
    data[skipped] = kept_rows
    if undefined:
        _flag_undefined(target, theta1, theta2, faraday, undefined)
    _record(target, correction, skip)
    warn_skipped(antennas_all, skip, skipped.size, data.shape[0], "the data")
    return target
