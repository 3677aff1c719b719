# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Earth orientation and the epochs of a computation.

The IERS tables and how they are read (`eop`, `iers_files`), the quantities
that change over days interpolated between nodes (`nodes`), UTC days and the
Earth's rotation within them (`utc_days`), the orientation of the Earth at
many epochs (`orientation`), the directions of a network of sites (`diurnal`),
`~astropy_feedrot.Epochs` (`epochs`), and the step from astropy objects to
Earth-fixed unit vectors (`frames`).

May import: ``core``, ``io``.
"""
