"""Tests of hexaleg.commands.report.write: the self-contained HTML and its plots on disk, what a
browser shows, a bad design file that leaves no directory (the command line:
tests/commands/report/test_command.py)."""

from __future__ import annotations

import base64
import math
import re
import subprocess
import tempfile

import numpy as np
import pytest
from browser import CHROMIUM_FLAGS, chromium, finish, page_requests, start_screenshot
from PIL import Image

from hexaleg.commands.report.write import PLOTS, write_report

SECTIONS = ("summary", "angles", "torques", "power", "forces", "energy", "cot", "transform",
            "curve", "paper")


def test_html_has_every_section_and_embeds_every_plot(report_written, data):
    r, out = report_written
    html = (out / "report.html").read_text()
    for sid in SECTIONS:
        assert re.search(rf'<section id="{sid}">\s*<h2>', html), sid
    for heading in ("Robot and gait", "Joint angles", "motor vs spring", "Power per joint",
                    "friction usage", "with and without springs", "Cost of transport",
                    "energy of transforming",
                    "Stiffness curve", "single joint"):
        assert heading in html
    imgs = re.findall(r'<img[^>]*id="plot-(\w+)"[^>]*src="data:image/png;base64,([^"]+)"', html)
    assert sorted(n for n, _ in imgs) == sorted(PLOTS)
    for name, b64 in imgs:  # the embedded image is the PNG file written next to the page
        assert base64.b64decode(b64) == (out / f"{name}.png").read_bytes()
        assert (out / f"{name}.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert data["title"] == "test report" and "<title>test report</title>" in html
    assert sorted(data["files"]) == sorted(p.name for p in r.files)


def test_html_needs_no_external_url(report_written):
    html = (report_written[1] / "report.html").read_text()
    refs = re.findall(r'(?:src|href)\s*=\s*"([^"]*)"', html)
    assert refs and all(u.startswith(("data:", "#")) for u in refs), refs
    assert not re.search(r"url\(|@import|<script|<link|<iframe", html)
    assert "http" not in re.sub(r"<p class=\"note\">Motor data:.*?</p>", "", html, flags=re.S)


def test_html_numbers_are_the_json_numbers(report_written, data):
    """Each number as the page's rule writes it: savings signed with two decimals, spring rates
    in N·mm/deg, angles in degrees, lengths in mm, other quantities to four figures."""
    html = (report_written[1] / "report.html").read_text()
    e = data["energy"]["totals"]["electrical"]
    for q in (e["with_springs"], e["baseline"], data["robot"]["mass"],
              data["forces"]["peak_friction_usage"]):
        assert f"{q['value']:.4g}" in html, q
    assert f"saving {e['saving']['value']:+.2f} %" in html
    assert f"<b id=\"headline-saving\">{data['design']['saving']['value']:+.2f} %</b>" in html
    k_m = data["stiffness_curve"]["k_M"]["value"] * 1000 * math.pi / 180
    assert f"{k_m:.4g} N·mm/deg" in html
    lf = data["reference"]["joints"]["LF_femur"]
    assert f"{math.degrees(lf['neutral']['value']):.1f}°" in html
    assert f"{100 * lf['engaged_fraction']['value']:.2f} %" in html
    ref = data["reference"]["energy"]["electrical"]["saving"]
    assert f"{ref['value']:+.2f} %" in html  # the reference's saving, in its own section
    law = data["springs"]["joints"]["LF_tibia"]["parameters"]  # the answer's spring, its law
    assert (f"k {law['stiffness']['value'] * 1000 * math.pi / 180:.4g} N·mm/deg, reference "
            f"angle {math.degrees(law['reference']['value']):.1f}°") in html
    assert f"{1000 * data['gait']['stride_length']['value']:.1f} mm" in html


def test_the_stiffness_curve_is_drawn_in_n_mm_per_deg(report_written):
    """The plot's rates match the page's tables: N·mm/deg, k_M's line where the page says."""
    from hexaleg.commands.report.write import _figures

    r, _ = report_written
    ax = _figures(r)["stiffness_curve"].axes[0]
    assert "N·mm/deg" in ax.get_xlabel() and "N·m/rad" not in ax.get_xlabel()
    k_m = r.data["stiffness_curve"]["k_M"]["value"] * 1000 * math.pi / 180
    assert any(str(line.get_label()) == f"k_M (eq. 19) = {k_m:.4g} N·mm/deg"
               for line in ax.get_lines())
    assert max(ax.get_lines()[0].get_xdata()) == pytest.approx(
        max(r.curve.stiffness) * 1000 * math.pi / 180)


def _visible(html: str) -> str:
    """The page's text as a reader sees it (no tags, no embedded images)."""
    import html as h

    return h.unescape(re.sub(r"<[^>]+>", " ", re.sub(r'src="data:[^"]*"', "", html)))


def test_the_page_follows_the_reading_rules(report_written, data):
    """#29's rules: one precision for percentages, no float noise, no SI-only numbers a spring
    maker would convert (m, rad), one k_M of this gait."""
    text = _visible((report_written[1] / "report.html").read_text())
    own = text.split("The paper's single joint, for reference")[0]  # its verdicts are quoted
    own = re.sub(r"≥ [\d.]+ \+ \d+ %", "", own)  # the arbor's margin setting, "+ 10 %"
    percents = re.findall(r"([−+-]?\d+(?:\.\d+)?) %", own)
    odd = sorted({p for p in percents if not re.fullmatch(r"[+-]?\d+\.\d\d", p)})
    assert percents and not odd, odd
    assert not re.search(r"\de-\d", own)  # −2.224e-16 J of net work: 0 J
    assert abs(data["energy"]["net_work"]["with_springs"]["value"]) < 1e-12
    assert "net work ∫ τq̇ 0 J" in " ".join(own.split())
    # engineering words, not code names (#43): metrics, cones, conventions, objectives
    for code in ("net_work", "electrical_noregen", "int_sq", "eq14", "(soc)", "force objective",
                 "theta_minus", "torque_at_reference", "mean_abs"):
        assert code not in text, code
    assert not re.search(r"\d (?:m|rad)(?![\w/·²])|\d rad/s", own)  # mm, deg, deg/s
    assert own.count("k_M (eq. 19) on this gait") == 1
    assert "N·m/rad" not in own


# --------------------------------------------------------------------------- in the browser

needs_chromium = pytest.mark.skipif(chromium() is None,
                                    reason="chromium not on PATH (apt-get install chromium)")


@needs_chromium
def test_browser_loads_every_plot_and_fetches_nothing(report_written, tmp_path):
    """Chromium opens a copy of report.html with a probe script that lists the decoded images
    (naturalWidth > 0) in the DOM; the net log shows that the page requested nothing."""
    page = tmp_path / "probe.html"
    probe = ("<script>window.addEventListener('load', () => { const ok = [...document.images]"
             ".filter(i => i.complete && i.naturalWidth > 0).map(i => i.id + ':' + "
             "i.naturalWidth + 'x' + i.naturalHeight); document.body.setAttribute("
             "'data-loaded', ok.join(' ')); });</script>")
    html = (report_written[1] / "report.html").read_text()
    page.write_text(html.replace("</body>", probe + "</body>"))
    profile = tempfile.mkdtemp(prefix="hexaleg-chromium-", dir=tmp_path)
    net = tmp_path / "net.json"
    dom = subprocess.run([chromium(), *CHROMIUM_FLAGS, f"--user-data-dir={profile}",
                          "--virtual-time-budget=3000", f"--log-net-log={net}", "--dump-dom",
                          page.as_uri()], capture_output=True, text=True, timeout=120).stdout
    loaded = re.search(r'data-loaded="([^"]*)"', dom)
    assert loaded, dom[:500]
    sizes = dict(item.split(":") for item in loaded.group(1).split())
    assert sorted(sizes) == sorted(f"plot-{n}" for n in PLOTS)
    for name in PLOTS:
        w, h = Image.open(report_written[1] / f"{name}.png").size
        assert sizes[f"plot-{name}"] == f"{w}x{h}"
    assert page_requests(net) == []


@needs_chromium
def test_browser_screenshot_shows_coloured_plots(report_written, tmp_path):
    png = tmp_path / "shot.png"
    finish(start_screenshot((report_written[1] / "report.html").as_uri(), png, size=(1000, 1800)),
           timeout=120)
    rgb = np.asarray(Image.open(png).convert("RGB"), dtype=float) / 255
    sat = rgb.max(2) - rgb.min(2)
    # the plots' coloured lines (six leg colours) cover a visible part of the page; text, tables
    # and a blank page are grey or white
    assert (sat > 0.3).mean() > 0.005
    assert rgb.std() > 0.1  # not a blank page


# --------------------------------------------------------------------------- CLI and bad input


def test_a_bad_design_file_leaves_no_directory(tmp_path):
    """A run that cannot start writes nothing: --design /dev/zero used to create --out first."""
    from hexaleg.errors import ConfigError
    from hexaleg.report.config import ReportConfig

    out = tmp_path / "report-out"
    cfg = ReportConfig.from_mapping({"report": {"design": "/dev/zero"}})
    with pytest.raises(ConfigError, match=r"/dev/zero is not a regular file"):
        write_report(out, cfg, progress=None)
    assert not out.exists()
