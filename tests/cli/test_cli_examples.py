# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Every printed example runs as printed, in an empty directory, with the package alone.

The examples are read from where users read them: the ``examples:`` of ``feedrot --help``
and of every command's ``--help``, the ``$ feedrot ...`` lines of the documentation
(``docs/*.rst``), and the Python snippets of README.md and the documentation that are not
doctests (doctests run already). Each runs in a new empty directory through ``bash -c``
(a Python snippet as a script), with ``feedrot`` on the PATH meaning this checkout's
package; it must exit with status 0 (or print the error its page shows after it) and
write the files it names with ``-o``, ``--plot``, ``--table`` or ``--output-dir``. Files
an example reads are the shipped samples, named as ``feedrot samples NAME`` prints them.

An example that needs an optional package says so in a comment, with the extra that
installs it (``# sgp4: the all extra``, ``# python-casacore, dask: the ms and dask
extras``); a snippet may instead follow the install command of an extra (``".[uvdata]"``),
which then stands for the extra's first package. It is skipped, with the reason, when
such a package is not installed.

The examples run two at a time (the machine's cores) the first time one of them is asked
for; each test then checks its own.
"""

import os
import re
import shlex
import subprocess
import sys
import textwrap
import time
import tomllib
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from importlib import metadata
from pathlib import Path

import pytest
from packaging.requirements import Requirement

from astropy_feedrot.cli import build_parser

ROOT = Path(__file__).resolve().parents[2]
TIMEOUT = 300  # s, for one example

#: Options whose value is a file or folder the command writes.
OUTPUT_OPTIONS = ("-o", "--output", "--plot", "--table", "--output-dir")

_NEEDS = re.compile(r"#\s*([\w.-]+(?:, [\w.-]+)*)(?: \([^)]*\))?: "
                    r"the ([\w-]+(?:(?:, | and )[\w-]+)*) extras?\b")
_EXTRA_INSTALL = re.compile(r"\.\[([\w,-]+)\]")


@dataclass(frozen=True)
class Example:
    where: str          # file (or --help) and line
    text: str           # as printed (dedented)
    kind: str           # "shell" or "python"
    needs: tuple = ()   # (package, extra) pairs
    error: str = ""     # the error line the page shows after it, if any
    outputs: tuple = field(default=())

    @property
    def key(self):
        """The text with its line breaks and runs of blanks as one blank: the same
        command printed in two places runs once."""
        return re.sub(r"\s+", " ", re.sub(r"\\\n\s*", " ", self.text)).strip()

    @property
    def id(self):
        return f"{self.where}: {self.text.splitlines()[0][:70]}"


def _extras_declared():
    return tomllib.loads((ROOT / "pyproject.toml").read_text())["project"][
        "optional-dependencies"]


def _name(requirement):
    return re.sub(r"[-_.]+", "-", Requirement(requirement).name).lower()


def named_needs(text, context=""):
    """(package, extra) pairs an example names: in comments, or by an install command."""
    declared = _extras_declared()
    found = []
    for match in _NEEDS.finditer(text):
        packages = match.group(1).split(", ")
        extras = re.split(r", | and ", match.group(2))
        for package in packages:
            homes = [e for e in extras
                     if _name(package) in map(_name, declared.get(e, ()))]
            assert homes, f"{package} is not in the extra(s) {extras} of pyproject.toml"
            found.append((package, homes[0]))
    for match in _EXTRA_INSTALL.finditer(context):
        for extra in match.group(1).split(","):
            assert extra in declared, f"an example names the extra {extra!r}, which " \
                "pyproject.toml lacks"
            found.append((Requirement(declared[extra][0]).name, extra))
    return tuple(dict.fromkeys(found))


def written_files(command):
    """What a shell example names as its outputs (the value after -o and the like)."""
    words = shlex.split(command.replace("\\\n", " "), comments=True)
    return tuple(value for option, value in zip(words, words[1:]) if option in OUTPUT_OPTIONS)


def shell_example(where, text, error=""):
    return Example(where, text, "shell", named_needs(text), error, written_files(text))


# Where the examples are printed ---------------------------------------------------------


def help_examples():
    parser = build_parser()
    commands = parser._subparsers._group_actions[0].choices
    found = []
    for name, command in [("", parser), *commands.items()]:
        text = command.format_help()
        assert "examples:\n" in text, f"feedrot {name} --help has no examples"
        for line in text.split("examples:\n", 1)[1].splitlines():
            if not line.startswith("  feedrot"):
                break
            found.append(shell_example(f"feedrot {name} --help".replace("  ", " "),
                                       line.strip()))
    return found


def _indented_block(lines, start):
    """The lines of the indented block from ``start`` on (blank lines inside kept)."""
    end = start
    while end < len(lines) and (not lines[end].strip() or lines[end][:1] in " \t"):
        end += 1
    while end > start and not lines[end - 1].strip():
        end -= 1
    return lines[start:end]


def _paragraph_before(lines, index):
    start = index
    while start > 0 and lines[start - 1].strip():
        start -= 1
    return "\n".join(lines[start:index + 1])


def rst_examples(path):
    lines = path.read_text().splitlines()
    where = path.relative_to(ROOT).as_posix()
    found = []
    for i, line in enumerate(lines):
        if not (line.rstrip().endswith("::") or line.strip().startswith(".. code-block::")):
            continue
        start = i + 1
        while start < len(lines) and not lines[start].strip():
            start += 1
        if start >= len(lines) or not lines[start].startswith((" ", "\t")):
            continue
        if lines[start].lstrip().startswith(":"):  # options of a directive
            continue
        block = textwrap.dedent("\n".join(_indented_block(lines, start))).splitlines()
        if any(b.startswith(">>>") for b in block):
            continue  # a doctest: pytest --doctest-rst runs it
        if block[0].startswith("$ "):
            found += _console_commands(block, f"{where}:{start + 1}")
        elif (re.match(r"(from|import) \w", next(b for b in block if not b.startswith("#")))
              and ".. code-block:: console" not in line):
            text = "\n".join(block) + "\n"
            found.append(Example(f"{where}:{start + 1}", text, "python",
                                 named_needs(text, _paragraph_before(lines, i))))
    return found


def _console_commands(block, where):
    found = []
    k = 0
    while k < len(block):
        if not block[k].startswith("$ "):
            k += 1
            continue
        command = [block[k][2:]]
        while command[-1].endswith("\\") and k + 1 < len(block):
            k += 1
            command.append(block[k].strip())
        k += 1
        shown = []
        while k < len(block) and not block[k].startswith("$ "):
            shown.append(block[k])
            k += 1
        error = next((s for s in shown if s.startswith("feedrot: error:")), "")
        found.append(shell_example(where, "\n    ".join(command), error))
    return found


def readme_examples():
    lines = (ROOT / "README.md").read_text().splitlines()
    found = []
    i = 0
    while i < len(lines):
        fence = re.match(r"```(\w+)", lines[i])
        if not fence:
            i += 1
            continue
        end = lines.index("```", i + 1)
        body = lines[i + 1:end]
        context = _paragraph_before(lines, i - 1) if i else ""
        if fence.group(1) == "python":
            text = "\n".join(body) + "\n"
            found.append(Example(f"README.md:{i + 2}", text, "python",
                                 named_needs(text, context)))
        elif fence.group(1) in ("bash", "console", "shell"):
            # Shell blocks of the README install the package and run Python scripts (CI's
            # readme-check runs them in a fresh environment); feedrot lines are examples.
            found += [shell_example(f"README.md:{i + 2 + n}", line.removeprefix("$ "))
                      for n, line in enumerate(body) if line.removeprefix("$ ").startswith(
                          "feedrot")]
        i = end + 1
    return found


def all_examples():
    found = help_examples() + readme_examples()
    for path in sorted((ROOT / "docs").glob("**/*.rst")):
        if not {"_build", "api"} & set(path.relative_to(ROOT / "docs").parts):
            found += rst_examples(path)
    return found


EXAMPLES = all_examples()


# Running them ---------------------------------------------------------------------------


def missing(needs):
    """Of the (package, extra) pairs an example needs, those not installed, as words."""
    absent = []
    for package, extra in needs:
        try:
            metadata.distribution(package)
        except metadata.PackageNotFoundError:
            absent.append(f"{package} (the {extra} extra)")
    return absent


def run(example, directory):
    """(exit status, stdout + stderr) of one example, run in an empty ``directory``."""
    bin_dir = directory.parent / (directory.name + "-bin")
    directory.mkdir(exist_ok=True)
    bin_dir.mkdir()
    wrapper = bin_dir / "feedrot"
    wrapper.write_text(f'#!/bin/sh\nexec "{sys.executable}" -m astropy_feedrot "$@"\n')
    wrapper.chmod(0o755)
    env = dict(os.environ, PATH=f"{bin_dir}{os.pathsep}{os.environ['PATH']}",
               PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT),
                                                        os.environ.get("PYTHONPATH")])),
               MPLBACKEND="Agg")
    env.pop("PYTHONWARNINGS", None)
    if example.kind == "shell":
        argv = ["bash", "-c", example.text]  # as a shell runs it, without pipefail
    else:
        (directory.parent / (directory.name + ".py")).write_text(example.text)
        argv = [sys.executable, str(directory.parent / (directory.name + ".py"))]
    start = time.perf_counter()
    done = subprocess.run(argv, cwd=directory, env=env, capture_output=True, text=True,
                          timeout=TIMEOUT)
    return done.returncode, done.stdout + done.stderr, time.perf_counter() - start


