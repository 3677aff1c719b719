# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The phase centres of pyuvdata's ``phase_center_catalog`` as sources of feed rotation.

Sidereal centres become `~astropy.coordinates.SkyCoord` objects; ephemerides
and drift scans become functions of the epochs, which
`~astropy_feedrot.visibilities.feed_rotation_rows` follows as they move.
"""

import numpy as np
from astropy import units as u
from astropy.coordinates import AltAz, SkyCoord
from astropy.time import Time

__all__ = ["phase_centre_sources"]


def _epoch(frame, epoch, default):
    if epoch is None:
        epoch = default
    return Time(float(epoch), format="byear" if frame.startswith("fk4") else "jyear")


def _sidereal(entry):
    frame = str(entry.get("cat_frame") or "icrs").lower()
    kwargs = {}
    if frame in ("fk5", "fk4", "fk4noeterms"):
        kwargs["equinox"] = _epoch(frame, entry.get("cat_epoch"),
                                   1950.0 if frame.startswith("fk4") else 2000.0)
    lat = float(entry["cat_lat"])
    pm_ra, pm_dec = entry.get("cat_pm_ra"), entry.get("cat_pm_dec")
    if pm_ra is not None or pm_dec is not None:
        # pyuvdata: mas/yr, dRA/dt (not times cos dec), relative to J2000.0.
        kwargs["pm_ra_cosdec"] = float(pm_ra or 0.0) * np.cos(lat) * u.mas / u.yr
        kwargs["pm_dec"] = float(pm_dec or 0.0) * u.mas / u.yr
        kwargs["obstime"] = Time(2000.0, format="jyear")
    if entry.get("cat_dist") is not None:
        kwargs["distance"] = float(entry["cat_dist"]) * u.pc
    return SkyCoord(float(entry["cat_lon"]) * u.rad, lat * u.rad, frame=frame, **kwargs)


class _Ephemeris:
    """A source interpolated from pyuvdata's ephemeris (cat_times, cat_lon, cat_lat)."""

    def __init__(self, entry):
        self.name = entry.get("cat_name")
        self.times = np.asarray(entry["cat_times"], dtype=float).reshape(-1)
        order = np.argsort(self.times)
        self.times = self.times[order]
        self.lon = np.unwrap(np.asarray(entry["cat_lon"], dtype=float).reshape(-1)[order])
        self.lat = np.asarray(entry["cat_lat"], dtype=float).reshape(-1)[order]
        dist = entry.get("cat_dist")
        self.dist = None if dist is None else np.broadcast_to(
            np.asarray(dist, dtype=float), self.times.shape)[order]
        self.frame = str(entry.get("cat_frame") or "icrs").lower()
        self.epoch = entry.get("cat_epoch")

    def _interp(self, jd, values):
        if self.times.size == 1:
            return np.full(jd.shape, values[0])
        if self.times.size < 4:
            return np.interp(jd, self.times, values)
        from scipy.interpolate import make_interp_spline  # a dependency of pyuvdata

        return make_interp_spline(self.times, values, k=3)(jd)

    def __call__(self, epochs):
        jd = epochs.utc.jd
        first, last = self.times[0], self.times[-1]
        # Half a microsecond of slack for rounding in the Julian dates.
        slack = 0.5e-6 / 86400
        outside = (jd < first - slack) | (jd > last + slack)
        if np.any(outside):
            raise ValueError(
                f"the ephemeris of phase centre {self.name!r} covers JD {first:.6f} to "
                f"{last:.6f} but the data reach JD {jd[outside].min():.6f}-"
                f"{jd[outside].max():.6f}; extrapolating a moving source is refused: give "
                "an ephemeris that spans the observation")
        lon = self._interp(jd, self.lon) * u.rad
        lat = self._interp(jd, self.lat) * u.rad
        kwargs = {}
        if self.frame in ("fk5", "fk4", "fk4noeterms"):
            kwargs["equinox"] = _epoch(self.frame, self.epoch,
                                       1950.0 if self.frame.startswith("fk4") else 2000.0)
        if self.dist is not None:
            kwargs["distance"] = self._interp(jd, self.dist) * u.pc
        return SkyCoord(lon, lat, frame=self.frame, **kwargs)


class _FixedAltAz:
    """A fixed azimuth and elevation at the telescope (drift scans, unprojected data)."""

    def __init__(self, az, el, location):
        self.az, self.el, self.location = az, el, location

    def __call__(self, epochs):
        n = epochs.size
        return SkyCoord(AltAz(az=np.full(n, self.az) * u.rad, alt=np.full(n, self.el) * u.rad,
                              obstime=epochs, location=self.location))


def phase_centre_sources(uv):
    """The sources of a `~pyuvdata.UVData` object's phase centres, as feed rotation needs them.

    Parameters
    ----------
    uv : `~pyuvdata.UVData`
        Data with a ``phase_center_catalog``.

    Returns
    -------
    sources : dict
        ``{catalogue id: source}``: a `~astropy.coordinates.SkyCoord` for a
        sidereal centre (its frame, equinox, proper motion and distance), a
        function of the epochs for an ephemeris (interpolated) or a drift
        scan (a fixed azimuth and elevation), as
        `~astropy_feedrot.visibilities.feed_rotation_rows` takes them.
    unprojected : set
        The ids of unprojected centres (the zenith).

    Raises
    ------
    ValueError
        For a phase centre of another type.

    Examples
    --------
    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> from astropy_feedrot.visibilities.phase_centres import phase_centre_sources
    >>> uv = SimpleNamespace(phase_center_catalog={0: dict(
    ...     cat_name="3C286", cat_type="sidereal", cat_lon=np.radians(202.78),
    ...     cat_lat=np.radians(30.51), cat_frame="icrs", cat_epoch=2000.0)})
    >>> sources, unprojected = phase_centre_sources(uv)
    >>> round(float(sources[0].ra.deg), 2), unprojected
    (202.78, set())
    """
    sources, unprojected = {}, set()
    for key, entry in uv.phase_center_catalog.items():
        kind = entry["cat_type"]
        for field in ("cat_lon", "cat_lat"):
            value = entry.get(field)
            if value is not None and not np.all(np.isfinite(np.asarray(value, float))):
                raise ValueError(f"phase centre {entry.get('cat_name')!r} (id {key}) has "
                                 f"{field} {value}, not a number: every angle of its rows "
                                 "would be NaN; give its position in phase_center_catalog")
        if kind == "sidereal":
            sources[key] = _sidereal(entry)
        elif kind == "ephem":
            sources[key] = _Ephemeris(entry)
        elif kind in ("driftscan", "unprojected"):
            az = float(entry.get("cat_lon") or 0.0)
            el = float(np.pi / 2 if entry.get("cat_lat") is None else entry["cat_lat"])
            sources[key] = _FixedAltAz(az, el, uv.telescope.location)
            if kind == "unprojected":
                unprojected.add(key)
        else:
            raise ValueError(f"phase centre {entry.get('cat_name')!r} is of type {kind!r}; "
                             "feed rotation is computed for sidereal, ephem, driftscan and "
                             "unprojected phase centres")
    return sources, unprojected
