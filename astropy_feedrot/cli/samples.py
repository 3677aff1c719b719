# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot samples``: the sample files shipped with the package, and where they lie.

The package ships a few small files (orbits, attitude, observations, the
station catalogue, a visibility file: `astropy_feedrot.data`) for the
examples and a first try. ``feedrot samples`` lists them with what each is;
``feedrot samples NAME`` prints the path of one, to give to another command
(``feedrot rinex "$(feedrot samples gnss_sample.rnx)" ...``).
"""

import os

from ..core.outputs import CommandError
from ..data import DESCRIPTIONS, SAMPLES, sample_file

__all__ = ["run_samples"]


def run_samples(args):
    if args.name is None:
        width = max(len(name) for name in SAMPLES)
        for name in SAMPLES:
            size = os.path.getsize(sample_file(name))
            print(f"{name:<{width}}  {size / 1024:7.1f} KiB  {DESCRIPTIONS[name]}")
        print(f"in {sample_file(SAMPLES[0]).parent}")
        return 0
    if args.name not in SAMPLES:
        raise CommandError(f"no sample file {args.name!r}; 'feedrot samples' lists them: "
                           + ", ".join(SAMPLES))
    print(sample_file(args.name))
    return 0
