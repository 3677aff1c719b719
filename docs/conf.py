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

# Equations render offline: MathJax is copied into the built pages
# (_static/mathjax) by sphinx-mathjax-offline instead of loaded from a CDN.
extensions = list(extensions) + ["sphinx-mathjax-offline"]

# Offline builds: pass ``-D disable_intersphinx=1`` (the build_docs tox env
# does) and cross-references to astropy, numpy and Python stay plain text.


# The station table of stations.rst is written from the embedded catalogue at
# each build (docs/_generated/stations.csv), so the page shows the data as it is.
def _write_station_table():
    import csv
    from pathlib import Path

    from astropy.table import Table

    from astropy_feedrot.data import sample_file

    table = Table.read(sample_file("stations.ecsv"), format="ascii.ecsv")
    out = Path(__file__).parent / "_generated"
    out.mkdir(exist_ok=True)

    def text(value):
        return "" if hasattr(value, "mask") and value.mask else str(value)

    with open(out / "stations.csv", "w", newline="") as handle:
        writer = csv.writer(handle)
        for row in table:
            writer.writerow([
                row["name"], text(row["aliases"]).replace(",", ", "),
                text(row["networks"]).replace(",", ", "),
                f"{row['x']:.3f}, {row['y']:.3f}, {row['z']:.3f}",
                row["mount"], text(row["focus"]), row["position_source"],
                row["mount_source"], row["focus_source"],
                (f"{row['largest_difference']:.3f} m ({row['largest_difference_source']})"
                 if text(row["largest_difference_source"]) else "none: one source"),
            ])


_write_station_table()
