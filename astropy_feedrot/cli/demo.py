# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot demo``: the paper's Section 4.1 simulation on embedded data."""

from pathlib import Path

from astropy import units as u

from ..applied.feed_rotation_tables import baseline_summary
from ..applied.simulations import gps_short_baseline
from ..core.extras import install_hint
from ..core.outputs import CommandError, check_outputs, table_writer, write_files
from .common import drawer, figure_types, parse_quantity
from .shared import MAX_EPOCHS

__all__ = ["run_demo"]


def run_demo(args):
    directory = Path(args.output_dir).expanduser()
    if directory.exists() and not directory.is_dir():
        raise CommandError(f"--output-dir: {args.output_dir!r} is not a directory")
    step = parse_quantity(args.step, u.s, "--step")
    steps = (11 * u.hour / step).decompose().value
    if not steps < MAX_EPOCHS:
        raise CommandError(f"--step {args.step} gives {steps + 1:.3g} epochs over the 11 hours "
                           f"of the demo, more than the {MAX_EPOCHS} of one run; use a larger "
                           "--step")
    try:  # a new folder is made, as a user naming one expects
        directory.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise CommandError(f"--output-dir: cannot make {args.output_dir!r}: "
                           f"{error.strerror or error}") from None
    try:
        types = figure_types()
    except CommandError:
        types = None
    names = [("table", directory / "feedrot_demo.ecsv", (".ecsv",))]
    if types is not None:
        names.append(("figure", directory / "feedrot_demo.png", types))
    paths = check_outputs([("--output-dir", str(path), kinds) for _, path, kinds in names], [],
                          args.overwrite, hint="choose another --output-dir")
    table = gps_short_baseline(step=step)
    summary = baseline_summary(table)
    files = [(paths[0], table_writer(table, "ascii.ecsv"))]
    if types is not None:
        files.append((paths[1], drawer(table, "baseline", paths[1])))
    write_files(files, overwrite=args.overwrite)
    print("Section 4.1 of the paper: GPS SVN 76 over the GNSS antenna DBR205 and the")
    print("alt-az telescope FD-VLBA, 73 m apart, on 2023-01-25 (embedded element set, Table 2).")
    print(summary)
    print(f"table:  {names[0][1]}")
    if types is not None:
        print(f"figure: {names[1][1]}")
    else:
        print(f"figure: skipped (matplotlib: {install_hint('all', 'matplotlib')})")
    return 0
