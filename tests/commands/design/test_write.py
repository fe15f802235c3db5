"""Tests of the files of ``hexaleg design``: design.html, the files listed, the command line and
its errors."""

from __future__ import annotations

import copy
import json
import re
from html import unescape
from pathlib import Path
from typing import Any

import pytest
from browser import chromium

from hexaleg.cli import main
from hexaleg.outputs.html import render_design_html


def test_design_html_leads_with_the_answer(design_written):
    out = design_written[1]
    data = json.loads((out / "design.json").read_text())
    assert sorted(data["files"]) == sorted(p.name for p in out.iterdir()
                                          if not p.name.startswith("."))  # not the record
    html = (out / "design.html").read_text()
    assert html.index("Fit these springs") < html.index("The springs to buy")
    for plot in ("pareto", "map_period_stride", "map_payload_mu", "robust", "tolerance"):
        assert f'id="plot-{plot}"' in html
    assert html.index("The springs to buy") < html.index('<section id="simulated">')
    for row in data["simulation"]:
        loop = ", balance feedback" if row.get("feedback") else ", open loop"
        assert f'<td class="name">{row["label"]}{loop}</td>' in html
        assert row["simulated_saving"]["unit"] == row["predicted_saving"]["unit"] == "%"



def _page(design_written: Any) -> tuple[dict[str, Any], str]:
    out = design_written[1]
    return json.loads((out / "design.json").read_text()), (out / "design.html").read_text()


def _text(html: str) -> str:
    """The page's visible text: no style, no embedded images, no tags, spaces collapsed."""
    html = re.sub(r"<style>.*?</style>|src=\"data:[^\"]*\"", "", html, flags=re.S)
    return " ".join(unescape(re.sub(r"<[^>]+>", " ", html)).split())


def _section(html: str, sid: str) -> str:
    start = html.index(f'<section id="{sid}">')
    return html[start:html.index("</section>", start)]


def _pct(q: dict[str, Any]) -> str:
    return f"{q['value']:+.2f} %"


def test_tolerance_section_gives_the_numbers_of_design_json(design_written):
    """"Stops as a workshop mounts them": nominal and worst saving of the tolerant and the
    tolerance-blind design as design.json has them, what the worst is taken over, the plot
    (also written as tolerance.png); the answer quotes the recommended design's worst case."""
    data, html = _page(design_written)
    t = data["stop_tolerance"]
    assert t is not None and t["chosen"] == "tolerant"
    section = _text(_section(html, "tolerance"))
    assert section.startswith("Stops as a workshop mounts them")
    for name in ("tolerant", "blind"):
        assert f"{_pct(t[name]['nominal_saving'])} {_pct(t[name]['worst_saving'])}" in section
    assert "designed for ±1° — recommended" in section
    assert "worst case, not the mean" in section.lower()
    assert 'id="plot-tolerance"' in html and (design_written[1] / "tolerance.png").exists()
    answer = _text(html[html.index('<p class="answer">'):html.index("</p>")])
    assert f"within ±1°: {_pct(t['tolerant']['worst_saving'])} at worst" in answer


def test_springs_to_buy_give_the_arbor_the_envelope_and_the_hard_stop(design_written):
    """Each part's wound inside diameter against its arbor + margin; each part's worst S_y/σ
    over the whole envelope and where; the small design's femur spring yields at its URDF limit
    and the page tells the builder the stop (angle from the centre in deg, torque in N·mm)."""
    data, html = _page(design_written)
    buy = _text(_section(html, "buy"))
    for p in data["recommended"]["parts"]:
        s = p["torsion_spring"]
        assert (f"{1000 * s['wound_inner_diameter']['value']:.2f} ≥ "
                f"{1000 * s['arbor_diameter']['value']:.2f} + "
                f"{100 * s['arbor_margin']['value']:.0f} %") in buy
    stops = [e for e in data["envelope"] if e["hard_stop"]]
    assert [e["group"] for e in stops] == ["femur"]  # the case: it winds 286° at +150°
    for e in data["envelope"]:
        assert f"{e['safety_factor']['value']:.2f} ({e['design_factor']['value']:.2f})" in buy
        assert f"{e['worst']['source']}: {e['worst']['joint']} at" in buy
    (e,) = stops
    stop = e["hard_stop"]
    angle = f"{57.29577951308232 * stop['angle_from_centre']['value']:+.1f}°"
    torque = f"{1000 * stop['torque']['value']:.4g} N·mm"
    assert (f"Build a hard stop for the femur spring ({e['side']}): on each femur joint (6), "
            f"stop the spring's moving leg at {angle} from the joint's centre of motion") in buy
    assert f"the stop holds {torque}" in buy