@pytest.fixture(scope="module")
def results(request, tmp_path_factory):
    """Every example selected in this session, run two at a time, by its text."""
    chosen = {item.callspec.params["example"] for item in request.session.items
              if getattr(item, "module", None) is sys.modules[__name__]
              and hasattr(item, "callspec") and "example" in item.callspec.params}
    to_run = {e.key: e for e in chosen if not missing(e.needs)}
    directories = {key: tmp_path_factory.mktemp("example") for key in to_run}
    with ThreadPoolExecutor(max_workers=2) as pool:
        futures = {key: pool.submit(run, e, directories[key]) for key, e in to_run.items()}
        return {key: (directories[key], *future.result()) for key, future in futures.items()}


@pytest.mark.parametrize("example", EXAMPLES, ids=[e.id for e in EXAMPLES])
def test_example_runs_as_printed(results, example):
    absent = missing(example.needs)
    if absent:
        pytest.skip(f"needs {', '.join(absent)}, not installed")
    directory, status, output, seconds = results[example.key]
    if example.error:
        assert status != 0, output
        assert example.error.removeprefix("feedrot: error: ") in " ".join(output.split()), \
            output
        return
    assert status == 0, f"exit status {status}:\n{output}"
    for name in example.outputs:
        assert (directory / name).exists(), f"{name} not written:\n{output}"


