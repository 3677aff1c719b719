# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Sphinx configuration of the astropy_feedrot documentation."""

import datetime
from importlib import metadata

from sphinx_astropy.conf.v2 import *  # noqa: F401, F403
from sphinx_astropy.conf.v2 import exclude_patterns, extensions  # noqa: F401

project = "astropy_feedrot"
author = "The astropy_feedrot developers"
copyright = f"{datetime.date.today().year}, {author}"
try:
    release = metadata.version(project)
except metadata.PackageNotFoundError:  # pragma: no cover
    release = "unknown"
version = release.split("+")[0]

html_title = f"{project} {version}"
html_theme_options = {
    "github_url": "https://github.com/astropy-feedrot/astropy_feedrot",
    "use_edit_page_button": False,
}
exclude_patterns += ["_build"]

# Every public name is documented; automodapi writes its pages under api/.
automodapi_toctreedirnm = "api"
automodsumm_inherited_members = False
numpydoc_show_class_members = False

# Offline builds: pass ``-D disable_intersphinx=1`` (the build_docs tox env
# does) and cross-references to astropy, numpy and Python stay plain text.