def test_fatigue_replaces_the_static_only_sentence(design_written):
    """The fatigue safety at the stated life and the cycles a year at 1 h/day; no "static check
    only" left."""
    data, html = _page(design_written)
    buy = _text(_section(html, "buy"))
    assert "Static check only" not in html and "not checked" not in buy
    assert "n_f at 10 7 cycles" in buy  # 10<sup>7</sup>
    for f in data["fatigue"]:
        assert f["safety_factor"]["value"] >= 1
        row = buy[buy.index(f"{f['group']} ({f['side']}, {f['role']})", buy.index("Fatigue")):]
        assert f"{f['safety_factor']['value']:.2f} infinite" in row
        assert "1.31·10 6 (3.15·10 7 )" in row  # a 1 s period: 1314000 cycles a year


def test_fatigue_below_one_states_the_life_in_years(design_written):
    """A spring that does not last the stated life: the page gives the life it has, in cycles
    and in years at an hour of walking a day (a case built from the written design)."""
    data, _ = _page(design_written)
    data = copy.deepcopy(data)
    f = data["fatigue"][0]
    f.update(safety_factor={"value": 0.8, "unit": "1"}, meets=False,
             life={"value": 2.628e6, "unit": "cycles"})
    text = _text(render_design_html(data, _images(design_written[1])))
    assert (f"{f['group']} spring ({f['side']}): fatigue safety 0.80 at 10 7 cycles: it lasts "
            "2.63·10 6 cycles, about 2.0 years at an hour of walking a day") in text


def _images(out: Path) -> dict[str, str]:
    return {p.stem: "data:," for p in out.glob("*.png")}


def test_dropped_groups_and_robust_springs_to_buy(design_written):
    """Parsimony's dropped group with what it would have added; the robust design as springs to
    buy, in the recommended springs' table (one macro)."""
    data, html = _page(design_written)
    dropped = data["recommended"]["dropped_groups"]
    assert dropped, "the small design drops the coxa (+0.24 %, under the 1-point bar)"
    text = _text(html)
    for g, info in dropped.items():
        assert f"{g}: would have added {_pct(info['marginal_saving'])} of the electrical" in text
    robust = _section(html, "robust")
    assert robust.count('<table class="parts">') == 1
    header = _section(html, "buy")
    header = header[header.index('<table class="parts">'):header.index("</tr>")]
    assert header in robust
    for p in data["robust"]["design"]["parts"]:
        assert f"{1000 * p['torsion_spring']['wire_diameter']['value']:.2f} / " in robust


def test_page_reads_in_engineering_units_and_one_precision(design_written):
    """No SI spring sizes, masses or torques, no float noise (a 1e-18 magnitude reads 0), every
    percentage in a table cell of the design's own tables with two decimals, and each metric the
    springs make worse explained."""
    data, html = _page(design_written)
    text = _text(html)
    assert not re.search(r"\d(\.\d+)?e[-+]?\d", text), re.findall(r"\S+e[-+]?\d+", text)
    for sid in ("buy", "robust", "families", "pareto", "ranking"):  # mm, g, N·mm
        assert not re.search(r"\d (kg|m|N·m)\b", _text(_section(html, sid))), sid
    own = html.replace(_section(html, "simulated"), "")
    cells = re.findall(r"<td[^>]*>\s*([-+]?\d[\d.]* %)\s*</td>", own)  # a percentage alone
    assert len(cells) > 20 and all(re.fullmatch(r"[-+]\d+\.\d\d %", c) for c in cells), cells
    worse = [k for k, s in data["recommended"]["saving"].items() if s["value"] < 0]
    assert "positive_work" in worse
    words = {"positive_work": "positive work ∫ max(0, τq̇)", "absolute_work": "absolute work ∫ |τq̇|",
             "mean_abs_torque": "mean |τ|"}
    for k in worse:
        assert f"{words.get(k, k)} {_pct(data['recommended']['saving'][k])}:" in text
    assert "the servos' electrical draw" in text
    for code in ("positive_work", "electrical_noregen", "x the animal line"):  # words (#43)
        assert code not in text, code


