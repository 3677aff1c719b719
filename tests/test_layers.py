# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The layout of the package: subpackages by idea, and imports that run one way.

The table `MAY_IMPORT` is the architecture (docs/architecture.rst draws it):
each subpackage and the subpackages it may import. Every import of the
package's own modules, at the top of a module or inside a function, is
checked against it, and each subpackage's docstring must say the same.
"""

import ast
import pathlib
import subprocess
import sys

import pytest

import astropy_feedrot

PACKAGE = pathlib.Path(astropy_feedrot.__file__).parent

#: Each subpackage (or top-level module) and what it may import, lowest first.
BELOW_ENGINE = {"core", "io", "earth", "antennas", "transmitters", "ionosphere"}
MAY_IMPORT = {
    "_version": set(),
    "data": set(),
    "core": {"_version", "data"},
    "io": {"core"},
    "earth": {"core", "io"},
    "antennas": {"core", "earth"},
    "transmitters": {"core", "io", "earth", "data"},
    "ionosphere": {"core", "earth"},
    "engine": BELOW_ENGINE,
    "stations": BELOW_ENGINE | {"engine", "data"},
    "applied": BELOW_ENGINE | {"engine", "stations"},
    "visibilities": BELOW_ENGINE | {"engine", "stations", "applied"},
    "gnss": BELOW_ENGINE | {"engine", "stations", "applied", "data"},
    "cli": BELOW_ENGINE | {"engine", "stations", "applied", "visibilities", "gnss", "data"},
    # The import surface and ``python -m astropy_feedrot``: above everything.
    "__init__": set(),
    "__main__": {"cli"},
}
MAY_IMPORT["__init__"] = set(MAY_IMPORT) - {"__init__", "__main__", "cli", "gnss",
                                            "visibilities"}

#: Imports inside functions: for optional or heavy dependencies only, each named here.
LAZY = {
    # feedrot starts without astropy: main imports what runs every command only once the
    # command line has parsed; that module (cli.running) imports the command's family by
    # the name the parser's table (cli.parser.COMMANDS) gives.
    ("cli", "cli.running"): "start-up time of feedrot --help and --version",
}


def modules():
    """Every module of the package: (path, dotted name relative to the package, is a package)."""
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = list(path.relative_to(PACKAGE).with_suffix("").parts)
        is_package = parts[-1] == "__init__"
        if is_package and len(parts) > 1:
            parts = parts[:-1]
        yield path, ".".join(parts), is_package


def package_imports(path, name, is_package):
    """The package's modules that a source file imports: (dotted target, at the top?)."""
    tree = ast.parse(path.read_text())
    top = set()
    for node in tree.body:  # a top-level try (of an optional import) is the top too,
        top.add(id(node))      # and so are the imports for static tools (if TYPE_CHECKING)
        if isinstance(node, ast.Try) or (isinstance(node, ast.If)
                                         and getattr(node.test, "id", "") == "TYPE_CHECKING"):
            top.update(id(n) for n in node.body)
    here = name.split(".") if name != "__init__" else []
    base = here if is_package else here[:-1]
    for node in ast.walk(tree):
        targets = []
        if isinstance(node, ast.ImportFrom) and node.level:
            parent = base[:len(base) - (node.level - 1)]
            module = parent + (node.module.split(".") if node.module else [])
            targets = [".".join(module + [alias.name]) if not node.module else ".".join(module)
                       for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith("astropy_feedrot"):
            targets = [node.module.removeprefix("astropy_feedrot").lstrip(".")]
        elif isinstance(node, ast.Import):
            targets = [alias.name.removeprefix("astropy_feedrot").lstrip(".")
                       for alias in node.names if alias.name.startswith("astropy_feedrot")]
        for target in targets:
            yield target, id(node) in top


def layer(dotted):
    return dotted.split(".")[0] if dotted else "__init__"


ALL = list(modules())


@pytest.mark.parametrize("path, name, is_package", ALL, ids=[name for _, name, _ in ALL])
def test_imports_run_down_the_layers(path, name, is_package):
    own = layer(name)
    assert own in MAY_IMPORT, f"{name}: a subpackage that the table of layers does not know"
    up = sorted({target for target, _ in package_imports(path, name, is_package)
                 if layer(target) != own and layer(target) not in MAY_IMPORT[own]})
    assert up == [], f"{name} imports above its layer ({own}): {up}"


def test_function_level_imports_are_only_the_named_lazy_ones():
    found = {(name, target) for path, name, is_package in ALL
             for target, at_top in package_imports(path, name, is_package) if not at_top}
    assert found == set(LAZY), found ^ set(LAZY)


@pytest.mark.parametrize("subpackage", [name for name in MAY_IMPORT
                                        if (PACKAGE / name / "__init__.py").exists()])
def test_each_subpackage_says_what_it_holds_and_may_import(subpackage):
    import importlib

    doc = importlib.import_module(f"astropy_feedrot.{subpackage}").__doc__
    assert doc and len(doc.splitlines()[0]) > 10, f"{subpackage}: no docstring"
    if subpackage in ("data",):
        return
    said = doc.split("May import:")[1].split("\n\n")[0] if "May import:" in doc else ""
    named = {word.strip("`,. \n") for word in said.replace("``", " ").split()}
    expected = MAY_IMPORT[subpackage] - {"_version", "data"}
    assert expected <= named, f"{subpackage}'s docstring omits {expected - named}"
    assert not (named & set(MAY_IMPORT)) - MAY_IMPORT[subpackage], \
        f"{subpackage}'s docstring names more than the table"


def test_no_module_is_left_at_the_top():
    # Beside the import surface, only the subpackages and the generated version.
    top = sorted(p.name for p in PACKAGE.glob("*.py"))
    assert top == ["__init__.py", "__main__.py", "_version.py"] or \
        top == ["__init__.py", "__main__.py"], top


def test_modules_are_of_one_idea():
    # No module past 800 lines.
    large = {name: n for path, name, _ in ALL
             if (n := len(path.read_text().splitlines())) > 800}
    assert large == {}, large


def test_every_module_imports_first_without_a_cycle():
    # In a fresh interpreter, each module imports first (a cycle fails there).
    names = [name for _, name, _ in ALL if name not in ("__init__", "__main__")]
    script = ("import importlib, sys\n"
              f"for name in {names!r}:\n"
              "    for key in [k for k in sys.modules if k.startswith('astropy_feedrot')]:\n"
              "        del sys.modules[key]\n"
              "    importlib.import_module('astropy_feedrot.' + name)\n")
    subprocess.run([sys.executable, "-W", "ignore", "-c", script], cwd=PACKAGE.parent, check=True)


def test_the_command_line_has_no_circle():
    """The parser imports no command and no command imports the parser: what they share
    is cli.shared's; the parser names each command's module in its table, which exists."""
    import importlib

    from astropy_feedrot.cli.parser import COMMANDS

    cli = {name: path for path, name, _ in ALL if name.startswith("cli.")}
    importers = {name for name, path in cli.items()
                 if "cli.parser" in {t for t, _ in package_imports(path, name, False)}}
    assert importers <= {"cli.running"}, importers  # what runs a command reads the table
    parser_imports = {t for t, _ in package_imports(cli["cli.parser"], "cli.parser", False)}
    assert {t for t in parser_imports if t.startswith("cli.")} == {"cli.samples", "cli.shared"}
    for module, function in COMMANDS.values():
        assert callable(getattr(importlib.import_module(f"astropy_feedrot.cli.{module}"),
                                function))


def test_earth_orientation_does_not_import_frames():
    # The orientation of the Earth is below the astropy frames layer of earth/.
    path = PACKAGE / "earth" / "orientation.py"
    assert "earth.frames" not in {t for t, _ in package_imports(path, "earth.orientation", False)}


# --- docs/architecture.rst follows the code ----------------------------------------------

ARCHITECTURE = PACKAGE.parent / "docs" / "architecture.rst"


def architecture_table():
    """The rows of the table of folders: {folder: (modules, may import)}."""
    import re

    text = ARCHITECTURE.read_text()
    table = text.split(".. list-table:: The folders")[1].split("\n\n")[1]
    rows = {}
    for row in table.split("   * - ")[2:]:
        cells = [" ".join(cell.split()) for cell in row.split("\n     - ")]
        folder = cells[0].strip("`")
        modules = set(re.findall(r"``(\w+)``", re.sub(r"\([^)]*\)", "", cells[1])))
        rows[folder] = (modules, cells[2])
    return rows


def test_architecture_names_every_module_in_its_folder():
    rows = architecture_table()
    folders = {name for name in MAY_IMPORT if (PACKAGE / name / "__init__.py").exists()}
    assert set(rows) == folders - {"data"}
    for folder, (modules, _) in rows.items():
        actual = {p.stem for p in (PACKAGE / folder).glob("*.py")} - {"__init__"}
        assert modules == actual, f"{folder}: the page names {modules ^ actual} wrongly"


def test_architecture_says_what_each_folder_may_import():
    import re

    rows = architecture_table()
    assert len(rows) == 12
    for folder, (_, said) in rows.items():
        allowed = MAY_IMPORT[folder] - {"_version", "data"}
        if said == "every folder above":
            names = list(architecture_table())
            assert allowed == set(names[:names.index(folder)]), folder
        elif said == "nothing":
            assert allowed == set(), folder
        else:
            assert set(re.findall(r"``(\w+)``", said)) == allowed, folder


def test_the_routes_of_the_architecture_page_exist():
    # Every function a route names is where the page says it is.
    import importlib
    import re

    text = ARCHITECTURE.read_text().split("The route of a call")[1]
    names = set(re.findall(r"`(astropy_feedrot(?:\.\w+)+)`", text))
    assert len(names) > 20
    for name in sorted(names):
        parts = name.split(".")
        for cut in range(len(parts), 0, -1):
            try:
                obj = importlib.import_module(".".join(parts[:cut]))
            except ImportError:
                continue
            for attribute in parts[cut:]:
                obj = getattr(obj, attribute, None)
                assert obj is not None, f"{name}: no {attribute}"
            break
