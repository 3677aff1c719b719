# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Test configuration: everything runs offline."""

import sys

import pytest
from astropy.utils import iers
from astropy.utils.data import conf as data_conf

# The scripts that made the test data write files when run: not test modules.
collect_ignore_glob = ["data/*"]


def pytest_configure(config):
    # The IERS tables bundled with astropy (astropy-iers-data) are enough; any
    # attempt to reach the network is an error in the tests.
    iers.conf.auto_download = False
    data_conf.allow_internet = False


@pytest.fixture(autouse=True)
def close_figures():
    """Close the figures a test drew (plotting functions leave them open)."""
    yield
    if "matplotlib.pyplot" in sys.modules:
        sys.modules["matplotlib.pyplot"].close("all")
