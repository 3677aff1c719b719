# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The wind-up engine and its two front-ends.

`equations` is the one place that decides which equation a receiver uses;
`receivers` reads once what each antenna declares; `rates` gives the rate of
the feed rotation. The front-ends: `antenna` (`~astropy_feedrot.Antenna`,
one antenna) and the grids of many antennas and targets (`grid`, with
`grid_arrays` for plain arrays and `grid_natural` for natural sources);
`continuity` makes the results continuous (Eq 9) and gives the rotation
delay.

May import: ``core``, ``io``, ``earth``, ``antennas``, ``transmitters``,
``ionosphere``.
"""
