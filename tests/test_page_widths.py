"""Every page a user opens fits a 1400 px window (#29): headless Chromium loads the report page,
the design page, the co-design page and the documentation site's landing page at 1400 px and
measures every table and code block against its container.

A block is *cut off* when it is wider than a container that does not scroll (its right part is
hidden or spills over the page); it *scrolls* when it sits in a container with ``overflow-x:
auto`` and that container has to scroll. The report and design pages must do neither (the
springs-to-buy table used to lose its mass column); the documentation site lets wide code blocks
and tables scroll by design (``docs/assets/css/extra.css``), so there only cut-off blocks fail.
"""

from __future__ import annotations

import html
import json
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

import pytest
from browser import CHROMIUM_FLAGS, chromium

ROOT = Path(__file__).resolve().parents[1]
WIDTH = 1400

PROBE = """<script>window.addEventListener('load', () => {
  const cut = [], scrolls = [];
  const name = el => el.tagName.toLowerCase() + ' "' + el.textContent.trim().replace(/\\s+/g, ' ')
    .slice(0, 50) + '"';
  for (const el of document.querySelectorAll('table, pre')) {
    let box = el.parentElement, scroller = null;
    for (let b = el; b && b !== document.body; b = b.parentElement) {
      const o = getComputedStyle(b).overflowX;
      if (o === 'auto' || o === 'scroll') { scroller = b; break; }
    }
    const right = el.getBoundingClientRect().right;
    const room = box.getBoundingClientRect().right - parseFloat(getComputedStyle(box).paddingRight);
    if (scroller) {
      if (scroller.scrollWidth > scroller.clientWidth + 1)
        scrolls.push(name(el) + ' ' + scroller.scrollWidth + ' > ' + scroller.clientWidth + ' px');
    } else if (el.scrollWidth > el.clientWidth + 1 || right > room + 1) {
      cut.push(name(el) + ' ' + Math.round(right) + ' > ' + Math.round(room) + ' px');
    }
  }
  document.body.setAttribute('data-widths', JSON.stringify({
    blocks: document.querySelectorAll('table, pre').length, cut: cut, scrolls: scrolls,
    window: window.innerWidth}));
});</script>"""
"""Measures every ``table`` and ``pre`` once the page has loaded; the result is an attribute of
``<body>`` in the dumped DOM."""

needs_chromium = pytest.mark.skipif(chromium() is None,
                                    reason="chromium not on PATH (apt-get install chromium)")


def measure(page: Path, tmp: Path) -> dict:
    """Load a copy of ``page`` (beside it, so its relative links and assets resolve) with
    :data:`PROBE` in a 1400 px wide headless Chromium; the probe's findings."""
    probe = page.with_name(f"probe-{page.name}")
    probe.write_text(page.read_text().replace("</body>", PROBE + "</body>"))
    profile = tempfile.mkdtemp(prefix="hexaleg-chromium-", dir=tmp)
    try:
        dom = subprocess.run([chromium(), *CHROMIUM_FLAGS, f"--user-data-dir={profile}",
                              f"--window-size={WIDTH},1000", "--virtual-time-budget=3000",
                              "--dump-dom", probe.as_uri()],
                             capture_output=True, text=True, timeout=180).stdout
    finally:
        probe.unlink()
        shutil.rmtree(profile, ignore_errors=True)
    found = re.search(r"data-widths=\"([^\"]*)\"", dom)
    assert found, dom[:500]
    return json.loads(html.unescape(found.group(1)))


@pytest.fixture(scope="module")
def pages(design_written, tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """design.html of the run's small design (``design_written``: its two families, Pareto
    point, maps and robust box, made once for the run; this fixture had designed a smaller one
    of its own, 9 s of a worker), copied to ``design/`` beside the report, and report.html of
    the default report led by it (it links the design page relatively)."""
    from hexaleg.commands.report.write import write_report
    from hexaleg.report.config import ReportConfig

    out = tmp_path_factory.mktemp("pages")
    shutil.copytree(design_written[1], out / "design")
    cfg = ReportConfig.from_mapping({"gait": {"samples": 200},
                                     "report": {"design": str(out / "design" / "design.json"),
                                                "stiffness_points": 5}})
    write_report(out / "report", cfg, progress=None)
    return {"report": out / "report" / "report.html", "design": out / "design" / "design.html"}


@needs_chromium
@pytest.mark.parametrize("name", ["report", "design"])
def test_the_report_and_design_pages_fit_1400_px(pages, name, tmp_path):
    found = measure(pages[name], tmp_path)
    assert found["window"] == WIDTH and found["blocks"] >= 5, found
    assert found["cut"] == [] and found["scrolls"] == [], found


@needs_chromium
def test_the_codesign_page_fits_1400_px(ruled, tmp_path):
    """codesign.html with the springs to buy (its parts table the widest block) neither cuts
    nor scrolls at 1400 px (issue #43)."""
    from hexaleg.commands.codesign.write import write_result

    write_result(ruled, tmp_path / "codesign")
    found = measure(tmp_path / "codesign" / "codesign.html", tmp_path)
    assert found["window"] == WIDTH and found["blocks"] >= 6, found
    assert found["cut"] == [] and found["scrolls"] == [], found


def test_the_report_links_its_design_page_relatively(pages):
    page = pages["report"].read_text()
    links = set(re.findall(r'href="([^"#]+)(?:#[^"]*)?"', page))
    assert links == {"../design/design.html"}, links
    assert (pages["report"].parent / "../design/design.html").resolve() == pages["design"]


@needs_chromium
@pytest.mark.skipif(shutil.which("mkdocs", path=str(ROOT / ".venv" / "bin")) is None
                    and shutil.which("mkdocs") is None,
                    reason='mkdocs not installed (pip install -e ".[docs]", which CI runs after '
                           "the tests)")
def test_the_docs_landing_page_cuts_nothing_at_1400_px(tmp_path):
    """The site built to a temporary folder; on its landing page no table or code block is cut
    off (wide ones scroll inside their own box)."""
    mkdocs = shutil.which("mkdocs", path=str(ROOT / ".venv" / "bin")) or shutil.which("mkdocs")
    site = tmp_path / "site"
    subprocess.run([mkdocs, "build", "-q", "-d", str(site)], cwd=ROOT, check=True,
                   capture_output=True, timeout=600)
    found = measure(site / "index.html", tmp_path)
    assert found["window"] == WIDTH and found["blocks"] >= 3, found
    assert found["cut"] == [], found
