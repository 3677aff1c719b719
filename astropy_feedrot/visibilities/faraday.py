# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The ionosphere's Faraday rotation in a correction: rotation measures per antenna and
epoch, lambda^2 per channel, and the angle that enters the correction.

The ionosphere turns the wave's plane of polarization by chi = RM lambda^2
before it reaches an antenna; for the receptors that is the same as a feed
turned by -chi. A correction that removes both takes, for each receptor of
each antenna, the position angle

.. math:: \\theta - \\mathrm{RM}\\,\\lambda^2(\\nu)

per row *and per channel* (the feed rotation's :math:`\\theta` is one per
row). Here:

* `rotation_measure_rows`: the RM of each (epoch, source, antenna) once,
  with `~astropy_feedrot.ionosphere.Ionosphere.rotation_measure` (IONEX maps
  on its 60 s grid, interpolated to the epochs; or a table); the formats look
  their rows up as they do the feed rotation
  (`~astropy_feedrot.visibilities.ReceptorAngleTable`);
* the channels' lambda^2 of each format: `ms_lambda_squared` (``CHAN_FREQ``
  of ``SPECTRAL_WINDOW``), `fitsidi_lambda_squared` (``REF_FREQ`` of
  ``UV_DATA``, ``BANDFREQ`` and ``CH_WIDTH`` of ``FREQUENCY``),
  `lambda_squared` (pyuvdata's ``freq_array``);
* `faraday_angles`: the receptors' angles per row and channel;
* `correct_rows`: rows corrected from the angles and RM of their antennas'
  places (`row_places` for rows that carry their own, `rows_lambda_squared`
  for FITS-IDI's setups); circular products take `correct_circular`, both
  rotations in one pass;
* `ionosphere_text`: what the history records.
"""

import warnings

import numpy as np
from astropy import units as u
from astropy.coordinates import BaseCoordinateFrame, EarthLocation, SkyCoord

from ..antennas.receptors import RECEPTOR_TYPES, basis_of
from ..applied.correction import correct_receptor_visibilities
from ..core.exceptions import DegenerateGeometryWarning, warn_caller
from ..core.inputs import as_skycoord
from ..core.polarization import polarization_sign
from ..ionosphere import Ionosphere, IonosphereError
from ..ionosphere.faraday import wavelength_squared
from .rows import distinct_epochs

__all__ = ["check_ionosphere", "rotation_measure_rows", "lambda_squared", "ms_lambda_squared",
           "fitsidi_lambda_squared", "faraday_angles", "ionosphere_text", "correct_rows",
           "correct_circular", "row_places", "rows_lambda_squared"]


def check_ionosphere(ionosphere):
    """``ionosphere`` itself if it is None or an `~astropy_feedrot.ionosphere.Ionosphere`.

    Raises
    ------
    TypeError
        For anything else, saying how to make one.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.faraday import check_ionosphere
    >>> check_ionosphere(None) is None
    True
    """
    if ionosphere is None or isinstance(ionosphere, Ionosphere):
        return ionosphere
    raise TypeError(f"ionosphere must be an Ionosphere (Ionosphere.from_ionex(files) or "
                    f"Ionosphere.from_rm(table)), got {type(ionosphere).__name__}")


def ionosphere_text(ionosphere, before=""):
    """What a correction's history says of the ionosphere it removed (or applied).

    ``before`` precedes the text; an empty text for no ionosphere (None).

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.table import QTable
    >>> from astropy.time import Time
    >>> from astropy_feedrot.ionosphere import Ionosphere
    >>> from astropy_feedrot.visibilities.faraday import ionosphere_text
    >>> table = QTable({"time": Time(["2024-06-01T00:00", "2024-06-01T02:00"]),
    ...                 "rm": [1.0, 3.0] * u.rad / u.m**2})
    >>> print(ionosphere_text(Ionosphere.from_rm(table)))
    and the ionospheric Faraday rotation (RM lambda^2 per channel) from a table of rotation ...
    """
    if ionosphere is None:
        return ""
    if ionosphere.files:
        names = ", ".join(path.name for path in ionosphere.files)
        source = (f"the IONEX files {names} (shell at {ionosphere.height.to_value(u.km):g} km, "
                  "IGRF through spinifex)")
    else:
        source = "a table of rotation measures"
    return f"{before}and the ionospheric Faraday rotation (RM lambda^2 per channel) from {source}"


def _sites(antennas, keys):
    """The distinct sites of antennas ``keys``: (EarthLocation (S,), names, site of each key)."""
    seen, site_of = {}, []
    for key in keys:
        antenna = antennas[int(key)]
        xyz = tuple(np.round(antenna.location.to_geocentric()[i].to_value(u.m), 3)
                    for i in range(3))
        name = None if antenna.name is None else str(antenna.name)
        site_of.append(seen.setdefault((name, xyz), len(seen)))
    xyz = np.array([place for _, place in seen], dtype=float).reshape(-1, 3)
    location = EarthLocation.from_geocentric(xyz[:, 0], xyz[:, 1], xyz[:, 2], unit=u.m)
    names = [name for name, _ in seen]
    return location, (None if any(n is None for n in names) else names), np.array(site_of)


def rotation_measure_rows(ionosphere, antennas, keys, obstime, sources, source_keys,
                          where="the data"):
    """The rotation measure of the line of sight of each (epoch, source, antenna).

    Parameters
    ----------
    ionosphere : `~astropy_feedrot.ionosphere.Ionosphere`
        IONEX maps or a table of rotation measures.
    antennas : mapping
        ``{key: Antenna}``; an antenna's ``name`` selects its series of a
        table per antenna.
    keys : array-like of int, shape (N,)
        The antenna of each entry.
    obstime : `~astropy.time.Time`, shape (N,)
        The epoch of each entry.
    sources : mapping
        ``{source key: SkyCoord, or a function of the epochs for a moving
        source}`` (as `~astropy_feedrot.visibilities.feed_rotation_rows`).
    source_keys : array-like, shape (N,)
        The source of each entry.
    where : str, optional
        The data, for messages.

    Returns
    -------
    `~numpy.ndarray`
        RM in rad m^-2, shape (N,); NaN where the source is below an
        antenna's horizon.

    Raises
    ------
    IonosphereError
        If the ionosphere does not cover the epochs, or a table per antenna
        lacks an antenna (named): one line, before any data are written.

    Notes
    -----
    Each source is asked once, at its distinct epochs, for all the distinct
    sites at once: with IONEX maps the RM is computed on the ionosphere's
    coarse grid (60 s) and interpolated, so its cost grows with the length of
    the observation and the number of antennas, not with the rows.

    Examples
    --------
    >>> import numpy as np, astropy.units as u
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy.table import QTable
    >>> from astropy.time import Time
    >>> from astropy_feedrot import get_antenna
    >>> from astropy_feedrot.ionosphere import Ionosphere
    >>> from astropy_feedrot.visibilities.faraday import rotation_measure_rows
    >>> table = QTable({"time": Time(["2023-01-25T19:00", "2023-01-25T23:00"] * 2),
    ...                 "rm": [1.0, 3.0, 2.0, 2.0] * u.rad / u.m**2,
    ...                 "antenna": ["FD-VLBA", "FD-VLBA", "PIETOWN", "PIETOWN"]})
    >>> antennas = {1: get_antenna("FD-VLBA"), 2: get_antenna("PIETOWN")}
    >>> rotation_measure_rows(Ionosphere.from_rm(table), antennas, [1, 2, 1],
    ...                       Time(["2023-01-25T20:00"] * 2 + ["2023-01-25T21:00"]),
    ...                       {0: SkyCoord("3h19m48s +41d30m42s")}, [0, 0, 0])
    array([1.5, 2. , 2. ])
    """
    keys = np.asarray(keys, dtype=int)
    source_keys = np.asarray(source_keys)
    out = np.full(keys.size, np.nan)
    for source in np.unique(source_keys).tolist():
        rows = np.flatnonzero(source_keys == source)
        epochs, at = distinct_epochs(obstime[rows])
        used, site_key = np.unique(keys[rows], return_inverse=True)
        location, names, site_of = _sites(antennas, used)
        target = sources[source]
        if callable(target) and not isinstance(target, (SkyCoord, BaseCoordinateFrame)):
            target = as_skycoord(target(epochs))  # a moving source: one position an epoch
            target = target.reshape(target.shape + (1,))
            epochs_asked = epochs.reshape(epochs.shape + (1,))
        else:
            epochs_asked = epochs
        try:
            with warnings.catch_warnings():  # counted below, once for all sources
                warnings.simplefilter("ignore", DegenerateGeometryWarning)
                rm = ionosphere.rotation_measure(location, target, epochs_asked, antenna=names)
        except IonosphereError as error:
            raise IonosphereError(f"{where}: {error}") from None
        rm = np.asarray(rm.to_value(u.rad / u.m**2)).reshape(epochs.size, location.size)
        out[rows] = rm[at, site_of[site_key.reshape(-1)]]
    below = int(np.count_nonzero(np.isnan(out)))
    if below:
        warn_caller(f"{where}: the rotation measure is undefined for {below} of {out.size} "
                    "(epoch, source, antenna), where the source is below the antenna's "
                    "horizon: the rows of those antennas and epochs are set to NaN (flagged)",
                    DegenerateGeometryWarning)
    return out


def lambda_squared(frequency, where="the data"):
    """The squared wavelength (m^2) of each channel, from frequencies in Hz.

    Parameters
    ----------
    frequency : array-like
        Channel frequencies in Hz (a `~astropy.units.Quantity` with a
        spectral unit is also taken).
    where : str, optional
        The data, for messages.

    Returns
    -------
    `~numpy.ndarray`
        (c / nu)^2 in m^2, of the shape of ``frequency``.

    Raises
    ------
    ValueError
        If a frequency is not positive and finite: lambda^2 would be wrong.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.faraday import lambda_squared
    >>> lambda_squared([1.4e9, 5e9])  # doctest: +FLOAT_CMP
    array([0.04585486, 0.00359502])
    """
    if isinstance(frequency, u.Quantity):
        frequency = frequency.to_value(u.Hz, equivalencies=u.spectral())
    return wavelength_squared(frequency, f"{where}: channel frequency {{hertz:g}} Hz is not "
                              "positive: the Faraday rotation RM lambda^2 needs each channel's "
                              "frequency; fix the file's frequency axis")


def ms_lambda_squared(path, tables):
    """lambda^2 (m^2) of the channels of each spectral window of a Measurement Set.

    Parameters
    ----------
    path : path-like
        The Measurement Set.
    tables : module
        ``casacore.tables``.

    Returns
    -------
    dict
        ``{SPECTRAL_WINDOW row: lambda^2 of its channels (CHAN_FREQ, Hz)}``.
    """
    out = {}
    with tables.table(str(path / "SPECTRAL_WINDOW"), ack=False) as table:
        for row in range(table.nrows()):
            frequency = np.asarray(table.getcell("CHAN_FREQ", row), dtype=float)
            out[row] = lambda_squared(frequency, f"{str(path)!r}, table SPECTRAL_WINDOW, "
                                                 f"row {row}")
    return out


def fitsidi_lambda_squared(hdul, index, name):
    """lambda^2 (m^2) of the samples of one ``UV_DATA`` table's ``FLUX``, per ``FREQID``.

    The frequency of channel ``k`` (1-based) of band ``b``: ``REF_FREQ`` (or
    the FREQ axis' ``CRVAL``) + ``BANDFREQ[b]`` + (k - ``REF_PIXL``) *
    ``CH_WIDTH[b]`` (FITS-IDI, AIPS Memo 114).

    Parameters
    ----------
    hdul : `~astropy.io.fits.HDUList`
        The file.
    index : int
        The ``UV_DATA`` extension.
    name : str
        The file, for messages.

    Returns
    -------
    column : str or None
        The column of each row's ``FREQID`` (None: one setup).
    values : dict
        ``{FREQID: lambda^2}``, each shaped as a row's ``FLUX`` in numpy
        order without its ``COMPLEX`` and ``STOKES`` axes, with length 1 on
        the axes other than ``FREQ`` and ``BAND``.

    Raises
    ------
    ValueError
        If the frequencies cannot be read (no ``FREQUENCY`` table, no FREQ
        axis); the message names what is missing.
    """
    hdu = hdul[index]
    header = hdu.header
    naxes = int(header["MAXIS"])
    types = [str(header.get(f"CTYPE{k}", "")).strip().upper() for k in range(1, naxes + 1)]
    dims = [int(header[f"MAXIS{k}"]) for k in range(1, naxes + 1)]
    if "FREQ" not in types:
        raise ValueError(f"{name}, table UV_DATA: no FREQ axis (CTYPEn): the Faraday "
                         "rotation needs each channel's frequency")
    k = types.index("FREQ") + 1
    reference = float(header.get("REF_FREQ", header.get(f"CRVAL{k}", np.nan)))
    pixel = float(header.get("REF_PIXL", header.get(f"CRPIX{k}", 1.0)))
    channels = dims[k - 1]
    frequency_table = next((h for h in hdul if h.name == "FREQUENCY"), None)
    if frequency_table is None:
        raise ValueError(f"{name}: no FREQUENCY table: the Faraday rotation needs each "
                         "channel's frequency")
    data = frequency_table.data
    bands = dims[types.index("BAND")] if "BAND" in types else 1
    # Numpy order of a row's FLUX: the FITS axes reversed; COMPLEX and STOKES dropped.
    kept = [t for t in reversed(types) if t not in ("COMPLEX", "STOKES")]
    shape = [1] * len(kept)
    shape[kept.index("FREQ")] = channels
    if "BAND" in kept:
        shape[kept.index("BAND")] = bands
    values = {}
    for row in range(len(data)):
        freqid = int(data["FREQID"][row]) if "FREQID" in data.names else 1
        offset = np.asarray(data["BANDFREQ"][row], dtype=float).reshape(-1)[:bands]
        width = np.asarray(data["CH_WIDTH"][row], dtype=float).reshape(-1)[:bands]
        hertz = reference + offset[:, None] + (np.arange(channels) + 1 - pixel) * width[:, None]
        if "BAND" in kept and kept.index("BAND") > kept.index("FREQ"):
            hertz = hertz.T
        values[freqid] = lambda_squared(hertz, f"{name}, table FREQUENCY, FREQID {freqid}"
                                        ).reshape(shape)
    column = "FREQID" if "FREQID" in hdu.columns.names else None
    return column, values


def faraday_angles(theta, rm, lambda2, per_row=False):
    """The receptors' position angles (deg) per row and channel, the Faraday rotation taken.

    Parameters
    ----------
    theta : `~numpy.ndarray`, shape (N, 2)
        The receptors' position angles (deg) of one antenna of each row.
    rm : `~numpy.ndarray`, shape (N,)
        The rotation measure (rad m^-2) of its line of sight.
    lambda2 : `~numpy.ndarray`, shape (...) or (N, ...)
        lambda^2 (m^2) of the channels, the same for every row, or per row
        with ``per_row``.
    per_row : bool, optional
        Whether the first axis of ``lambda2`` is the rows'.

    Returns
    -------
    `~numpy.ndarray`
        theta - degrees(RM lambda^2), shape (N, ..., 2): the ionosphere turns
        the wave by +RM lambda^2, which the receptors see as a feed turned by
        -RM lambda^2.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.visibilities.faraday import faraday_angles
    >>> faraday_angles(np.array([[10.0, 10.0]]), np.array([np.pi / 180]),
    ...                np.array([1.0, 2.0]))  # doctest: +FLOAT_CMP
    array([[[9., 9.],
            [8., 8.]]])
    """
    lambda2 = np.asarray(lambda2, dtype=float)
    if not per_row:
        lambda2 = lambda2[np.newaxis]
    chi = np.degrees(rm.reshape((-1,) + (1,) * (lambda2.ndim - 1)) * lambda2)
    return theta.reshape((theta.shape[0],) + (1,) * (chi.ndim - 1) + (2,)) - chi[..., None]


def correct_rows(data, angles, rm, place1, place2, products, *, lambda2=None, per_row=False,
                 conjugate=False, direction="remove"):
    """Correct rows of visibilities in place for the feed rotation and the Faraday rotation.

    The receptors' angles (and rotation measures) are given once per place,
    an antenna at an epoch and source, as
    `~astropy_feedrot.visibilities.ReceptorAngleTable` holds them; each row
    names the places of its two antennas. With the Faraday rotation, circular
    products with one set of channels for every row take `correct_circular`;
    the others, the angles per channel (`faraday_angles`) through
    `~astropy_feedrot.applied.correction.correct_receptor_visibilities`, as
    the feed rotation alone does with one angle pair per row.

    Parameters
    ----------
    data : `~numpy.ndarray`, shape (N, ..., P)
        Visibilities with the products last, corrected in place.
    angles : `~numpy.ndarray`, shape (K, 2)
        The receptors' position angles (deg) of each place.
    rm : `~numpy.ndarray`, shape (K,), or None
        The rotation measure (rad m^-2) of each place (with ``lambda2``).
    place1, place2 : `~numpy.ndarray` of int, shape (N,)
        The places of the two antennas of each row.
    products : sequence of str
        The products, in the order of the data.
    lambda2 : `~numpy.ndarray`, optional
        lambda^2 (m^2) of a row's samples (or, with ``per_row``, of each
        row's); None: the feed rotation only.
    per_row : bool, optional
        Whether the first axis of ``lambda2`` is the rows'.
    conjugate : bool, optional
        Data in pyuvdata's (and FITS-IDI's) conjugated convention.
    direction : {'remove', 'apply'}, optional
        As in `~astropy_feedrot.applied.correction.correct_receptor_visibilities`.

    Returns
    -------
    `~numpy.ndarray` of bool, shape (N,)
        The rows whose angles or rotation measures are NaN (their data are
        NaN; the caller flags them).

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.visibilities.faraday import correct_rows
    >>> data = np.exp(1j * np.radians([[[-20.0, 20.0]]]))  # RR, LL
    >>> bad = correct_rows(data, np.array([[0.0, 0.0], [20.0, 20.0]]), None,
    ...                    np.array([1]), np.array([0]), ["RR", "LL"])
    >>> np.round(np.degrees(np.angle(data)), 9) + 0.0, bad
    (array([[[0., 0.]]]), array([False]))
    """
    theta1, theta2 = angles[place1], angles[place2]
    bad = np.isnan(theta1).any(axis=1) | np.isnan(theta2).any(axis=1)
    if lambda2 is not None:
        rm1, rm2 = rm[place1], rm[place2]
        bad |= np.isnan(rm1) | np.isnan(rm2)
    with np.errstate(invalid="ignore"):  # NaN and inf in the data give NaN
        if lambda2 is not None and not per_row and basis_of(products) == "circular":
            correct_circular(data, angles, rm, place1, place2, lambda2, products,
                             conjugate=conjugate, direction=direction)
            return bad
        if lambda2 is None:  # one angle pair per row, for every sample
            expand = (theta1.shape[0],) + (1,) * (data.ndim - 2) + (2,)
            theta1, theta2 = theta1.reshape(expand), theta2.reshape(expand)
        else:  # the angles per sample
            theta1 = faraday_angles(theta1, rm1, lambda2, per_row)
            theta2 = faraday_angles(theta2, rm2, lambda2, per_row)
        correct_receptor_visibilities(data, theta1 * u.deg, theta2 * u.deg, products,
                                      conjugate=conjugate, out=data, direction=direction)
    return bad


def row_places(time, centre, antenna1, antenna2):
    """Places of the two antennas of each row: an antenna at an epoch and phase centre.

    For `correct_rows` where the rows give their own angles (pyuvdata's
    ``UVData``): the angles of a place are those of any row at it.

    Parameters
    ----------
    time, centre, antenna1, antenna2 : `~numpy.ndarray`, shape (N,)
        Each row's epoch, phase centre and antennas.

    Returns
    -------
    place1, place2 : `~numpy.ndarray` of int, shape (N,)
        Indices from 0 to the number of places less one.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.visibilities.faraday import row_places
    >>> row_places(np.array([5.0, 5.0, 6.0]), np.zeros(3), np.array([0, 0, 1]),
    ...            np.array([1, 2, 2]))
    (array([0, 0, 3]), array([1, 2, 4]))
    """
    epoch = np.unique(time, return_inverse=True)[1].reshape(-1)
    field = np.unique(centre, return_inverse=True)[1].reshape(-1)
    numbers, ends = np.unique(np.concatenate([antenna1, antenna2]), return_inverse=True)
    row = (epoch * (field.max() + 1) + field) * numbers.size
    codes = np.concatenate([row, row]) + ends.reshape(-1)
    at = np.unique(codes, return_inverse=True)[1].reshape(-1)
    return at[:row.size], at[row.size:]


def rows_lambda_squared(faraday, freqid=None):
    """lambda^2 of the rows' samples: one array for every row, or one per row.

    Parameters
    ----------
    faraday : dict
        ``{setup: lambda^2}`` (`fitsidi_lambda_squared`).
    freqid : `~numpy.ndarray`, optional
        The setup of each row (default: the one setup).

    Returns
    -------
    lambda2 : `~numpy.ndarray`
        Shaped as a row's samples, or with a first axis of the rows.
    per_row : bool
        Whether the first axis of ``lambda2`` is the rows'.

    Raises
    ------
    ValueError
        If rows use a setup that ``faraday`` lacks.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.visibilities.faraday import rows_lambda_squared
    >>> faraday = {1: np.array([0.04, 0.05]), 2: np.array([0.01, 0.02])}
    >>> rows_lambda_squared(faraday, np.array([1, 1]))
    (array([0.04, 0.05]), False)
    >>> rows_lambda_squared(faraday, np.array([2, 1]))[0]
    array([[0.01, 0.02],
           [0.04, 0.05]])
    """
    if freqid is None:
        return next(iter(faraday.values())), False
    setups = np.unique(freqid).astype(int).tolist()
    missing = sorted(set(setups) - set(faraday))
    if missing:
        raise ValueError(f"rows use FREQID {missing} that the FREQUENCY table lacks "
                         f"(it has {sorted(faraday)}): their frequencies are unknown")
    if len(setups) == 1:
        return faraday[setups[0]], False
    return np.stack([faraday[int(f)] for f in freqid]), True


# Rows of circular products corrected at once by `correct_circular`: about this many bytes of
# their factors (they stay in the cache between their making and their use).
_BLOCK_BYTES = 2**18


def correct_circular(data, theta, rm, place1, place2, lambda2, products, *,
                     conjugate=False, direction="remove"):
    """Remove (or apply) the feed and Faraday rotations of circular products, in place.

    For circular receptors the correction of product pq is one phase factor,
    :math:`e^{i s_p (\\theta_{1p} - \\chi_1)} \\, e^{-i s_q (\\theta_{2q} - \\chi_2)}`
    (:math:`s_R = 1`, :math:`s_L = -1`, :math:`\\chi = \\mathrm{RM}\\,\\lambda^2`), the
    product of one factor per antenna: those are computed once per place (an
    antenna at an epoch, which its baselines share) and channel, and each row
    takes one multiplication per sample, block by block in the cache. The same
    numbers as `~astropy_feedrot.applied.correction.correct_receptor_visibilities`
    with the angles of `faraday_angles`, in the data's precision.

    Parameters
    ----------
    data : `~numpy.ndarray`, shape (N, ..., P)
        Visibilities with the products last, corrected in place (any byte
        order and strides).
    theta : `~numpy.ndarray`, shape (K, 2)
        The receptors' position angles (deg), R and L, of each place.
    rm : `~numpy.ndarray`, shape (K,)
        The rotation measure (rad m^-2) of each place's line of sight.
    place1, place2 : `~numpy.ndarray` of int, shape (N,)
        The places of the two antennas of each row.
    lambda2 : `~numpy.ndarray`
        lambda^2 (m^2) of a row's samples without the products: a shape that
        broadcasts to ``data.shape[1:-1]``, the same for every row.
    products : sequence of str
        Circular products (``'RR'``, ``'LL'``, ``'RL'``, ``'LR'``), in the
        order of the data.
    conjugate : bool, optional
        Data in pyuvdata's (and FITS-IDI's) conjugated convention.
    direction : {'remove', 'apply'}, optional
        As in `~astropy_feedrot.applied.correction.correct_receptor_visibilities`.

    Examples
    --------
    RR of a baseline whose antennas see 10 and 30 deg of Faraday rotation
    (and no feed rotation) has turned by -20 deg: it is turned back.

    >>> import numpy as np
    >>> from astropy_feedrot.visibilities.faraday import correct_circular
    >>> data = np.exp(1j * np.radians([[[-20.0, 20.0]]]))
    >>> correct_circular(data, np.zeros((2, 2)), np.radians([10.0, 30.0]), np.array([0]),
    ...                  np.array([1]), np.array([1.0]), ["RR", "LL"])
    >>> np.round(np.degrees(np.angle(data)), 9) + 0.0
    array([[[0., 0.]]])
    """
    sign = (-1.0 if conjugate else 1.0) * (-1.0 if direction == "apply" else 1.0)
    n = data.shape[0]
    if n == 0:  # no rows, no places
        return
    samples = data.shape[1:-1]
    lambda2 = np.broadcast_to(np.asarray(lambda2, dtype=float), samples).reshape(-1)
    used, at1, at2 = _compact(place1, place2)
    angle = np.radians(np.asarray(theta, dtype=float)[used])
    chi = np.multiply.outer(np.asarray(rm, dtype=float)[used], lambda2)
    dtype = np.result_type(data.dtype, np.complex64).newbyteorder("=")
    phase = {}
    with np.errstate(invalid="ignore"):  # NaN angles give NaN factors (rows made NaN)
        for k, letter in enumerate(RECEPTOR_TYPES["circular"]):
            if k and np.array_equal(angle[:, k], angle[:, 0], equal_nan=True):
                phase[letter] = phase["R"].conj()  # the usual case: one angle for both
                continue
            phase[letter] = np.exp(1j * sign * polarization_sign(letter)
                                   * (angle[:, k, np.newaxis] - chi)).astype(dtype)
    names = [str(product).upper() for product in products]
    first = np.stack([phase[p] for p, _ in names], axis=-1)  # (used, samples, products)
    second = np.stack([phase[q].conj() for _, q in names], axis=-1)
    step = max(1, _BLOCK_BYTES // max(1, first[0].nbytes))
    shape = data.shape[1:]
    for start in range(0, n, step):
        rows = slice(start, min(start + step, n))
        factor = first[at1[rows]]
        factor *= second[at2[rows]]
        data[rows] *= factor.reshape((-1,) + shape)


def _compact(place1, place2):
    """The places rows use, and each row's index into them (``np.unique`` with
    ``return_inverse``, without a sort where the places lie in a short range: the
    rows of a chunk span a few epochs)."""
    place1, place2 = np.asarray(place1), np.asarray(place2)
    low = int(min(place1.min(), place2.min()))
    span = int(max(place1.max(), place2.max())) - low + 1
    if span > 4 * place1.size + 1024:
        used, at = np.unique(np.concatenate([place1, place2]), return_inverse=True)
        at = at.reshape(-1)
        return used, at[:place1.size], at[place1.size:]
    seen = np.zeros(span, dtype=bool)
    seen[place1 - low] = True
    seen[place2 - low] = True
    index = np.cumsum(seen) - 1
    return np.flatnonzero(seen) + low, index[place1 - low], index[place2 - low]
