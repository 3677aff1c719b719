# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Configuration of astropy_feedrot."""

from astropy import config as _config

__all__ = ["conf"]


class Conf(_config.ConfigNamespace):
    """Configuration parameters for `astropy_feedrot`."""

    iers_auto_download = _config.ConfigItem(
        False,
        "Whether coordinate transformations made by astropy_feedrot may download "
        "newer IERS-A Earth orientation tables. The default (False) keeps every "
        "computation offline, using the tables bundled with astropy "
        "(astropy-iers-data); set True to allow astropy's usual auto-download.",
    )
    fast_path = _config.ConfigItem(
        True,
        "Whether Earth orientation at the epochs of a call (the directions of sources "
        "fixed in a celestial frame, the TEME to ITRS rotation of SGP4 orbits, the Sun) "
        "comes from astropy_feedrot.earth.orientation.EarthOrientation, which evaluates ERFA's "
        "slow series a few times a day and the Earth's rotation at every epoch (within "
        "0.001 mas of astropy's transformation, and faster at any number of epochs), "
        "instead of astropy's transformation at every epoch. Set False for the "
        "rigorous path.",
    )
    fast_path_step = _config.ConfigItem(
        15.0,
        "No longer used (kept so that existing settings still load): the fast path "
        "chooses the spacing of its exact evaluations per quantity and by the density "
        "of the epochs.",
    )


conf = Conf()
