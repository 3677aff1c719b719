# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The parts of a receiving antenna that turn its feed.

Mounts (`mounts`), foci and trains of mirrors (`focus`), feed rotators
(`rotators`) and receptor angles of the feeds (`receptors`). An antenna made
of these parts, `~astropy_feedrot.Antenna`, is a front-end of the engine
(``astropy_feedrot.engine.antenna``), since it computes.

May import: ``core``, ``earth``.
"""
