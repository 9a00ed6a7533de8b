"""The browser check: the site opened in headless Chromium (Debian's chromium and
chromium-driver). `.ci/run` installs them and sets SPRINGLAB_REQUIRE_BROWSER=1, so
CI always runs this; elsewhere it is skipped when Chromium is not installed."""

import os
import shutil
from pathlib import Path

import pytest

from springlab.workbench import site
from springlab.workbench.notebooks import run_notebook

ROOT = Path(__file__).resolve().parents[1]
REQUIRED = os.environ.get("SPRINGLAB_REQUIRE_BROWSER") == "1"

pytestmark = pytest.mark.skipif(site.find_browser() is None and not REQUIRED,
                                reason="headless Chromium not installed (apt-get install chromium chromium-driver)")


@pytest.fixture(scope="module")
def built_site():
    """build/site-check: the site of one notebook run with quick=True, and the index."""
    out = ROOT / "build" / "site-check"
    shutil.rmtree(out, ignore_errors=True)
    notebooks, figures = out / "notebooks", out / "figures"
    stem = "lenzo2017_two_spring_arm"
    run_notebook(ROOT / "notebooks" / f"{stem}.ipynb", notebooks / f"{stem}.ipynb",
                 {"quick": True, "figures_dir": str(figures / stem)})
    assert site.executed_errors(notebooks / f"{stem}.ipynb") == []
    index = site.build_site(notebooks, out / "site", figures, out / "cache")
    return index, out / "site" / f"{stem}.html"


def test_index_and_a_notebook_page_render_in_chromium(built_site):
    index, page = built_site
    shot = ROOT / "build" / "site-check" / "screenshot-notebook.png"
    report = index.parent / "report.html"
    result = site.browser_check([page, index, report], screenshot=shot)
    assert result == {page.name: [], index.name: [], report.name: []}
    assert shot.exists() and shot.stat().st_size > 10_000


def test_the_browser_check_catches_a_broken_page(tmp_path):
    (tmp_path / "ok.png").write_bytes((ROOT / "figures" / "lenzo2017_two_spring_arm" / "fig5_layouts.png").read_bytes())
    page = tmp_path / "broken.html"
    page.write_text('<html><body><img src="ok.png"><img src="missing.png"><a href="gone.html">gone</a>'
                    "<pre>Traceback (most recent call last):\n  boom</pre></body></html>")
    problems = site.browser_check([page])[page.name]
    assert any("missing.png" in p and "did not load" in p for p in problems)
    assert any("gone.html" in p for p in problems)
    assert any("traceback" in p for p in problems)
    assert not any("ok.png" in p for p in problems)
