# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The built documentation makes no request outside itself (equations render offline).

The pages are checked when they have been built (``sphinx-build ... docs
docs/_build/html``; ``.ci/run`` builds them and then runs this file again).
"""

import re
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).parent.parent
BUILT = ROOT / "docs" / "_build" / "html"

# A script, stylesheet, font or frame loaded from another host (http:, https: or //).
REMOTE = re.compile(r"<(script|link|img|iframe)\b[^>]*\b(src|href)=[\"'](https?:)?//",
                    re.IGNORECASE)
MATHJAX = re.compile(r"<script\b[^>]*\bsrc=[\"']([^\"']*mathjax[^\"']*)[\"']", re.IGNORECASE)


def test_mathjax_is_part_of_the_docs_build():
    # Sphinx's default loads MathJax from a CDN: offline every equation showed as LaTeX.
    conf = (ROOT / "docs" / "conf.py").read_text()
    assert '"sphinx-mathjax-offline"' in conf
    with open(ROOT / "pyproject.toml", "rb") as handle:
        docs = tomllib.load(handle)["project"]["optional-dependencies"]["docs"]
    assert any(req.startswith("sphinx-mathjax-offline") for req in docs)


@pytest.mark.skipif(not (BUILT / "index.html").exists(),
                    reason="docs/_build/html not built (.ci/run builds it, then runs this)")
def test_built_pages_load_nothing_from_elsewhere():
    pages = sorted(BUILT.rglob("*.html"))
    remote = {}
    for page in pages:
        text = page.read_text(encoding="utf-8", errors="replace")
        tags = [m.group(0) for m in REMOTE.finditer(text)
                if not m.group(0).lower().startswith("<link") or "stylesheet" in m.group(0)
                or "preload" in m.group(0)]
        if tags:
            remote[str(page.relative_to(BUILT))] = tags[:2]
    assert remote == {}
    # Pages with equations load the MathJax copied into the build.
    with_math = [p for p in pages if 'class="math' in p.read_text(encoding="utf-8")]
    assert with_math
    for page in with_math:
        sources = MATHJAX.findall(page.read_text(encoding="utf-8"))
        assert sources, page
        for source in sources:
            assert (page.parent / source.split("?")[0]).is_file(), (page, source)
