# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The error of the ionosphere subpackage."""

__all__ = ["IonosphereError"]


class IonosphereError(ValueError):
    """Rotation measures cannot be given for the epochs, antennas or files asked.

    Raised with one line that says what was wrong, with the value, and what
    to do: epochs outside the span the IONEX maps or the table of rotation
    measures cover (the message gives the span), an antenna the table does
    not list (the message lists those it does), a file that is not an IONEX
    file, two files for the same day.

    Examples
    --------
    >>> from astropy_feedrot.ionosphere import IonosphereError
    >>> issubclass(IonosphereError, ValueError)
    True
    """