def test_every_place_has_examples():
    # The extraction itself: each kind of place gives what it prints.
    places = {e.where.split(":")[0].split(" --help")[0] for e in EXAMPLES}
    assert {"feedrot", "feedrot correct", "README.md", "docs/cli.rst",
            "docs/correcting.rst", "docs/network.rst"} <= places
    assert len([e for e in EXAMPLES if e.where.endswith("--help")]) >= 30
    assert any(e.kind == "python" for e in EXAMPLES if e.where.startswith("docs/"))
    assert any(e.error for e in EXAMPLES)


@pytest.mark.parametrize("text, needs", [
    ("feedrot demo   # sgp4 (matplotlib for the figure): the all extra", (("sgp4", "all"),)),
    ("feedrot correct x --workers 2   # python-casacore, dask: the ms and dask extras",
     (("python-casacore", "ms"), ("dask", "dask"))),
    ("feedrot stations", ()),
])
def test_named_needs(text, needs):
    assert named_needs(text) == needs


def test_an_install_command_before_a_snippet_names_the_extra():
    assert named_needs("import x\n", 'With pyuvdata (``pip install ".[uvdata]"``):') == (
        ("pyuvdata", "uvdata"),)


def test_a_package_the_extra_lacks_is_an_error():
    with pytest.raises(AssertionError, match="sgp4 is not in the extra"):
        named_needs("feedrot x   # sgp4: the ms extra")
    with pytest.raises(AssertionError, match="names the extra 'plots', which pyproject"):
        named_needs("import x\n", '".[plots]"')


def test_missing():
    assert missing((("sgp4", "all"), ("no-such-package-here", "all"))) == [
        "no-such-package-here (the all extra)"]


def test_the_same_command_printed_twice_runs_once():
    one = shell_example("a", 'feedrot natural X --source "1h 2d" \\\n      --step 10min')
    assert one.key == shell_example("b", 'feedrot natural X --source "1h 2d"  --step 10min').key


def test_written_files():
    assert written_files('feedrot natural X -o a.ecsv --plot "b c.png"   # -o d') == (
        "a.ecsv", "b c.png")


def test_a_failing_example_fails(tmp_path):
    # The runner is not blind: an example naming a file nothing ships exits non-zero.
    status, output, _ = run(shell_example("here", "feedrot antennas experiment.idifits"),
                            tmp_path / "work")
    assert status != 0 and "experiment.idifits" in output