@pytest.mark.skipif(chromium() is None, reason="chromium not on PATH (apt-get install chromium)")
def test_page_fits_a_1400_px_window(design_written, tmp_path):
    """Headless Chromium at 1400 px: the page does not scroll sideways, and a table wider than
    its container sits in a wrapper that scrolls it (overflow-x: auto)."""
    import subprocess
    import tempfile

    from browser import CHROMIUM_FLAGS

    probe = ("<script>window.addEventListener('load', () => { const bad = [...document"
             ".querySelectorAll('table, pre')].filter(t => t.scrollWidth > t.parentElement"
             ".clientWidth + 1 && getComputedStyle(t.parentElement).overflowX !== 'auto')"
             ".map(t => t.closest('section').id); bad.push('doc:' + (document.documentElement"
             ".scrollWidth > window.innerWidth)); document.body.setAttribute('data-wide', "
             "bad.join(' ')); });</script>")
    page = tmp_path / "probe.html"
    html = (design_written[1] / "design.html").read_text()
    page.write_text(html.replace("</body>", probe + "</body>"))
    profile = tempfile.mkdtemp(prefix="hexaleg-chromium-", dir=tmp_path)
    dom = subprocess.run([chromium(), *CHROMIUM_FLAGS, f"--user-data-dir={profile}",
                          "--window-size=1400,900", "--virtual-time-budget=3000", "--dump-dom",
                          page.as_uri()], capture_output=True, text=True, timeout=120).stdout
    wide = re.search(r'data-wide="([^"]*)"', dom)
    assert wide, dom[:500]
    assert wide.group(1) == "doc:false"


BASE = '[design]\nsamples = 100\nfamilies = ["linear"]\npareto_fractions = []\n'


