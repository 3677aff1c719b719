# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""What users do with feed rotation: correct, tabulate, plan, plot.

`correction` corrects phases, visibilities and Jones matrices (both
directions); `rr_ll` predicts the RR - LL phase of a baseline (Eq 46);
`feed_rotation_tables` gives one antenna's or a baseline's feed rotation as
astropy Tables; `faraday_tables` the ionosphere's rotation measure, its
Faraday rotation and the feed rotation of stations; `planning` ranks sources
for polarization calibration; `plotting` draws them; `simulations` runs the satellite simulations of
Section 4 of the paper.

May import: every layer below: ``core``, ``io``, ``earth``, ``antennas``,
``transmitters``, ``ionosphere``, ``engine``, ``stations``.
"""
