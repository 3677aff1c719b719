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
        "Whether the directions of fixed celestial sources at many epochs come from "
        "Earth orientation evaluated exactly every fast_path_step and interpolated "
        "(astropy_feedrot.earth; within 0.0002 mas of astropy's transformation at the "
        "default step) instead of astropy's transformation at every epoch. Set False "
        "for the rigorous path.",
    )
    fast_path_step = _config.ConfigItem(
        15.0,
        "Node spacing of the fast path in minutes. The interpolation error grows as "
        "its fourth power: about 0.0002 mas at 15 min, 0.002 mas at 30 min and "
        "0.02 mas at 60 min.",
    )


conf = Conf()
