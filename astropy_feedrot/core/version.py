# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The package's version, as the build wrote it (``unknown`` in a source tree without a build)."""

try:
    from .._version import version
except ImportError:  # pragma: no cover - running from a source tree without a build
    version = "unknown"

__all__ = ["version"]