@pytest.mark.parametrize(("extra", "says"), [
    ("[design.max_outer_diameter]\nfemur = 0.0003\n", ["thinnest preferred wire"]),
])
def test_bad_design_inputs_say_what_to_change(tmp_path, capsys, extra, says):
    """Inputs no design can meet end in a named error that says what to change."""
    config = tmp_path / "d.toml"
    config.write_text(BASE + extra)
    assert main(["design", "--config", str(config), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    for text in says:
        assert text in err


def test_a_map_condition_without_a_gait_is_a_cell_that_says_why(tmp_path):
    """A stride ×8 the leg cannot reach is a map cell "no gait: …" (n/a on the plot), and the
    page says why and what would work — not the end of the design."""
    config = tmp_path / "d.toml"
    config.write_text(BASE + "map_stride = [1.0, 8.0]\nmap_period = [1.0]\nmap_payload = [0.0]\n"
                      "map_mu = [0.6]\n")
    assert main(["design", "--config", str(config), "--out", str(tmp_path / "o")]) == 0
    data = json.loads((tmp_path / "o" / "design.json").read_text())
    (status,) = [m["status"] for m in data["maps"] if m["axes"] == ["period", "stride"]]
    assert status[0][0] == "ok" and status[0][1].startswith("no gait:")
    text = _text((tmp_path / "o" / "design.html").read_text())
    assert "Cells marked n/a: no gait:" in text and "would work" in text


def test_limits_under_which_no_spring_pays_give_that_answer(tmp_path, capsys):
    """A spring torque bound of 0.1 µN·m leaves nothing to save: the design is written and says
    "no springs pay" — an answer, not an error, and never a recommendation that costs energy."""
    config = tmp_path / "d.toml"
    config.write_text(BASE + "max_torque = 1e-7\n")
    assert main(["design", "--config", str(config), "--out", str(tmp_path / "o")]) == 0
    out = capsys.readouterr().out
    assert "no springs pay here" in out
    data = json.loads((tmp_path / "o" / "design.json").read_text())
    assert data["pays"] is False
    assert any(n.startswith("no springs pay") for n in data["notes"])


def test_a_non_finite_number_is_written_as_null_and_read_back(design_written, tmp_path):
    """One JSON policy (#37, #39): a part's stress that is not finite (no spring fits) goes into
    design.json as null with a note, never ``Infinity``; load_design, report --design and the
    design page read the file back."""
    import hexaleg
    from hexaleg.cli import main
    from hexaleg.config import read_json
    from hexaleg.quantities import NON_FINITE, json_text
    from hexaleg.report.design_section import design_section

    data = read_json(design_written[1] / "design.json")
    data["recommended"]["parts"][0]["torsion_spring"]["stress"]["value"] = float("inf")
    path = tmp_path / "design.json"
    path.write_text(json_text(data))
    text = path.read_text()
    assert not re.search(r"[:\[,]\s*-?(?:NaN|Infinity)\b", text)  # no such JSON token
    back = read_json(path)
    assert back["recommended"]["parts"][0]["torsion_spring"]["stress"]["value"] is None
    assert back[NON_FINITE]["paths"] == [
        "recommended.parts[0].torsion_spring.stress.value"]
    assert hexaleg.load_design(path).springs
    assert design_section(str(path))
    assert main(["report", "--design", str(path), "--out", str(tmp_path / "r")]) == 0


TINY_TOML = """[design]
samples = 100
families = ["linear"]
map_period = [1.0]
map_stride = [1.0]
map_payload = [0.0]
map_mu = [0.6]
map_slope = [0.0]
map_pattern = ["tripod"]
robust_period = [1.0, 1.25]
robust_stride = [1.0, 1.0]
robust_payload = [0.0, 0.0]
robust_mu = [0.6, 0.6]
pareto_fractions = []
"""
"""tests/conftest.py's TINY_DESIGN as a file."""


@pytest.mark.slow
def test_a_stage_that_fails_leaves_the_design_before_it_and_the_next_run_resumes(
        design_json, tmp_path, capsys, monkeypatch):
    """The maps failing (injected) end the design's stages there, not the design: the command
    writes design.json and the page with the stages before it, naming the stage and the keys
    that set it, in one error line (status 2), and keeps the finished stages; the next run
    reads them back instead of computing them, and its design is the one a run never
    interrupted writes (tests/conftest.py's ``design_json``), but for the timings. ~10 s."""
    from conftest import TINY_DESIGN

    from hexaleg.commands.design.write import write_design
    from hexaleg.design.chain import chain as chain_module
    from hexaleg.design.chain.checkpoint import FOLDER
    from hexaleg.errors import InvalidParameterError
    from hexaleg.scenario.scenario import Scenario

    def fails(*_a, **_k):
        raise InvalidParameterError("design.map_mu", 9.0, "an injected failure")

    (tmp_path / "tiny.toml").write_text(TINY_TOML)
    out = tmp_path / "o"
    monkeypatch.setattr(chain_module, "robustness_maps", fails)
    assert main(["design", "--config", str(tmp_path / "tiny.toml"), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    (line,) = [x for x in err.splitlines() if "error:" in x]
    assert line.startswith("hexaleg design: error: the maps stage failed (InvalidParameterError:")
    assert "robust, proof not run" in line and "map_period" in line and "resumes" in line
    data = json.loads((out / "design.json").read_text())
    assert data["failed"]["stage"] == "maps" and data["failed"]["left_out"] == ["robust", "proof"]
    assert data["stages"] == ["candidates", "pareto", "ranking", "tolerance", "envelope", "fold"]
    assert data["maps"] == [] and data["robust"] is None and data["recommended"]
    assert sorted(data["files"]) == sorted(p.name for p in out.iterdir()
                                           if not p.name.startswith("."))
    page = _text((out / "design.html").read_text())
    assert "The maps stage failed" in page and "map_slope" in page
    kept = sorted(p.stem for p in (out / FOLDER).glob("*.pickle"))
    assert kept == sorted(data["stages"])

    monkeypatch.undo()
    said: list[str] = []
    write_design(out, Scenario.from_tables("hexaleg", TINY_DESIGN), progress=said.append)
    # linear's optimum, the Pareto front, the ranking, the envelope, the fold (a linear
    # spring has no stop: no tolerance line)
    assert sum(line.endswith("(kept from the earlier run)") for line in said) == 5
    assert not (out / FOLDER).exists()  # the design is whole: nothing left to resume
    again = json.loads((out / "design.json").read_text())
    whole = json.loads(design_json.read_text())
    for d in (again, whole):
        d.pop("timings")
    assert again == whole
