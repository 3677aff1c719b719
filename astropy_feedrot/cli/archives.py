# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot correct A.ms B.ms ... --in-place`` and ``feedrot correct *.idifits -o OUTDIR/``:
an archive corrected one task per file, each file's outcome in one table."""

import sys

import numpy as np

from ..core.outputs import CommandError
from ..visibilities import OUTCOMES, correct_files
from ..visibilities.history import OPTION_WORDS

__all__ = ["run_correct_files", "outcome_summary"]

#: The columns of the table printed, in order (the warnings only where some file has one).
_SHOWN = ("path", "outcome", "seconds", "output", "reason")


def outcome_summary(table):
    """One line: how many files had each outcome.

    Examples
    --------
    >>> from astropy.table import Table
    >>> from astropy_feedrot.cli.archives import outcome_summary
    >>> outcome_summary(Table({"outcome": ["corrected", "corrected", "failed"]}))
    '3 files: 2 corrected, 0 skipped, 0 refused, 1 failed'
    """
    counts = [f"{int((table['outcome'] == k).sum())} {k}" for k in OUTCOMES]
    n = len(table)
    return f"{n} file{'s' if n != 1 else ''}: {', '.join(counts)}"


def run_correct_files(args, options, client):
    """Correct every input into -o OUTDIR (or in place), print the table of outcomes on
    standard output and one summary line on standard error; exit status 1 if any file
    was refused or failed."""
    if args.in_place and args.output is not None:
        raise CommandError("-o/--output and --in-place exclude each other: several inputs "
                           "are corrected into -o OUTDIR/ or in place")
    if not args.in_place and args.output is None:
        raise CommandError("give -o/--output OUTDIR/ for the corrected copies of the inputs, "
                           "or --in-place for Measurement Sets and MSv4 processing sets")
    columns = dict(data_column=args.data_column, overwrite_column=args.overwrite_column)
    if args.column is not None:
        columns["corrected_column"] = args.column
    try:
        table = correct_files(args.input, args.output, client=client,
                              overwrite=args.overwrite, **columns, **options)
    except ValueError as error:
        raise CommandError(" ".join(str(error).split())) from None
    for api, command in OPTION_WORDS.values():  # the reasons in the command line's words
        table["reason"] = [reason.replace(f"pass {api}", f"pass {command}")
                           for reason in table["reason"]]
    shown = list(_SHOWN) + (["warnings"] if any(table["warnings"]) else [])
    table[shown].write(sys.stdout, format="ascii.fixed_width_two_line")
    bad = bool(np.isin(table["outcome"], ("refused", "failed")).any())
    if not args.quiet or bad:
        print(f"feedrot: {outcome_summary(table)}", file=sys.stderr)
    return 1 if bad else 0
