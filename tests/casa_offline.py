# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""CASA (casatools, casatasks, casadata) run offline in a subprocess, for the
tests that compare the correction with CASA's own ``applycal(parang=True)``.

A site configuration file in a temporary directory (``CASASITECONFIG``)
points the measures and data at casadata's copy and turns every automatic
update off; ``HOME`` is that directory too, so the user's ``~/.casa`` is
never read or written. ``casa_sim.py`` beside this file holds what CASA runs.

The tests that need CASA are the files ``tests/visibilities/test_casa*.py``. CASA is not
among the test dependencies (it weighs 1.5 GB): its own extra installs it,
``python -m pip install -e ".[test-casa]"``, and ``python -m pytest
tests/visibilities/test_casa*.py`` runs them. Without it they are skipped, saying why,
except where ``FEEDROT_REQUIRE_CASA`` is set (``.ci/run`` sets it): there a
missing CASA fails them.
"""

import importlib.util
import os
import subprocess
import sys
from pathlib import Path

import pytest

MISSING = [name for name in ("casatools", "casatasks", "casadata")
           if importlib.util.find_spec(name) is None]
SKIP_WITHOUT_CASA = pytest.mark.skipif(
    bool(MISSING) and not os.environ.get("FEEDROT_REQUIRE_CASA"),
    reason=f"CASA is not installed ({', '.join(MISSING)} missing: python -m pip install "
           f"-e '.[test-casa]')")

SCRIPT = Path(__file__).parent / "casa_sim.py"


def run_casa(home, *args):
    """Run casa_sim.py with CASA configured offline in ``home``."""
    config = home / "casasiteconfig.py"
    if not config.exists():
        config.write_text(
            "import casadata\n"
            "measurespath = casadata.datapath\n"
            "datapath = [casadata.datapath]\n"
            "measures_auto_update = False\n"
            "data_auto_update = False\n"
            "nologfile = True\n"
            "nologger = True\n"
            "nogui = True\n"
            f"cachedir = {str(home / 'cache')!r}\n")
    env = dict(os.environ, HOME=str(home), CASASITECONFIG=str(config))
    result = subprocess.run([sys.executable, str(SCRIPT), *map(str, args)], cwd=home, env=env,
                            capture_output=True, text=True, timeout=600)
    assert result.returncode == 0 and "done" in result.stdout, result.stderr[-2000:]


def check_casa_starts(home):
    """Skip, saying why, if the installed CASA does not start (e.g. built for
    another numpy); fail instead where ``FEEDROT_REQUIRE_CASA`` is set (.ci/run
    sets it: a skip there would hide the comparison)."""
    if MISSING:  # only with FEEDROT_REQUIRE_CASA: else SKIP_WITHOUT_CASA skipped the test
        pytest.fail(f"CASA is not installed ({', '.join(MISSING)} missing), and "
                    "FEEDROT_REQUIRE_CASA asks for its tests: python -m pip install -e "
                    "'.[test-casa]'")
    try:
        run_casa(home, "check")
    except AssertionError as error:
        lines = [line for line in str(error).splitlines() if line.strip()]
        reason = f"CASA is installed but does not start here: {lines[-1] if lines else ''}"
        if os.environ.get("FEEDROT_REQUIRE_CASA"):
            pytest.fail(reason)
        pytest.skip(reason)
