# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Promises of the packaging: licence, minimums tested exactly, instructions that work."""

import re
import tomllib
from pathlib import Path

ROOT = Path(__file__).parent.parent
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())
PROJECT = PYPROJECT["project"]


def test_licence_as_pep_639():
    # A licence table and a licence classifier made setuptools warn, and the wheel had
    # no licence file.
    assert PROJECT["license"] == "BSD-3-Clause"
    files = [path for pattern in PROJECT["license-files"] for path in ROOT.glob(pattern)]
    assert ROOT / "licenses" / "LICENSE.rst" in files
    assert not any(c.startswith("License ::") for c in PROJECT.get("classifiers", []))
    assert any(re.fullmatch(r"setuptools>=(7[7-9]|[89]\d)", req)
               for req in PYPROJECT["build-system"]["requires"])


def test_oldest_constraints_are_the_declared_minimums():
    declared = {}
    for requirement in PROJECT["dependencies"]:
        name, minimum = re.fullmatch(r"([\w-]+)>=([\d.]+)", requirement).groups()
        declared[name] = minimum
    pinned = {}
    for line in (ROOT / ".ci" / "oldest-constraints.txt").read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            name, version = line.split("==")
            pinned[name] = version
    assert set(pinned) == set(declared)
    for name, version in pinned.items():
        # 6.0.0 for >=6.0, 2.0.1.1 for >=2.0.1.1: the minimum itself.
        assert version.split(".")[:len(declared[name].split("."))] == declared[name].split(".")
        assert all(part == "0" for part in version.split(".")[len(declared[name].split(".")):])
    run = (ROOT / ".ci" / "run").read_text()
    assert "-c .ci/oldest-constraints.txt" in run
    tox = (ROOT / "tox.ini").read_text()
    assert "oldestdeps: PIP_CONSTRAINT = {toxinidir}/.ci/oldest-constraints.txt" in tox


def test_readme_test_command_is_what_ci_runs_first():
    readme = (ROOT / "README.md").read_text()
    command = 'python -m pip install -e ".[test]" && python -m pytest'
    assert f"```bash\n{command}\n```" in readme
    commands = [line for line in (ROOT / ".ci" / "run").read_text().splitlines()
                if line.startswith("python -m pip install -e")]
    assert commands[0] == command


def test_install_instructions_do_not_use_the_package_index():
    # astropy_feedrot is not on PyPI: 'pip install astropy_feedrot' fails.
    for path in [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.rst"))]:
        for line in path.read_text().splitlines():
            assert not re.search(r"pip install (-U )?astropy[_-]feedrot\b", line), (path, line)


def test_package_data_holds_every_sample_file():
    # A Measurement Set is a folder of tables: 'data/*' alone left its files out of the
    # wheel (setuptools globs the patterns below each package; checked on a built wheel:
    # all 78 files of vla_sim.ms inside).
    package = ROOT / "astropy_feedrot"
    patterns = PYPROJECT["tool"]["setuptools"]["package-data"]["astropy_feedrot"]
    shipped = {path for pattern in patterns for path in package.glob(pattern) if path.is_file()}
    from astropy_feedrot.data import SAMPLES, sample_file

    for name in SAMPLES:
        path = sample_file(name)
        files = [path] if path.is_file() else [p for p in path.rglob("*") if p.is_file()]
        assert files and set(files) <= shipped, name
