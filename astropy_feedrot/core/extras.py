# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""How to install what an optional feature needs, in words that work.

The package is installed from a clone of its repository (or an unpacked
source archive), not from a package index, so ``pip install
'astropy_feedrot[uvdata]'`` names a distribution no index has. Every message
about a missing optional dependency says the command that works from
anywhere (the dependency itself, from the index) and the one that installs
the whole extra from a clone (see ``docs/install.rst``).
"""

__all__ = ["install_hint"]


def install_hint(extra, *packages):
    """The commands that install an extra's packages: from the index, or from a clone.

    Parameters
    ----------
    extra : str
        The extra of ``pyproject.toml`` (``'all'``, ``'uvdata'``, ``'ms'``,
        ``'gnss'``, ``'dask'``).
    *packages : str
        What the feature needs from the package index.

    Returns
    -------
    str

    Examples
    --------
    >>> from astropy_feedrot.core.extras import install_hint
    >>> print(install_hint("uvdata", "pyuvdata"))  # doctest: +NORMALIZE_WHITESPACE
    python -m pip install pyuvdata (or, in a clone of astropy_feedrot,
    python -m pip install -e '.[uvdata]')
    """
    return (f"python -m pip install {' '.join(packages)} (or, in a clone of astropy_feedrot, "
            f"python -m pip install -e '.[{extra}]')")
