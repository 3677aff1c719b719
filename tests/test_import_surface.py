# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The import surface: every public name from ``astropy_feedrot``, imported on first use.

``astropy_feedrot/__init__.py`` names each public name's home in one table and
imports it when it is first used (PEP 562), so that ``import astropy_feedrot``
and the command line start without astropy.
"""

import ast
import importlib
import pathlib
import subprocess
import sys

import pytest

import astropy_feedrot

SOURCE = pathlib.Path(astropy_feedrot.__file__)


def homes_table():
    """The table {name: home} as written in the source."""
    tree = ast.parse(SOURCE.read_text())
    for node in tree.body:
        if isinstance(node, ast.Assign) and getattr(node.targets[0], "id", "") == "_HOMES":
            return ast.literal_eval(node.value)
    raise AssertionError("no table of homes")


def type_checking_imports():
    """{name: module} of the imports inside ``if TYPE_CHECKING:``."""
    tree = ast.parse(SOURCE.read_text())
    found = {}
    for node in tree.body:
        if isinstance(node, ast.If) and getattr(node.test, "id", "") == "TYPE_CHECKING":
            for statement in node.body:
                assert isinstance(statement, ast.ImportFrom) and statement.level == 1
                for alias in statement.names:
                    found[alias.asname or alias.name] = "." + statement.module
    return found


HOMES = homes_table()


def test_all_is_the_table():
    assert astropy_feedrot.__all__ == list(HOMES)
    assert len(HOMES) > 60
    for name in ("get_antenna", "feed_rotation_grid", "correct_phase", "mount_from_label",
                 "read_tle", "FileFormatError", "OrbitWarning", "feed_rotation_table"):
        assert name in astropy_feedrot.__all__


def test_static_tools_see_the_same_names():
    # The TYPE_CHECKING imports (for type checkers and editors) are the table.
    assert type_checking_imports() == HOMES


@pytest.mark.parametrize("name", list(HOMES))
def test_each_name_is_the_object_of_its_home(name):
    home = importlib.import_module("astropy_feedrot" + HOMES[name])
    value = getattr(astropy_feedrot, name)
    assert value is getattr(home, name)
    # Defined there (or, for the readers of io, in a module of that folder).
    defined = value.__module__ if hasattr(value, "__qualname__") else type(value).__module__
    assert defined.startswith(home.__name__), (name, defined)


def test_dir_lists_every_name():
    listed = dir(astropy_feedrot)
    assert set(astropy_feedrot.__all__) <= set(listed)
    assert {"__version__", "stations", "cli"} <= set(listed)


def test_an_unknown_name_is_an_attribute_error_naming_the_module():
    with pytest.raises(AttributeError, match="module 'astropy_feedrot' has no attribute 'nope'"):
        astropy_feedrot.nope
    assert not hasattr(astropy_feedrot, "feed_rotation")  # a method of Antenna, not a name


def test_folders_are_attributes():
    assert astropy_feedrot.stations is importlib.import_module("astropy_feedrot.stations")


def test_star_import_gives_every_name():
    names = {}
    exec("from astropy_feedrot import *", names)
    assert set(astropy_feedrot.__all__) <= set(names)
    assert names["Antenna"] is astropy_feedrot.engine.antenna.Antenna


HEAVY = ("astropy", "numpy", "erfa")


@pytest.mark.parametrize("statement", ["import astropy_feedrot",
                                       "from astropy_feedrot import __version__",
                                       "import astropy_feedrot.cli",
                                       "from astropy_feedrot.cli import main, build_parser"])
def test_importing_the_surface_imports_nothing_heavy(statement):
    # In a fresh interpreter: astropy (astropy.units, astropy.coordinates), numpy and
    # pyerfa wait for the first name that needs them.
    script = (f"import sys; {statement}\n"
              f"print(sorted(m for m in sys.modules if m.split('.')[0] in {HEAVY!r}))")
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         cwd=SOURCE.parent.parent, check=True)
    assert run.stdout.strip() == "[]", run.stdout
