# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Circular polarization hands (IEEE convention, Sec. 2)."""

__all__ = ["POLARIZATIONS", "polarization_sign"]

#: Accepted names of the two hands, each mapped to the sign of the feed
#: rotation it sees: RCP as computed, LCP negated (Sec. 3, Appendix D).
POLARIZATIONS = {"RCP": 1, "RHCP": 1, "R": 1, "LCP": -1, "LHCP": -1, "L": -1}


def polarization_sign(polarization):
    """Sign of the feed rotation for a circular polarization hand.

    Parameters
    ----------
    polarization : str
        ``'RCP'`` (right-handed, IEEE) or ``'LCP'``; ``'RHCP'``/``'LHCP'`` and
        ``'R'``/``'L'`` are accepted, in any case.

    Returns
    -------
    int
        +1 for RCP, -1 for LCP.

    Raises
    ------
    ValueError
        For anything else, listing the valid names.

    Examples
    --------
    >>> from astropy_feedrot.core.polarization import polarization_sign
    >>> polarization_sign("lcp")
    -1
    """
    key = polarization.upper() if isinstance(polarization, str) else polarization
    try:
        return POLARIZATIONS[key]
    except (KeyError, TypeError):
        raise ValueError(
            f"polarization must be one of {sorted(POLARIZATIONS)}, got {polarization!r}"
        ) from None
