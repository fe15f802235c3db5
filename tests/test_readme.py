"""The README's quick-start commands are the ones CI runs."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

import hexaleg
import hexaleg.design.evaluator
from hexaleg import units
from hexaleg.design.robust.conditions import robustness
from hexaleg.design.studies.optimise import optimise
from hexaleg.report.build import build_report
from hexaleg.robot.registry import DESCRIPTIONS

ROOT = Path(__file__).resolve().parents[1]


def _bash_blocks(text: str) -> list[str]:
    return [b.strip() for b in re.findall(r"```bash\n(.*?)```", text, re.S)]


def test_ci_runs_the_readme_quick_start_commands():
    """The Quick start's two commands, install + the report and install + the tests, are lines
    of .ci/run verbatim."""
    blocks = _bash_blocks((ROOT / "README.md").read_text())
    report = [b for b in blocks if b.endswith("hexaleg report") and "pip install ." in b]
    tests = [b for b in blocks if b.endswith("pytest") and '".[test]"' in b]
    assert len(report) == 1 and len(tests) == 1, blocks
    ci = (ROOT / ".ci" / "run").read_text().splitlines()
    for cmd in (*report, *tests):
        assert cmd in ci, f"README command {cmd!r} not run verbatim by .ci/run"


# --------------------------------------------------------------------------------------------
# Golden numbers: every number "What the numbers say" quotes about the paper's joint and the
# walking robot, recomputed through the public API and compared at the precision the README
# prints it. Each number is read from README.md itself (a regex around its words), so editing
# the README or the code alone fails here.

README = " ".join((ROOT / "README.md").read_text().split())  # whitespace-normalised (wrapped)
NUMBER = r"([−+]?[\d,]*\.?\d+(?:e[−+-]?\d+)?)"
"""One number as the README prints it: sign (U+2212 or +), thousands commas, decimals, e-power."""


def _said(pattern: str) -> tuple[str, ...]:
    """The numbers the README says in ``pattern`` (``{n}`` stands for one number)."""
    m = re.search(pattern.replace("{n}", NUMBER), README)
    assert m, f"README.md no longer matches {pattern!r}: update the sentence or this test"
    return m.groups()


def _as_printed(value: float, printed: str) -> str:
    """``value`` written as the README writes ``printed``: the same decimals (or significant
    digits of an e-power, or rounding place of a comma-grouped integer) and sign style."""
    sign = "−" if value < 0 else ("+" if printed[0] in "+−" else "")
    body, x = printed.lstrip("+−"), abs(value)
    if "e" in body:
        mantissa, _ = body.split("e")
        digits = len(mantissa.partition(".")[2])
        m, e = f"{x:.{digits}e}".split("e")
        text = f"{m}e{int(e)}".replace("-", "−") if "−" in body else f"{m}e{int(e)}"
    elif "," in body:
        zeros = len(body.replace(",", "")) - len(body.replace(",", "").rstrip("0"))
        text = f"{round(x, -zeros):,.0f}"
    else:
        text = f"{x:.{len(body.partition('.')[2])}f}"
    return sign + text


def _check(label: str, value: float, printed: str) -> None:
    assert _as_printed(value, printed) == printed, (
        f"README says {label} = {printed}, the code gives {value!r} "
        f"(= {_as_printed(value, printed)} at the README's precision)")


def test_readme_design_answer_is_the_kept_log():
    """The Quick start's design answer is analysis/logs/answer_hexaleg.log's (the log is diffed
    against ``hexaleg design``'s computation by test_examples)."""
    log = (ROOT / "analysis" / "logs" / "answer_hexaleg.log").read_text()
    readme = (ROOT / "README.md").read_text()
    rec = re.search(r"recommended: .*; electrical\s+(\S+) %, net\s+(\S+) % \((\S+) g", log)
    assert rec, log
    saving, net, grams = rec.groups()
    assert f"saving {saving} % of the energy the" in readme.replace("\n", " ")
    assert f"({net} % net of their {grams} g)" in readme.replace("\n", " ")
    femur = re.search(r"femur\s+above needs .* d (\S+) mm, D \S+ mm, OD (\S+) .* (\S+) turns,"
                      r".* preload (\d+)°", log)
    assert femur, log
    d, od, turns, preload = femur.groups()
    text = readme.replace("\n", " ")
    assert f"{d} mm music wire, {turns} turns, {od} mm outer diameter, preloaded by {preload}°" \
        in text
    worst = re.search(r"worst\s+(\S+) % at (period ×[^\n]+)", log)
    assert worst and f"the worst case {worst.group(1)} % at {worst.group(2)}" in text
    # where the femur spring mounts, in LF_femur's own angle (from the joint's zero)
    mount = re.search(r"LF_femur\s+above centre\s+\S+, spring stop\s+(\S+) \(\S+\), free leg "
                      r"\s*\S+, hard stop (\S+)", log)
    assert mount, log
    assert f"its stop at joint angle {mount.group(1)} on LF_femur and a hard stop at " \
        f"{mount.group(2)}" in text
    # the fold out and back: its extra energy with the springs and the walk that pays for it
    ways = re.findall(r"→ \w+\s+(\S+) / (\S+), torque", log)
    assert len(ways) == 2, log
    extra = sum(float(w) - float(b) for w, b in ways)
    pays = re.search(r"pay for a fold out and back after (\S+) m", log)
    assert pays, log
    assert f"costs {extra:.2f} J more with them, which {pays.group(1)} m of walking" in text
    simulated = {c: re.search(rf"{c}\s+.* / +(\S+) % +\S+ mm", log)
                 for c in ("feedforward \\+ PD", "position only")}
    assert all(simulated.values()), log
    ff, pos = (m.group(1) for m in simulated.values() if m)
    assert f"with feedforward + PD servos they save {ff} % (position-only servos: {pos} %)" \
        in text


def test_as_printed_rounds_like_the_readme():
    assert _as_printed(1.7067, "1.71") == "1.71"
    assert _as_printed(-0.0121, "−1.2") == "−0.0"
    assert _as_printed(-1.2126, "−1.2") == "−1.2"
    assert _as_printed(0.474, "+0.5") == "+0.5"
    assert _as_printed(7.1354e-4, "7.14e-4") == "7.14e-4"
    assert _as_printed(96357.0, "96,000") == "96,000"
    assert _as_printed(8030.0, "8,000") == "8,000"
    assert _as_printed(5.93, "6") == "6"


@pytest.fixture(scope="module")
def report() -> dict:
    """``hexaleg report``'s numbers (report.json) at the defaults: built-in robot, default gait,
    AX-18A, the quick answer's springs analysed, the paper-style femur springs the reference;
    with the paper's single joint."""
    return build_report().data


def test_readme_quick_start_says_what_the_report_answers(report):
    """The line after the Quick start's first command quotes the answer ``hexaleg report``
    prints (its last summary line, the same function over the same numbers) and the paper
    design's saving it keeps as the reference."""
    from hexaleg.report.answer import answer_line

    quick = re.search(r"```bash\n[^`]*hexaleg report\n```\n\nIt answers which springs to fit: "
                      r"`([^`]+)` \(" + NUMBER + r" % for the paper's design",
                      (ROOT / "README.md").read_text())
    assert quick, "README.md's quick start lost its answer line: update it or this test"
    quoted, paper = quick.groups()
    assert report["design"]["origin"] == "quick" and report["design"]["saving"]["value"] > 0
    assert answer_line(report["design"]).startswith(quoted + " ("), (
        f"README quotes {quoted!r}; hexaleg report prints {answer_line(report['design'])!r}")
    _check("the paper-style femur springs' electrical saving (%)",
           report["reference"]["energy"]["electrical"]["saving"]["value"], paper)


def test_readme_paper_k_M(report):
    paper = report["paper"]
    printed, si, nmm_deg = _said(r'k_M = {n} "N·mm/deg" is {n} N·m/rad\*\* \(= {n} N·mm/deg\)')
    _check("the paper's printed k_M", paper["k_M_printed"]["value"], printed)
    k_M = paper["k_M"]["value"]  # eq. 19 in SI, N·m/rad
    _check("k_M (N·m/rad)", k_M, si)
    _check("k_M (N·mm/deg)", float(units.nm_per_rad_to_nmm_per_deg(k_M)), nmm_deg)
    (arith,) = _said(r"Table 6 gives {n} only with m in kg, l in mm and I in kg·mm²")
    _check("eq. 19 with the paper's units", paper["k_M_paper_number"]["value"], arith)
    assert paper["k_M_paper_units_are"].startswith("kg·mm²·s⁻²/rad = 1e-6 N·m/rad")


def test_readme_paper_simulated_stiffnesses(report):
    lo, hi, r_lo, r_hi = _said(r"simulates \({n}–{n} N·mm/deg\) are {n}–{n} × that")
    k_M = report["paper"]["k_M"]["value"]
    for k, ratio in ((lo, r_lo), (hi, r_hi)):
        _check(f"{k} N·mm/deg / k_M", float(units.nmm_per_deg_to_nm_per_rad(float(k))) / k_M,
               ratio)


def test_readme_paper_k_E_and_saving_not_reproduced(report):
    paper = report["paper"]
    k_E, saving = _said(r"k_E = {n} and its {n} % saving are not reproduced")
    _check("the paper's printed k_E", paper["k_E_printed"]["value"], k_E)
    _check("the paper's printed saving", paper["saving_printed"]["value"], saving)
    assert paper["k_E_verdict"].startswith("not reproduced")
    assert paper["saving_verdict"].startswith("not reproduced")


def test_readme_paper_no_gravity_savings(report):
    paper = report["paper"]
    peak, work = _said(r"peak torque exactly 1 − θ_k/A = {n} %, positive work {n} % at its optimum")
    model = paper["model"]
    ratio = 100 * (1 - model["theta_k"]["value"] / model["amplitude"]["value"])
    _check("1 − θ_k/A (%)", ratio, peak)
    _check("the peak-torque saving (%)", paper["peak_saving"]["value"], peak)
    _check("the positive-work saving at its optimum (%)",
           paper["optima_no_gravity"]["positive_work"]["saving"]["value"], work)


def test_readme_gait_energy_and_default_design(report):
    joule, electrical, period = _said(
        r"\({n} J of {n} J electrical per {n} s cycle of the default gait\)")
    assert report["gait"]["period"]["value"] == float(period)
    totals = report["energy"]["totals"]
    _check("Joule loss per cycle without springs (J)", totals["joule"]["baseline"]["value"], joule)
    _check("electrical energy per cycle without springs (J)",
           totals["electrical"]["baseline"]["value"], electrical)
    # the report's reference is the paper's design carried over: centred dead zone on the femurs
    springs = report["reference"]
    assert springs["design"] == "paper" and all(j.endswith("_femur") for j in springs["joints"])
    assert all(s["theta_minus"]["value"] == -s["theta_plus"]["value"]
               for s in springs["joints"].values())
    (cost,) = _said(r"centred on the femur's swing — the paper's design carried over — "
                    r"costs energy \({n} %\)")
    _check("the paper-style femur springs' electrical saving (%)",
           springs["energy"]["electrical"]["saving"]["value"], cost)


# The placement results: notebook 03's configuration, which the README names (samples per cycle,
# offset bound); the same calls as the notebook, one computation per session (~25 s).

CLASSES = ("coxa", "femur", "tibia")


@pytest.fixture(scope="module")
def placement_gait():
    """(evaluator of notebook 03's gait, class → joints, offset bound), as the README names them."""
    samples, bound = _said(r"notebook 03 at {n} samples per cycle, the neutral offset searched "
                           r"within ±{n} rad")
    ev = hexaleg.design.evaluator.evaluator(
        hexaleg.Scenario.load().with_gait({"samples": int(samples)}))
    return ev, {c: ev.robot.joints(c) for c in CLASSES}, float(bound)


@pytest.fixture(scope="module")
def symmetric(placement_gait):
    ev, groups, _ = placement_gait
    return {c: optimise(ev, c, groups[c], "electrical") for c in CLASSES}


@pytest.fixture(scope="module")
def off_centre(placement_gait):
    ev, groups, bound = placement_gait
    return {c: optimise(ev, c, groups[c], "electrical", offset_bounds=(-bound, bound),
                                grid=(8, 4, 7)) for c in ("femur", "tibia")}


def test_readme_symmetric_dead_zones(symmetric):
    (coxa,) = _said(r"symmetric dead zones save ≈ 0 % on femur and tibia \({n} % on the coxa\)")
    _check("the optimised symmetric coxa springs' saving (%)", 100 * symmetric["coxa"].saving,
           coxa)
    zero = f"{0:.{len(coxa.partition('.')[2])}f}"  # "≈ 0" at the precision of the coxa's number
    for c in ("femur", "tibia"):
        _check(f"the optimised symmetric {c} springs' saving (%)", abs(100 * symmetric[c].saving),
               zero)


def test_readme_off_centre_dead_zones(placement_gait, off_centre):
    femur, tibia = _said(r"saves {n} % \(femur\) and {n} % \(tibia\) of the electrical energy")
    _check("the off-centre femur springs' saving (%)", 100 * off_centre["femur"].saving, femur)
    _check("the off-centre tibia springs' saving (%)", 100 * off_centre["tibia"].saving, tibia)
    bound = placement_gait[2]  # "where the optimum sits on the bound"
    assert all(abs(o.offset) == pytest.approx(bound) for o in off_centre.values())


def test_readme_tibia_design_robustness(placement_gait, off_centre):
    ev, groups, _ = placement_gait
    low, high, change = _said(r"the tibia design keeps {n}–{n} % when the gait period or stride "
                              r"changes by ±{n} %")
    f = float(change) / 100
    run = hexaleg.Scenario.load().replace(gait=hexaleg.GaitParams(samples=ev.gait.samples))
    rob = robustness(run, {"tibia": groups["tibia"]}, {"tibia": off_centre["tibia"].design()},
                     "electrical", factors=(1 - f, 1.0, 1 + f))
    assert set(rob["parameter"]) == {"period", "stride_length"} and (rob["status"] == "ok").all()
    _check("the tibia design's least saving (%)", 100 * rob["saving"].min(), low)
    _check("the tibia design's largest saving (%)", 100 * rob["saving"].max(), high)


def test_readme_global_optimum_against_the_old_search():
    """The README's placement numbers are the kept placement log's (itself diffed against the
    study by tests/test_examples.py)."""
    new, old = _said(r"designed together, save {n} % of the Joule energy against {n} % for the "
                     r"old search")
    log = (ROOT / "analysis" / "logs" / "placement_hexaleg.log").read_text()
    preloaded = log[log.index("preloaded: every set"):]
    m = re.search(r"coxa\+femur\+tibia\s+\S+\s+(\S+)%\s+(\S+)%", preloaded)
    assert m and m.groups() == (f"+{new}", f"+{old}")


def test_readme_robot_flag_and_registered_robots():
    """"Every command but `paper` and `motors` takes `--robot NAME` (…)": the parser's commands
    and the registry's robots, in its order."""
    import argparse

    from hexaleg.cli import build_parser

    m = re.search(r"Every command but `paper` takes `--robot NAME` \(([^)]*)\)", README)
    assert m, "README.md no longer lists the robots --robot takes: update it or this test"
    assert m.group(1).split(", ") == list(DESCRIPTIONS)
    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    without = {name for name, p in sub.choices.items()
               if "--robot" not in {s for a in p._actions for s in a.option_strings}}
    assert without == {"paper"}


def test_docs_report_page_numbers_are_the_default_report(report):
    """docs/report.md's numbers of the default report (the answer's saving, the reference's,
    the fold into a sphere with the answer's springs) are ``hexaleg report``'s, at the
    precision the page prints them."""
    text = " ".join((ROOT / "docs" / "report.md").read_text().split())

    def said(pattern: str) -> tuple[str, ...]:
        m = re.search(pattern.replace("{n}", NUMBER), text)
        assert m, f"docs/report.md no longer matches {pattern!r}"
        return m.groups()

    (quick,) = said(r"On the default robot {n} % of the energy the servos draw")
    _check("the quick answer's saving (%)", report["design"]["saving"]["value"], quick)
    (ref,) = said(r"The paper's design carried over to the robot \({n} % on this robot\)")
    _check("the reference's saving (%)", report["reference"]["energy"]["electrical"]["saving"][
        "value"], ref)
    without, with_, saving = said(r"the transformation costs {n} J electrical without springs "
                                  r"and {n} J with the answer's linear springs \({n} %\)")
    fold = report["transform"]
    _check("the fold without springs (J)", fold["totals"]["electrical"]["baseline"]["value"],
           without)
    _check("the fold with springs (J)", fold["totals"]["electrical"]["with_springs"]["value"],
           with_)
    _check("the fold's saving (%)", fold["totals"]["electrical"]["saving"]["value"], saving)
    for metric, label in (("electrical", "electrical"), ("joule", "joule"),
                          ("positive_work", "positive work")):
        answer, paper, base, s_answer, s_paper = said(
            rf"\| {label} \| {{n}} J \| {{n}} J \| {{n}} J \| {{n}} %, {{n}} % \|")
        mine, ref = report["energy"]["totals"][metric], report["reference"]["energy"][metric]
        _check(f"the answer's {metric} (J)", mine["with_springs"]["value"], answer)
        _check(f"the reference's {metric} (J)", ref["with_springs"]["value"], paper)
        _check(f"the baseline's {metric} (J)", mine["baseline"]["value"], base)
        _check(f"the answer's {metric} saving (%)", mine["saving"]["value"], s_answer)
        _check(f"the reference's {metric} saving (%)", ref["saving"]["value"], s_paper)
    (usage,) = said(r"With them the peak friction usage is {n} \(μ = 0\.6\)")
    _check("the peak friction usage", report["forces"]["peak_friction_usage"]["value"], usage)
    rise, held = said(r"the motors' net work rises from {n} J \(= m g Δz_com\) by the {n} J")
    _check("m g Δz_com (J)", fold["potential_energy_rise"]["value"], rise)
    _check("the energy the springs hold (J)", fold["net_work"]["with_springs"]["value"]
           - fold["net_work"]["baseline"]["value"], held)


def test_readme_command_table_says_how_long_each_command_takes():
    """Each command of the README's table has its time, the one ``hexaleg COMMAND --help``
    says (``hexaleg.commands.parser.GUIDE``), and every command is in the table (#43)."""
    from hexaleg.cli import build_parser
    from hexaleg.commands.parser import GUIDE

    rows = {m.group(1): m.group(2) for m in re.finditer(
        r"^\| `hexaleg (\w+)[^|]*\|[^|]*\| ([^|]+) \| \[", (ROOT / "README.md").read_text(), re.M)}
    assert set(rows) == set(GUIDE), rows
    for command, time in rows.items():
        assert GUIDE[command][0].startswith(time), (command, time, GUIDE[command][0])
        sub = next(a for a in build_parser()._actions if hasattr(a, "choices") and a.choices)
        text = sub.choices[command].format_help()
        assert f"takes {GUIDE[command][0]}." in text and "examples:" in text
