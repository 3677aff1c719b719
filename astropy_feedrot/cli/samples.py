# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot samples``: the sample files shipped with the package, and where they lie.

The package ships a few small files (orbits, attitude, observations, the
station catalogue, visibility files: `astropy_feedrot.data`) for the
examples and a first try. ``feedrot samples`` lists them with what each is;
``feedrot samples NAME`` prints the path of one, to give to another command
(``feedrot rinex "$(feedrot samples gnss_sample.rnx)" ...``);
``feedrot samples NAME --copy`` copies one into the current directory, to
change it
(``feedrot correct "$(feedrot samples vla_sim.ms --copy)" --in-place``).
"""

from pathlib import Path

from ..core.outputs import CommandError
from ..data import DESCRIPTIONS, SAMPLES, copy_sample, sample_file

__all__ = ["run_samples"]


def _size(path):
    """Bytes of a file, or of every file of a directory (a Measurement Set)."""
    if not path.is_dir():
        return path.stat().st_size
    return sum(part.stat().st_size for part in path.rglob("*") if part.is_file())


def run_samples(args):
    if args.name is None:
        if args.copy:
            raise CommandError("--copy copies one sample: give its name "
                               "('feedrot samples' lists them)")
        width = max(len(name) for name in SAMPLES)
        for name in SAMPLES:
            size = _size(sample_file(name))
            print(f"{name:<{width}}  {size / 1024:7.1f} KiB  {DESCRIPTIONS[name]}")
        print(f"in {sample_file(SAMPLES[0]).parent}")
        return 0
    if args.name not in SAMPLES:
        raise CommandError(f"no sample file {args.name!r}; 'feedrot samples' lists them: "
                           + ", ".join(SAMPLES))
    if not args.copy:
        print(sample_file(args.name))
        return 0
    if Path(args.name).exists() and not args.overwrite:
        raise CommandError(f"{args.name} exists in {Path.cwd()}; remove it, work on it as it "
                           "is, or pass --overwrite to replace it with the sample")
    print(copy_sample(args.name, overwrite=args.overwrite))
    return 0
