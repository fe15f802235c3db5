"""docs/optimal.md's table, recomputed: the default gait's rows by hexaleg's pipeline, the
optimal cycle's by Crocoddyl (slow; needs the optimal extra)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

import hexaleg
from hexaleg.design.search.optimal import optimal_springs

DOC = Path(__file__).resolve().parents[2] / "docs" / "optimal.md"


def _rows() -> dict[str, float]:
    text = DOC.read_text(encoding="utf-8")
    table = text[text.index("## The table"):text.index("## How it compares")]
    return {m[1]: float(m[2]) for m in re.finditer(r"^\| ([^|]+?) \| ([0-9.]+) \|", table,
                                                   re.MULTILINE)}


@pytest.fixture(scope="module")
def default_rows():
    run = hexaleg.Scenario.load("hexaleg")
    prepared = run.prepare()
    d = run.motion().distance
    bare = prepared.evaluate(hexaleg.SpringSet()).metrics["total"]["electrical"] / d
    springs = optimal_springs(prepared, list(run.model.joint_classes), family="linear",
                              metric="electrical")
    return run, springs, bare, springs.analysis.metrics["total"]["electrical"] / d


def test_the_default_gaits_rows(default_rows):
    _, _, bare, sprung = default_rows
    rows = _rows()
    assert rows["default gait (hexaleg's pipeline)"] == pytest.approx(bare, abs=0.005)
    assert rows["default gait with its linear springs"] == pytest.approx(sprung, abs=0.005)


@pytest.mark.slow
def test_the_optimal_rows(default_rows):
    pytest.importorskip("crocoddyl")
    from hexaleg.design.codesign.alternation import alternate, predicted_per_metre
    from hexaleg.optimal.problem import OptimalParams, build_problem
    from hexaleg.optimal.solve import solve

    run, springs, _, _ = default_rows
    rows = _rows()
    params = OptimalParams(nodes=40)
    bare = solve(run.model, build_problem(run.model, run.motion(), run.actuator,
                                          hexaleg.SpringSet(), params))
    predicted, _ = predicted_per_metre(run.model, bare.task_space, run.actuator,
                                       hexaleg.SpringSet(), run.contact)
    assert rows["optimal cycle, no springs"] == pytest.approx(predicted, abs=0.005)
    alt = alternate(run.model, run.motion(), run.actuator, run.contact, springs=springs.springs,
                    params=params, rounds=3)
    assert rows["optimal cycle with its springs (alternation)"] == pytest.approx(
        alt.predicted, abs=0.005)


LOGS = Path(__file__).resolve().parents[2] / "analysis" / "bench_logs"


def _logged(log: str) -> list[tuple[float, ...]]:
    """The four rows a kept log printed (``OptimalRows.lines``): predicted, then each
    controller's simulated J/m or NaN where it did not walk."""
    lines = (LOGS / log).read_text(encoding="utf-8").splitlines()
    head = next(k for k, line in enumerate(lines) if "optimal motion (whole-body" in line)
    return _parsed(lines[head + 1:head + 5])


def _parsed(lines: list[str]) -> list[tuple[float, ...]]:
    """Rows printed as ``label  predicted   sim, sim`` (each sim a number, maybe followed by
    the controller that ran it in brackets, or ``— (why)``; an optimal row's predicted figure
    maybe followed by its stated spread, ``±0.01``, and what of it is not predicted in
    brackets)."""
    rows = []
    for line in lines:
        line = re.sub(r" \((?:open loop|balance feedback)\)", "", line)
        m = re.match(r"^(?:\S+ )?\s+[a-z][^0-9]*?\s{2,}([0-9.]+)(?: ±[0-9.]+)?(?: \([^)]*\))?"
                     r"\s+(.*)$", line)
        if m:
            sims = [float(p) if re.fullmatch(r"[0-9.]+", p.strip()) else float("nan")
                    for p in re.split(r", (?=[0-9—])", m[2])]
            rows.append((float(m[1]), *sims))
    return rows


def _documented(first: str) -> list[tuple[float, ...]]:
    """The four rows of docs/optimal.md's table whose header's first cell is ``first`` (a
    predicted figure maybe followed by its stated spread, ``±1``)."""
    text = DOC.read_text(encoding="utf-8")
    table = text[text.index(f"| {first} |"):].split("\n\n")[0].splitlines()[2:]
    return [tuple(float(c) if re.fullmatch(r"[0-9.]+", c) else float("nan")
                  for c in (cell.split(" ±")[0].strip() for cell in row.strip("|").split("|")[1:]))
            for row in table]


@pytest.mark.parametrize(("first", "log"), [
    ("Solo-12 row, rebuilt and balanced", "bench_optimal_rows_solo12_balanced.log"),
    ("Solo-12 row, under Raibert's placement", "bench_optimal_rows_solo12_placement.log"),
    ("Solo-12 row", "bench_optimal_rows_solo12_hold.log"),
    ("Solo-12 row, 300 iterations", "bench_optimal_rows_solo12_hold_300.log"),
    ("row (whole command)", "codesign_motion_optimal.log"),
    ("row (its optimal stage, stance held)", "bench_optimal_rows_hold.log"),
    ("row (the search's best gait, stance held)", "bench_optimal_rows_best_hold.log"),
    ("row (rebuilt in task space, open loop)", "bench_optimal_rows_judged.log"),
    ("row (timing searched, open loop)", "bench_optimal_rows_timing.log")])
def test_the_documented_rows_are_the_kept_logs(first, log):
    """Solo-12's table, the whole command's and its optimal stage rerun with the stance held
    come from runs too long for a test: the docs must print what their kept logs printed."""
    logged, documented = _logged(log), _documented(first)
    assert len(logged) == len(documented) == 4
    for a, b in zip(logged, documented, strict=True):
        assert a == pytest.approx(b, abs=0.005, nan_ok=True)


@pytest.mark.parametrize(("first", "log"), [
    ("row (rebuilt in task space, balance feedback)", "bench_optimal_rows_judged.log"),
    ("row (timing searched, balance feedback)", "bench_optimal_rows_timing.log")])
def test_the_closed_loop_rows_are_the_kept_log(first, log):
    """The rows rebuilt in task space simulated again with balance feedback on for every row:
    the docs print what the kept log's second table printed."""
    lines = (LOGS / log).read_text(encoding="utf-8").splitlines()
    head = next(k for k, line in enumerate(lines) if line.startswith("the same four motions"))
    logged = _parsed(lines[head + 1:head + 5])
    documented = _documented(first)
    assert len(logged) == len(documented) == 4
    for a, b in zip(logged, documented, strict=True):
        assert a == pytest.approx(b, abs=0.005)


@pytest.mark.parametrize("log", ["bench_optimal_rows_hold.log",
                                 "bench_optimal_rows_best_hold.log",
                                 "bench_optimal_rows_solo12_hold.log"])
def test_the_documented_stance_hold_is_the_kept_logs(log):
    """The stance slip and drift docs/optimal.md states for the optimal stages rerun with the
    stance held are their kept logs' (``optimal motion, … : … stance slip S m/s, drift D m``)."""
    text = (LOGS / log).read_text(encoding="utf-8")
    doc = DOC.read_text(encoding="utf-8")
    for name in ("its springs", "no springs"):
        m = re.search(rf"^optimal motion, {name}: .*stance slip ([0-9.e-]+) m/s, drift "
                      r"([0-9.e-]+) m,", text, re.MULTILINE)
        assert m, name
        slip, drift = float(m[1]) * 1e3, float(m[2]) * 1e3
        assert f"{slip:.1f} mm/s" in doc and f"{drift:.3f} mm" in doc, (name, slip, drift)


def test_the_duty_table_is_the_kept_log():
    """docs/optimal.md's table of G and the optimal cycle at other duty factors with the stance
    held is analysis/bench_logs/bench_optimal_duty_hold.log's (and, for the cycle on 80 knots,
    bench_optimal_duty_hold_80.log's): each row's predicted and simulated J/m under both
    servos."""
    logged = {}
    for log, knots in (("bench_optimal_duty_hold.log", ""),
                       ("bench_optimal_duty_hold_80.log", ", 80 knots")):
        text = (LOGS / log).read_text(encoding="utf-8")
        for m in re.finditer(r"^G at duty factor ([0-9.]+) with S: ([0-9.]+) J/m predicted, "
                             r"simulated feedforward ([0-9.]+), position ([0-9.]+)$", text,
                             re.MULTILINE):
            logged[f"G at duty factor {m[1]}"] = tuple(float(v) for v in m.group(2, 3, 4))
        for m in re.finditer(r"^optimal cycle at duty factor ([0-9.]+) with S: ([0-9.]+) J/m "
                             r".*\n  simulated under feedforward: ([0-9.]+) J/m.*\n"
                             r"  simulated under position: ([0-9.]+) J/m", text, re.MULTILINE):
            logged[f"optimal cycle at duty factor {m[1]}{knots}"] = tuple(
                float(v) for v in m.group(2, 3, 4))
    doc = DOC.read_text(encoding="utf-8")
    table = doc[doc.index("| cycle (from G, with S) |"):].split("\n\n")[0].splitlines()[2:]
    assert len(table) >= 8
    for row in table:
        cells = [c.strip() for c in row.strip("|").split("|")]
        assert cells[0] in logged, cells[0]
        assert tuple(float(c) for c in cells[1:]) == pytest.approx(logged[cells[0]], abs=0.005)


def _paragraph(start: str) -> str:
    """The docs/optimal.md paragraph that begins with ``start``."""
    doc = DOC.read_text(encoding="utf-8")
    return doc[doc.index(start):].split("\n\n")[0]


SIMULATED = (r"feedforward ([0-9.]+) \(open loop\), position ([0-9.]+) \(open loop\), "
             r"feedforward ([0-9.]+) \(balance feedback\), position ([0-9.]+) \(balance feedback\)")
"""A bench_optimal_duty.py line's four simulations (open loop, then balance feedback)."""


def test_the_rebuilt_duty_cycles_are_the_kept_logs():
    """The paragraph on duty factor 0.9 rebuilt prints its kept logs' numbers: G at 0.9 with S,
    the 40-knot cycle's missing forces, the 80-knot cycle's solver figure, prediction and four
    simulations."""
    text = _paragraph("**Duty factor 0.9, rebuilt**")
    log40 = (LOGS / "bench_optimal_duty_task_space.log").read_text(encoding="utf-8")
    log80 = (LOGS / "bench_optimal_duty_task_space_80.log").read_text(encoding="utf-8")
    g = re.search(r"^G at duty factor 0.9 with S: ([0-9.]+) J/m predicted, simulated "
                  + SIMULATED, log40, re.MULTILINE)
    assert g
    for value in g.groups():
        assert f"{float(value):.2f}" in text, value
    assert "μ = 0.77" in text and "the least friction that admits forces here is μ = 0.77" in log40
    solver = re.search(r"^optimal cycle at duty factor 0.9 with S: ([0-9.]+) J/m", log80,
                       re.MULTILINE)
    rebuilt = re.search(r"rebuilt in task space: ([0-9.]+) J/m predicted .*simulated "
                        + SIMULATED, log80)
    assert solver and rebuilt
    for value in (solver[1], *rebuilt.groups()):
        assert f"{float(value):.2f}" in text, value


def test_the_rebuilt_trot_is_the_kept_logs():
    """Solo-12's trot rebuilt: the base wrench the two stance feet missed with the base splined
    (bench_optimal_rows_solo12_task_space.log), then with it rolled about their support line
    and the swing feet above the ground (bench_optimal_rows_solo12_balanced.log): the solver's
    figures, the roll, the base's distance from its knots and the swing feet's depth."""
    text = _paragraph("**Solo-12's trot, rebuilt**")
    log = (LOGS / "bench_optimal_rows_solo12_task_space.log").read_text(encoding="utf-8")
    for miss in re.findall(r"miss the base rows by ([0-9.]+)", log):
        assert f"{float(miss):.2f}" in text, miss
    doc = DOC.read_text(encoding="utf-8")
    text = doc[doc.index("**Its base rolled about the support line**"):
               doc.index("**Duty factor 0.9, rebuilt**")]
    log = (LOGS / "bench_optimal_rows_solo12_balanced.log").read_text(encoding="utf-8")
    solver = re.search(r"the solver's own J/m at its knots: ([0-9.]+) \(no springs\), ([0-9.]+)",
                       log)
    assert solver
    numbers = list(solver.groups())
    for name in ("no springs", "its springs"):
        m = re.search(rf"^optimal motion, {name}, rebuilt: largest roll about a support line "
                      r"([0-9.]+) mrad, base within ([0-9.]+) mm and ([0-9.]+) mrad of its knots; "
                      r"swing feet at most ([0-9.]+) mm below the floor at the knots, ([0-9.]+) "
                      r"mm between them$", log, re.MULTILINE)
        assert m, name
        numbers += list(m.groups())
    for number in numbers:
        assert number in text, number


def test_the_diagnosis_is_the_kept_log():
    """docs/optimal.md's diagnosis of the optimal cycle played as its knots prints what
    analysis/bench_logs/bench_optimal_played.log printed."""
    doc = DOC.read_text(encoding="utf-8")
    text = doc[doc.index("## Played as planned"):doc.index("**Solo-12's trot, rebuilt**")]
    log = (LOGS / "bench_optimal_played.log").read_text(encoding="utf-8")
    numbers = []
    for pattern in (r"solver's own: ([0-9.]+) J/m", r"force program on the knots: ([0-9.]+)",
                    r"^knots simulated: feedforward ([0-9.]+) \(open loop\), position [0-9.]+ "
                    r"\(open loop\), feedforward ([0-9.]+)",
                    r"central-difference velocities: [0-9.]+ J/m predicted, simulated "
                    r"feedforward ([0-9.]+) \(open loop\), position [0-9.]+ \(open loop\), "
                    r"feedforward ([0-9.]+)",
                    r"stance feet up to ([0-9.]+) mm", r"velocities up to ([0-9.]+) rad/s",
                    r"\(largest ([0-9.]+)\)", r"power at v_\(k\+1\): ([0-9.]+)",
                    r"rebuilt in task space: ([0-9.]+) J/m predicted, simulated feedforward "
                    r"([0-9.]+) \(open loop\), position [0-9.]+ \(open loop\), feedforward "
                    r"([0-9.]+)"):
        m = re.search(pattern, log, re.MULTILINE)
        assert m, pattern
        numbers += [f"{float(v):.2f}" for v in m.groups()]
    m = re.search(r"springs' work ([0-9.]+) J \(trapezoid (\S+) J\), gravity's ([0-9.]+) J", log)
    assert m
    numbers += list(m.groups())
    for number in numbers:
        assert number in text, number


def test_the_timing_search_is_the_kept_logs():
    """The contact timing's section prints its kept logs: each timing's predicted and solver
    J/m, the parametric co-design at the widened duty-factor bound and the optimal stage run
    from it (the gait kept)."""
    doc = DOC.read_text(encoding="utf-8")
    text = doc[doc.index("## The contact timing as a decision"):doc.index("## How it compares")]
    log = (LOGS / "bench_optimal_rows_timing.log").read_text(encoding="utf-8")
    tried = re.findall(r"^timing: duty factor ([0-9.]+), period ([0-9.]+) s: (?:([0-9.]+) J/m "
                       r"predicted rebuilt|no prediction .*) \(the solver's ([0-9.]+)\)$", log,
                       re.MULTILINE)
    table = text[text.index("| timing (from G, with S) |"):].split("\n\n")[0].splitlines()[2:]
    assert len(tried) == len(table) == 5
    for (duty, period, predicted, solver), row in zip(tried, table, strict=True):
        cells = [c.strip() for c in row.strip("|").split("|")]
        assert cells[0].startswith(f"duty factor {duty}, period {period} s"), cells[0]
        if predicted:  # the log's four significant digits
            assert float(cells[1]) == pytest.approx(float(predicted), abs=0.0051)
        else:
            assert cells[1] == "—"
        assert float(cells[2]) == pytest.approx(float(solver), abs=0.0051)
    bound = (LOGS / "bench_codesign_duty_bound.log").read_text(encoding="utf-8")
    m = re.search(r"^co-design at duty-factor bound 0.9: ([0-9.]+) J/m predicted, simulated "
                  r"with balance feedback: feedforward ([0-9.]+), position ([0-9.]+)$", bound,
                  re.MULTILINE)
    assert m and all(v in text for v in m.groups())
    widened = (LOGS / "bench_optimal_rows_widened.log").read_text(encoding="utf-8")
    assert "the gait and its springs kept" in widened and "alternation keeps the gait" in text
    for pattern in (r"start: ([0-9.]+) J/m", r"re-optimised ([0-9.]+) J/m",
                    r"the gait's ([0-9.]+)|against ([0-9.]+) J/m\): the gait"):
        m = re.search(pattern, widened)
        assert m, pattern
        assert next(v for v in m.groups() if v) in text, pattern


def test_the_breakdown_is_the_kept_log():
    """The table of what bounds the best cycle prints the kept log: each motion's electrical
    J/m, its Joule heat, the rest, the motors' positive work and each joint class's electrical
    J/m; and the spring designed one a joint."""
    log = (LOGS / "bench_optimal_breakdown.log").read_text(encoding="utf-8")
    motions = re.findall(r"^[^ #].*?: ([0-9.]+) J/m electrical, of which Joule ([0-9.]+) "
                         r"\([0-9]+%\), mechanical through η ([0-9.]+); motors' positive work "
                         r"([0-9.]+) J/m\n  coxa +electrical +([0-9.]+).*\n  femur +electrical +"
                         r"([0-9.]+).*\n  tibia +electrical +([0-9.]+)", log, re.MULTILINE)
    doc = DOC.read_text(encoding="utf-8")
    table = doc[doc.index("| motion | electrical J/m |"):].split("\n\n")[0].splitlines()[2:]
    assert len(motions) == len(table) == 3
    for (e, joule, rest, work, coxa, femur, tibia), row in zip(motions, table, strict=True):
        cells = [c.strip() for c in row.strip("|").split("|")][1:]
        assert cells == [e, joule, rest, work, femur, tibia, coxa], row
    joint = re.search(r"linear springs one design a joint: ([0-9.]+) J/m", log)
    assert joint and f"reaches {joint[1]} J/m" in doc
    dead = (LOGS / "bench_optimal_breakdown_dead_zone.log").read_text(encoding="utf-8")
    zone = re.search(r"dead_zone springs one design a class: ([0-9.]+) J/m", dead)
    assert zone and f"class {zone[1]} (above" in doc


def test_the_starts_are_the_kept_log():
    """The multi-start's section prints its kept log: each start's predicted and solver J/m,
    the answer's alternation, its simulated J/m, the baseline's and the ratios; and each
    motion's split into Joule heat and the rest."""
    doc = DOC.read_text(encoding="utf-8")
    text = doc[doc.index("## Starts of the optimal motion"):doc.index("## How it compares")]
    log = (LOGS / "bench_optimal_starts.log").read_text(encoding="utf-8")
    tried = re.findall(r"^\S+ +(\S.*?): ([0-9.]+) J/m predicted rebuilt \(the solver's "
                       r"([0-9.]+)\)$", log, re.MULTILINE)
    table = text[text.index("| start (G at duty factor 0.85, with S) |"):].split(
        "\n\n")[0].splitlines()[2:]
    assert len(tried) == len(table) >= 4
    for (label, predicted, solver), row in zip(tried, table, strict=True):
        cells = [c.strip() for c in row.strip("|").split("|")]
        assert cells[0].startswith(label), (cells[0], label)
        assert cells[1].strip("*") == predicted and cells[2] == solver, row
    for pattern in (r"^\S+ the answer .*: alternation ([0-9.]+) → ([0-9.]+) → ([0-9.]+) → "
                    r"([0-9.]+) J/m predicted .* feedforward ([0-9.]+), position ([0-9.]+)$",
                    r"residual (\S+) N·m, stationarity (\S+) after",
                    r"^\S+ baseline: .*: ([0-9.]+) J/m "
                    r"predicted, simulated with balance feedback feedforward ([0-9.]+), "
                    r"position ([0-9.]+)$", r"predicted ([0-9.]+)× \(target ≤ 0.8\), simulated "
                    r"under the worse servo ([0-9.]+)×"):
        m = re.search(pattern, log, re.MULTILINE)
        assert m, pattern
        assert all(v in text for v in m.groups()), (pattern, m.groups())
    motions = re.findall(r"^\S+ (.*?): ([0-9.]+) J/m electrical, Joule ([0-9.]+), the rest "
                         r"([0-9.]+); motors' positive work ([0-9.]+) J/m\n\S+ +coxa +electrical "
                         r"+([0-9.]+).*\n\S+ +femur +electrical +([0-9.]+).*\n\S+ +tibia +"
                         r"electrical +([0-9.]+)", log, re.MULTILINE)
    split = text[text.index("| motion (duty bound 0.9) |"):].split("\n\n")[0].splitlines()[2:]
    assert len(motions) == len(split) == 4
    for (_, e, joule, rest, work, coxa, femur, tibia), row in zip(motions, split, strict=True):
        cells = [c.strip() for c in row.strip("|").split("|")][1:]
        assert cells == [e, joule, rest, work, femur, tibia, coxa], row


def test_the_end_to_end_run_is_the_kept_log():
    """The end-to-end run's table, its alternation and its times are the kept log's."""
    doc = DOC.read_text(encoding="utf-8")
    text = doc[doc.index("**End to end.**"):doc.index("## Starts of the optimal motion")]
    log = (LOGS / "codesign_motion_optimal_timing.log").read_text(encoding="utf-8")
    rows = re.findall(r"^\S+     ((?:default gait|parametric|optimal motion)[^0-9]*?) +([0-9.]+) +"
                      r"([0-9.]+) \(balance feedback\), ([0-9.]+) \(balance feedback\)$", log,
                      re.MULTILINE)
    table = text[text.index("| row (the command's own table"):].split("\n\n")[0].splitlines()[2:]
    assert len(rows) == len(table) == 4
    for (label, *numbers), row in zip(rows, table, strict=True):
        assert [c.strip() for c in row.strip("|").split("|")] == [label.strip(), *numbers], row
    trail = re.search(r"alternation ([0-9.]+) → ([0-9.]+) → ([0-9.]+) → ([0-9.]+) J/m", log)
    assert trail and " → ".join(trail.groups()) in text.replace("\n", " ").replace(
        "(that gait with S) ", "")
    user = float(re.search(r"User time \(seconds\): ([0-9.]+)", log)[1])
    system = float(re.search(r"System time \(seconds\): ([0-9.]+)", log)[1])
    wall = re.search(r"Elapsed .*: ([0-9]+):([0-9.]+)$", log, re.MULTILINE)
    assert f"{60 * int(wall[1]) + float(wall[2]):.0f} s wall" in text
    assert f"{user + system:.0f} s of CPU" in text and f"user {user:.0f} s" in text


def test_the_body_bound_is_the_kept_log():
    """The parametric co-design with its body-height box widened: the starts' section prints
    the kept log's chosen gait and its predicted and simulated J/m."""
    doc = DOC.read_text(encoding="utf-8")
    text = doc[doc.index("## Starts of the optimal motion"):doc.index("## How it compares")]
    log = (LOGS / "bench_codesign_body_bound.log").read_text(encoding="utf-8")
    rows = re.search(r"rows [0-9.]+ / [0-9.]+ / [0-9.]+ / ([0-9.]+) J/m", log)
    chosen = re.search(r"duty factor ([0-9.]+), period ([0-9.]+) s, step height [0-9.]+ m, body "
                       r"height ([0-9.]+) m \(box top \3 m\)", log)
    sims = re.search(r"body height ≤ 1.5 × the default: [0-9.]+ J/m predicted, simulated with "
                     r"balance feedback: feedforward ([0-9.]+), position ([0-9.]+)$", log,
                     re.MULTILINE)
    assert rows and chosen and sims
    flat = text.replace("\n", " ")
    assert f"predicts {rows[1]} J/m" in flat
    assert f"duty factor {chosen[1]}, period {chosen[2]} s, body height {chosen[3]} m" in flat
    assert f"for {sims[1]} (feedforward) and {sims[2]} (position)" in flat


def test_the_second_round_is_the_kept_log():
    """The target's second round prints its kept log: every probe's gait, optimal cycle, solver
    figure, ratios to the three co-designs, simulated J/m and friction use, and both
    alternations, row for row in the log's order."""
    doc = DOC.read_text(encoding="utf-8")
    text = doc[doc.index("## The 0.8× target, second round"):doc.index("## How it compares")]
    log = (LOGS / "bench_optimal_target2.log").read_text(encoding="utf-8")
    log = log[:log.index("\nwall ")]
    three = (r"([0-9.]+)× the default co-design, ([0-9.]+)× the widened co-design, "
             r"([0-9.]+)× the widest co-design")
    worse = (r"(?:\n    simulated with balance feedback: feedforward ([0-9.]+), position "
             r"([0-9.]+); under the worse servo ([0-9.]+)× the default co-design, ([0-9.]+)× "
             r"the widened co-design, ([0-9.]+)× the widest co-design)?")
    probes = re.findall(r"^  (.+?): its start gait ([0-9.]+) J/m predicted; the optimal cycle "
                        r"predicted rebuilt ([0-9.]+) J/m \(" + three + r"\); the solver's "
                        r"([0-9.]+) J/m; friction use ([0-9.]+) of μ.*$" + worse, log,
                        re.MULTILINE)
    alternations = re.findall(r"^the alternation from (.+?): ([0-9.]+) → [0-9.]+ → [0-9.]+ → "
                              r"([0-9.]+) J/m predicted \(the gait kept: False\); "
                              + three + r"; its solve: friction use "
                              r"([0-9.]+) of μ.*$" + worse, log, re.MULTILINE)
    want = []
    for label, gait, opt, d, w, v, solver, mu, ff, pos, wd, ww, wv in probes:
        sims = [f"{ff} / {pos}", f"{wd} / {ww} / {wv}"] if ff else ["", ""]
        want.append([label, gait, opt, solver, d, w, v, *sims, mu])
    for label, gait, opt, d, w, v, mu, ff, pos, wd, ww, wv in alternations:
        want.append([f"the alternation from {label}", gait, opt, "—", d, w, v, f"{ff} / {pos}",
                     f"{wd} / {ww} / {wv}", mu])
    table = text[text.index("| start (with its co-design's springs) |"):].split(
        "\n\n")[0].splitlines()[2:]
    assert len(probes) >= 20 and len(alternations) == 2 and len(table) == len(want)
    for row, cells in zip(table, want, strict=True):
        assert [c.strip() for c in row.strip("|").split("|")] == cells, row
    flat = " ".join(text.split())
    for quoted in ("0.722× predicted and 0.753× under the worse servo",
                   "0.932× predicted and 0.951× under the worse servo",
                   "the best is 0.887× and 0.866×"):
        assert quoted in flat, quoted
    v_alt = next(a for a in alternations if a[0] == "V")
    assert (v_alt[3], v_alt[9]) == ("0.722", "0.753") and (v_alt[5], v_alt[11]) == (
        "0.932", "0.951")


def test_the_converged_probes_are_the_kept_log():
    """The convergence paragraph quotes bench_optimal_converged.log: iterations and knots from
    G's taller start, the alternation from G at V's height, its simulation and its ratios."""
    doc = " ".join(DOC.read_text(encoding="utf-8").split())
    text = doc[doc.index("**Converged, finer, taller**"):doc.index("The starts lattice is")]
    log = (LOGS / "bench_optimal_converged.log").read_text(encoding="utf-8")

    def row(label: str) -> list[str]:
        line = next(x for x in log.splitlines() if f" {label}  " in x)
        return line.split(label)[1].split()

    first, many = row("body × 1.05, 40 knots, 100 iterations"), row(
        "body × 1.05, 40 knots, 1000 iterations")
    assert f"stationarity {many[5]} and move the judged figure from {first[0]} to {many[0]}" \
        in text
    assert f"(the solver's own from {first[4]} to {many[4]})" in text
    assert f"80 knots give {row('body × 1.05, 80 knots, 100 iterations')[0]} and 120 knots " \
        f"{row('body × 1.05, 120 knots, 100 iterations')[0]}" in text
    trail = re.search(r"alternation: 7\.898 → [0-9.]+ →.* → ([0-9.]+) J/m predicted rebuilt",
                      log)
    sims = re.search(r"simulated with balance feedback: feedforward ([0-9.]+), position "
                     r"([0-9.]+)", log)
    default = re.search(r"against the default co-design .*: predicted ([0-9.]+)×, worse servo "
                        r"([0-9.]+)×", log)
    widest = re.search(r"against the widest co-design .*: predicted ([0-9.]+)×, worse servo "
                       r"([0-9.]+)×", log)
    assert trail and sims and default and widest
    assert f"reaches {trail[1]} J/m predicted and walks for {sims[1]}" in text
    assert f"and {sims[2]} (position)" in text
    assert f"{default[1]}× the default co-design predicted and {default[2]}×" in text
    assert f"but {widest[1]}× and {widest[2]}× the co-design searched as tall" in text


def test_solo12s_command_tables_are_the_kept_log():
    """Solo-12's whole command on today's code (the kept log's last two blocks: the timing fixed,
    then searched): the docs print each table's four rows, a trot that falls short a dash."""
    lines = (LOGS / "codesign_motion_optimal_solo12.log").read_text(encoding="utf-8").splitlines()
    heads = [k for k, line in enumerate(lines) if "optimal motion (whole-body" in line]
    for head, first in zip(heads[-2:], ("Solo-12 row (the command's own table, timing fixed)",
                                        "Solo-12 row (the command's own table, timing searched)"),
                           strict=True):
        logged, documented = _parsed(lines[head + 1:head + 5]), _documented(first)
        assert len(logged) == len(documented) == 4
        for a, b in zip(logged, documented, strict=True):
            assert a == pytest.approx(b, abs=0.005, nan_ok=True), (first, a, b)
    doc = " ".join(DOC.read_text(encoding="utf-8").split())
    block = "\n".join(lines[heads[-1]:heads[-1] + 12])
    trail = re.search(r", alternation ((?:[0-9.]+ → )+[0-9.]+) J/m", block)
    assert trail and f"the alternation went {trail[1]} J/m" in doc


def test_the_speed_section_is_the_kept_logs():
    """The Speed section's figures are its logs': each solve's CPU and wall before and now and the
    timing lattice's wall in turn and side by side (both runs of bench_optimal_speed.log), and
    each whole command's wall and CPU (user + system) by /usr/bin/time."""
    doc = " ".join(DOC.read_text(encoding="utf-8").split())
    text = doc[doc.index("## Speed"):doc.index("## What is left")]
    log = (LOGS / "bench_optimal_speed.log").read_text(encoding="utf-8")
    solves = re.findall(r"one solve, (?:before|now): +100 iterations, [0-9.]+ J/m, wall ([0-9.]+) "
                        r"s, CPU ([0-9.]+) s", log)
    lattices = re.findall(r"timing lattice on [12] workers?: .* wall ([0-9.]+) s", log)
    assert len(solves) == len(lattices) == 4
    (wall_before, cpu_before), (wall_now, cpu_now), (_, cpu_before2), (_, cpu_now2) = solves
    assert f"took {cpu_before} s of CPU ({float(wall_before):.0f} s wall" in text
    assert f"it now takes {cpu_now} s ({wall_now} s wall)" in text
    assert f"{cpu_before2} s against {cpu_now2} s" in text
    turn, side, turn2, side2 = lattices
    assert f"{side2} s wall on two workers against {turn2} s in turn" in text
    assert f"{side} against {turn} s at load 5 to 6.5" in text
    for name, words in (("codesign_motion_optimal_speed.log", "**4 min 14 s wall and 182 s of"),
                        ("codesign_motion_optimal_timing_speed.log", "**3 min 33 s and 194 s")):
        run = (LOGS / name).read_text(encoding="utf-8")
        user = float(re.search(r"User time \(seconds\): ([0-9.]+)", run)[1])
        system = float(re.search(r"System time \(seconds\): ([0-9.]+)", run)[1])
        wall = re.search(r"Elapsed .*: ([0-9]+):([0-9.]+)$", run, re.MULTILINE)
        minutes, seconds = int(wall[1]), round(float(wall[2]))
        assert words.startswith(f"**{minutes} min {seconds} s")
        assert f"{user + system:.0f} s" in words and words in text, name


def test_the_footholds_are_the_kept_log():
    """The footholds' section prints bench_optimal_footholds.log: each alternation's figure and
    ratios, its simulation and worse-servo ratios, row for row, and the figures its text quotes
    (the relaxed hold's slide, the solver's trap, the 1e-9 move)."""
    doc = DOC.read_text(encoding="utf-8")
    text = doc[doc.index("## The footholds as decisions"):doc.index("## How it compares")]
    log = (LOGS / "bench_optimal_footholds.log").read_text(encoding="utf-8")
    alternations = dict(
        (label, (last, v, d)) for label, last, v, d in re.findall(
            r"^\S+ alternation from (.+?): [0-9.]+ →.*?([0-9.]+) J/m predicted rebuilt "
            r"\(.*?× V ([0-9.]+) × D ([0-9.]+);", log, re.MULTILINE))
    simulated = dict(
        (label, rest) for label, *rest in re.findall(
            r"^\S+ alternation from (.+?) simulated with balance feedback: feedforward "
            r"([0-9.]+), position ([0-9.]+); worse servo × V ([0-9.]+) × D ([0-9.]+)$", log,
            re.MULTILINE))
    table = text[text.index("| footholds |"):].split("\n\n")[0].splitlines()[2:]
    assert len(table) == len(alternations) == len(simulated) == 4
    for row in table:
        label, *cells = (c.strip() for c in row.strip("|").split("|"))
        ff, pos, wv, wd = simulated[label]
        assert cells == [*alternations[label], f"{ff} / {pos}", wv, wd], row
    flat = " ".join(text.split())
    trap = re.search(r"searched by the solver's figure:$", log, re.MULTILINE)
    solved = re.findall(r"the answer re-solved: judged ([0-9.]+) .*?solver ([0-9.]+),", log)
    moved = re.findall(r"the answer's footholds moved by 1e-9 m .*?: judged ([0-9.]+)", log)
    slide = re.search(r"relaxed foothold .*slip ([0-9.]+) mm/s", log)
    assert trap is None and len(solved) == len(moved) == 3 and slide
    assert f"{float(solved[1][1]):.2f} J/m by the solver's knots, {solved[1][0][:4]} rebuilt" \
        in flat
    assert f"({solved[2][0]} → {moved[2]} J/m predicted)" in flat
    assert f"slide ({float(slide[1]):.0f} mm/s)" in flat


def test_the_stated_spread_is_the_kept_logs():
    """How it is checked quotes the probe of where two solves part, the spreads the command's
    codesign.json holds and the rows it printed, and the one figure same-answer still moves."""
    doc = " ".join(DOC.read_text(encoding="utf-8").split())
    text = doc[doc.index("**The same answer, and the gap stated**"):doc.index("## The table")]
    probe = (LOGS / "bench_optimal_same_answer.log").read_text(encoding="utf-8")
    part = re.search(r"starts differ by ([0-9.e-]+) in the states.*?they part at iteration "
                     r"([0-9]+) \(.*?\) and reach ([0-9.]+) at iteration ([0-9]+): × ([0-9.]+) "
                     r"an iteration\nG: .*?stationarity ([0-9.]+)\nG moved: .*?stationarity "
                     r"([0-9.]+)\n", probe, re.DOTALL)
    assert part, "the probe's first block"
    assert (f"{part[1]} apart (the co-design's gait with its body 1e-9 m higher) part at "
            f"iteration {part[2]} and are {part[3]} apart by iteration {part[4]}, × {part[5]} "
            f"an iteration; they end at stationarity {part[6]} and {part[7]}") in text
    longer = probe[probe.index("--iterations 300"):]
    assert f"end {re.search(r'judged .*? J/m, spread ([0-9.]+) J/m', longer)[1]} J/m apart" \
        in text
    command = (LOGS / "codesign_motion_optimal_spread.log").read_text(encoding="utf-8")
    spreads = re.findall(r"^optimal motion, .*?: predicted [0-9.]+ J/m, spread ([0-9.]+) J/m",
                         command, re.MULTILINE)
    rows = re.findall(r"^    optimal motion, (?:no springs|its springs) +([0-9.]+ ±[0-9.]+) ",
                      command, re.MULTILINE)
    assert len(spreads) == len(rows) == 2
    assert f"the spreads are {spreads[0]} and {spreads[1]} J/m and the rows print {rows[0]} and " \
        f"{rows[1]}" in text
    moved = (LOGS / "same_answer_codesign_motion_optimal.log").read_text(encoding="utf-8")
    assert "17.5 and 17.6 J/m under position servos" in text
    head = (LOGS / "codesign_motion_optimal_spread.log").read_text(encoding="utf-8")
    cost = re.search(r"/usr/bin/time -v: ([0-9.]+) s user \+ [0-9.]+ s system, (\d+ min \d+ s) "
                     r"wall at load ([0-9.]+ to [0-9.]+) \(.*?at 3ec0662, .*?: ([0-9.]+) \+", head)
    assert cost and (f"took {cost[1]} s of user CPU and {cost[2]} wall at load {cost[3]}, "
                     f"against {cost[4]} s at 3ec0662") in doc
    quiet = re.search(r"Run again on a quiet machine .*?: ([0-9.]+) s user \+ ([0-9.]+) s system, "
                      r"(\d+ min \d+ s) wall", head)
    assert quiet and (f"running: {quiet[3]} wall and {quiet[1]} s of user CPU, the same output"
                      in doc)
    assert (f"took {quiet[3]} wall and {float(quiet[1]) + float(quiet[2]):.0f} s of CPU"
            in doc)
    for walked in ("17\\.5", "17\\.6"):
        assert re.search(r"optimal motion, its springs +10\.4 ±0\.1 +10\.3 \(open loop\), "
                         + walked + " ", moved), walked


def _bought(log: str) -> str:
    """A kept command log's springs to buy for the optimal motion as the docs print them: the
    family (and torque bound), J/m, the saving and the net saving, and their simulations."""
    buy = re.search(r"^    springs to buy \(full spring rules on the optimal motion: .*?\): "
                    r"(\w+)(, spring torque ≤ [0-9.]+ N·m)? on coxa, femur, tibia, ([0-9.]+) "
                    r"J/m, electrical saving \+([0-9.]+) % \(\+([0-9.]+) % net of ([0-9.]+) g of "
                    r"springs\)$", log, re.MULTILINE)
    sims = re.search(r"^      simulated electrical saving, the worse servo first: position only "
                     r"\+([0-9.]+) %, feedforward \+ PD \+([0-9.]+) %", log, re.MULTILINE)
    assert buy and sims
    return (f"{buy[1]}{buy[2] or ''}, on coxa, femur and tibia, {buy[3]} J/m, +{buy[4]} % "
            f"(+{buy[5]} % net of {buy[6]} g), simulated +{sims[1]} % under position servos and "
            f"+{sims[2]} % under feedforward")


def _optimal_table(log: str) -> dict[str, list[str]]:
    """A kept command log's optimal table: each row's label → its printed figures (predicted,
    then simulated under each servo; "—" where it has none), as printed."""
    block = log[log.index("  optimal motion (whole-body optimal control"):]
    rows = {}
    for label, figure, sims in re.findall(
            r"^    ((?:default gait|parametric co-design|optimal motion)[^0-9—]*?)\s{2,}"
            r"(\S+)(?: ±\S+)?(?: \(friction [^)]*\))?\s+(.*)$", block, re.MULTILINE):
        parts, depth, start = [], 0, 0
        for i, ch in enumerate(sims):  # the servos' cells: ", " outside parentheses
            depth += {"(": 1, ")": -1}.get(ch, 0)
            if depth == 0 and sims.startswith(", ", i):
                parts.append(sims[start:i])
                start = i + 2
        parts.append(sims[start:])
        rows[label.strip()] = [figure, *(part.split()[0] for part in parts)]
    return rows


def test_the_contact_sequence_is_the_kept_logs():
    """The contact sequence's table prints the three patterns' kept command logs row for row
    (the optimal motion with springs 'the gait kept' where the log says the alternation kept
    it), and the gap its text quotes is the wave log's alternation."""
    doc = DOC.read_text(encoding="utf-8")
    text = doc[doc.index("## The contact sequence"):doc.index("## How it compares")]
    table = text[text.index("| pattern |"):].split("\n\n")[0].splitlines()[2:]
    logs = {"tripod": "codesign_motion_optimal_spread.log",
            "ripple": "codesign_motion_optimal_ripple.log",
            "wave": "codesign_motion_optimal_wave.log"}
    assert [row.strip("|").split("|")[0].strip() for row in table] == list(logs)
    for row in table:
        pattern, *cells = (c.strip() for c in row.strip("|").split("|"))
        log = (LOGS / logs[pattern]).read_text(encoding="utf-8")
        rows = _optimal_table(log)
        kept = "the last row is that gait with its springs" in log
        assert cells[0] == rows["default gait, no springs"][0], row
        for cell, label in ((cells[1], "parametric co-design (its gait and springs)"),
                            (cells[2], "optimal motion, no springs"),
                            (cells[3], "optimal motion, its springs")):
            if label.endswith("its springs") and kept:
                assert cell == "the gait kept", row
                continue
            p, ff, pos = rows[label]
            assert cell == f"{p} · {ff} / {pos}", row
        solver = re.search(r"the solver's own J/m at its knots: \S+ \(no springs\), ([0-9.]+)",
                           log)
        assert cells[4] == solver[1], row
    wave = (LOGS / logs["wave"]).read_text(encoding="utf-8")
    start = re.search(r"alternation: start: ([0-9.]+) J/m predicted rebuilt \(the gait: "
                      r"([0-9.]+); the solver's ([0-9.]+)", wave)
    round_1 = re.search(r"round 1: springs [0-9.]+ J/m on the rebuilt cycle, re-optimised "
                        r"([0-9.]+) J/m predicted rebuilt \(the solver's ([0-9.]+)", wave)
    flat = " ".join(text.split())
    assert (f"predicts {start[1]} J/m rebuilt where the solver books {start[3]} at its knots, "
            f"and its round {round_1[1]} (the solver's {round_1[2]})") in flat
    assert f"over the gait it started from ({start[2]})" in flat
    ripple = (LOGS / logs["ripple"]).read_text(encoding="utf-8")
    least = re.search(r"the least friction that admits forces here is μ = ([0-9.]+)", ripple)
    assert f"needs μ = {least[1]} at one five-foot instant" in flat


def test_the_landing_is_the_kept_log():
    """Under position servos: the weights' table prints bench_optimal_servo.log's section A row
    for row (predicted, then simulated under feedforward and position servos), and the figures
    its diagnosis quotes are the log's."""
    doc = DOC.read_text(encoding="utf-8")
    text = doc[doc.index("## Under position servos: the landing"):doc.index("## How it compares")]
    log = (LOGS / "bench_optimal_servo.log").read_text(encoding="utf-8")
    part = log[log.index("# ---- A"):log.index("# ---- B")]
    runs = {}
    for weight, body in re.findall(r"^optimal motion, its springs(?:, servo_landing_weight "
                                   r"(\S+), servo_landing_knots 1)?:\n(.*?)(?=^\S|\Z)", part,
                                   re.MULTILINE | re.DOTALL):
        figures = [re.search(rf"{k} ([0-9.]+) J/m", body)[1]
                   for k in ("predicted", "feedforward: simulated", "position: simulated")]
        held = re.search(r"position: simulated.*?held through a stance .*? ([0-9.]+) mrad RMS",
                         body, re.DOTALL)[1]
        runs[weight or "off"] = (figures, held)
    table = text[text.index("| landing effort's weight |"):].split("\n\n")[0].splitlines()[2:]
    assert [row.strip("|").split("|")[0].strip() for row in table] == list(runs)
    for row in table:
        weight, *cells = (c.strip() for c in row.strip("|").split("|"))
        assert cells == runs[weight][0], row
    flat = " ".join(text.split())
    assert f"where its foot landed ({runs['off'][1]} mrad RMS against 5.4)" in flat
    start = part.index("parametric co-design (G with S):")
    co = part[start:part.index("optimal motion, its springs:\n", start)]
    assert re.search(r"position: simulated.*?held through a stance .*? 5.4 mrad RMS", co,
                     re.DOTALL)
    effort = re.findall(r"4 before ([0-9.]+)", part)
    assert f"{effort[1]} N·m RMS four samples (26 ms) before touch-down against the " \
           f"co-design's {effort[0]}" in flat


def test_the_landing_on_solo12_is_the_kept_logs():
    """The landing section's Solo-12 figures are the two kept command logs' optimal rows (with
    the weight, and the block of commit 33bcd0e without it)."""
    doc = DOC.read_text(encoding="utf-8")
    text = doc[doc.index("## Under position servos: the landing"):doc.index("## How it compares")]
    flat = " ".join(text.split())
    log = (LOGS / "codesign_motion_optimal_solo12_landing.log").read_text(encoding="utf-8")
    cut = log.index("# ===== without the weight")
    landing = _optimal_table(log[:cut])
    before = _optimal_table(re.sub(r"^\d\d:\d\d:\d\d ", "", log[cut:], flags=re.MULTILINE))
    sprung, bare = landing["optimal motion, its springs"], landing["optimal motion, no springs"]
    was_sprung, was_bare = (before["optimal motion, its springs"],
                            before["optimal motion, no springs"])
    assert f"predicts {sprung[0]} ±1 J/m ({was_sprung[0]} ±1 without it)" in flat
    assert f"under position servos for {sprung[-1]} ({was_sprung[-1]})" in flat
    assert f"walks for {bare[1]} and {bare[2]} J/m where it walked for {was_bare[1]} and " \
           f"{was_bare[2]}" in flat


def test_the_integrator_probe_is_the_kept_log():
    """The knots' integrator table prints bench_optimal_integrator.log row for row: each
    pattern's first solve (rebuilt / solver), its alternation's answer and that answer
    simulated, for the command's Euler knots and the RK4 row the alternation ran from."""
    doc = DOC.read_text(encoding="utf-8")
    text = doc[doc.index("## The knots' integrator\n"):
               doc.index("## Under position servos: the landing")]
    log = (LOGS / "bench_optimal_integrator.log").read_text(encoding="utf-8")
    blocks = dict(zip(("tripod", "wave"), log.split("\n# wave: ")[:2], strict=True))
    table = text[text.index("| pattern | knots |"):].split("\n\n")[0].splitlines()[2:]
    assert len(table) == 4
    for row in table:
        pattern, knots, first, alternation, simulated = (
            c.strip() for c in row.strip("|").split("|"))
        block = blocks[pattern]
        name = ("euler (the command's solve)" if knots.startswith("Euler") else
                "rk4 from " + re.search(r"from (.+?)\)", knots)[1].lower())
        solved = re.search(rf"^{re.escape(name)}\s+([0-9.]+)\s+([0-9.]+)\s", block,
                           re.MULTILINE)
        assert first == f"{solved[1]} / {solved[2]}", row
        alt = re.search(rf"^alternation from the row {re.escape(name)} .*?→ ([0-9.]+) J/m "
                        r"judged .*?the gait kept: (\w+)\);.*?\n  its answer simulated .*?"
                        r"feedforward ([0-9.]+) .*?position ([0-9.]+)", block,
                        re.MULTILINE | re.DOTALL)
        kept = " (the gait kept)" if alt[2] == "True" else ""
        assert alternation == f"{alt[1]}{kept}" and simulated == f"{alt[3]} / {alt[4]}", row


def test_the_landing_on_the_default_robot_is_the_kept_logs():
    """The landing section's whole-command figures are the two default-robot logs' last rows
    (with the weight and without)."""
    doc = DOC.read_text(encoding="utf-8")
    text = doc[doc.index("## Under position servos: the landing"):doc.index("## How it compares")]
    flat = " ".join(text.split())
    with_, without = (_optimal_table((LOGS / name).read_text(encoding="utf-8"))[
        "optimal motion, its springs"] for name in ("codesign_motion_optimal_landing.log",
                                                    "codesign_motion_optimal_spread.log"))
    assert (f"{with_[0]} ±0.1 J/m predicted, {with_[1]} under feedforward and {with_[2]} under "
            f"position servos, against {without[1]} and {without[2]} without the weight") in flat


def test_the_landing_choice_is_the_kept_logs():
    """The table of each optimal row's two answers prints the two whole commands' logs
    (codesign.json's ``optimal.rows[].landing``, by the bench's rows): each answer predicted,
    then simulated under feedforward and position servos, and which one the row kept; and the
    worse-servo ratios quoted under it are the kept answers' against the co-design's."""
    doc = DOC.read_text(encoding="utf-8")
    text = doc[doc.index("**So each optimal row chooses**"):doc.index("## How it compares")]
    expected = []
    worse = {}
    for robot, name in (("hexapod", "codesign_motion_optimal_worse_servo.log"),
                        ("Solo-12", "codesign_motion_optimal_solo12_worse_servo.log")):
        log = (LOGS / name).read_text(encoding="utf-8")
        for label, kept, *figures in re.findall(
                r"^(optimal motion, (?:no springs|its springs)): landing cost's answers "
                r"\(optimal\.rows\[\]\.landing\), kept (\d): weight 0: predicted ([0-9.]+) J/m, "
                r"simulated feedforward ([0-9.]+), position ([0-9.]+); weight 30: predicted "
                r"([0-9.]+) J/m, simulated feedforward ([0-9.]+), position ([0-9.]+)$", log,
                re.MULTILINE):
            v = [float(f) for f in figures]
            expected.append(f"| {robot} | {label} | {'with' if kept == '1' else 'without'} | "
                            + " / ".join(f"{x:.2f}" for x in v[:3]) + " | "
                            + " / ".join(f"{x:.2f}" for x in v[3:]) + " |")
            if label.endswith("its springs"):
                worse[robot] = max(v[4:6]) if kept == "1" else max(v[1:3])
        co = _optimal_table(re.sub(r"^\d\d:\d\d:\d\d ", "", log, flags=re.MULTILINE))[
            "parametric co-design (its gait and springs)"]
        worse[robot] = (worse[robot], max(float(x) for x in co[1:3]))
    table = text[text.index("| robot | row |"):].split("\n\n")[0].splitlines()[2:]
    assert table == expected
    flat = " ".join(text.split())
    (h, hc), (s, sc) = worse["hexapod"], worse["Solo-12"]
    assert f"for {h / hc:.2f}× the parametric co-design ({h:.2f} against {hc:.2f} J/m" in flat
    assert f"Solo-12's for {s / sc:.2f}× ({s:.2f} against {sc:.2f}" in flat


def test_the_starts_above_the_box_are_the_kept_logs():
    """The section on starts above the search box prints the default command's log (each
    start's prediction, the chosen one, the rows, the ratios against its co-design, the springs
    to buy), the co-design searched in one box with the start chosen and the ratios against it,
    and the × 1.3 probes' spreads (with 100 and 200 iterations)."""
    doc = DOC.read_text(encoding="utf-8")
    text = doc[doc.index("## Starts above the search box"):doc.index("## One wide box")]
    flat = " ".join(text.split())
    log = re.sub(r"^\d\d:\d\d:\d\d ", "", (LOGS / "codesign_motion_optimal_starts.log").read_text(
        encoding="utf-8"), flags=re.MULTILINE)
    line = re.search(r"^    starts of the optimal motion \(J/m predicted rebuilt, the co-design's "
                     r"springs\): (.*)$", log, re.MULTILINE)
    assert line
    tried = [(label.removeprefix("→ "), value, label.startswith("→ "))
             for label, value in (part.rsplit(": ", 1) for part in line[1].split("; "))]
    table = text[text.index("| start (the co-design's gait, with its springs) |"):].split(
        "\n\n")[0].splitlines()[2:]
    assert len(table) == len(tried) == 7
    for (label, value, chosen), row in zip(tried, table, strict=True):
        assert row == (f"| {label} (chosen) | **{value}** |" if chosen else
                       f"| {label} | {value} |"), row
    rows = _optimal_table(log)
    shown = text[text.index("| row (the command's own table) |"):].split(
        "\n\n")[0].splitlines()[2:]
    spreads = dict(re.findall(r"^    (optimal motion, (?:no springs|its springs)) +\S+ (±\S+) ",
                              log, re.MULTILINE))
    assert shown == [f"| {label} | {' '.join([figures[0], spreads.get(label, '')]).strip()} | "
                     + " | ".join(figures[1:]) + " |" for label, figures in rows.items()]
    judged = re.search(r"^optimal motion, its springs: predicted ([0-9.]+) J/m, spread [0-9.]+ "
                       r"J/m; judged ([0-9., ]+) J/m;", log, re.MULTILINE)
    landing = re.search(r"^optimal motion, its springs: landing cost's answers .*?kept 1: weight "
                        r"0: predicted ([0-9.]+) J/m, simulated feedforward [0-9.]+, position "
                        r"([0-9.]+); weight 30: predicted [0-9.]+ J/m, simulated feedforward "
                        r"([0-9.]+), position ([0-9.]+)$", log, re.MULTILINE)
    assert judged and landing
    co = rows["parametric co-design (its gait and springs)"]
    predicted, position = float(judged[1]), float(landing[4])
    assert float(landing[4]) > float(landing[3])  # position is the worse servo
    m = re.search(r"predicts ([0-9.]+) J/m, \*\*([0-9.]+)× the co-design's ([0-9.]+)\*\* \(its "
                  r"four repeats from starts moved by a hair ([0-9.]+)× to ([0-9.]+)×", flat)
    assert m and m[1] == f"{predicted:.3f}" and m[3] == co[0]
    assert abs(float(m[2]) - predicted / float(co[0])) < 1e-3
    repeats = [float(v) / float(co[0]) for v in judged[2].split(", ")]
    assert abs(float(m[4]) - min(repeats)) < 1e-3 and abs(float(m[5]) - max(repeats)) < 1e-3
    m = re.search(r"for ([0-9.]+) J/m, \*\*([0-9.]+)× the co-design's ([0-9.]+)\*\* under its "
                  r"worse", flat)
    assert m and m[1] == f"{position:.2f}" and m[3] == co[2]
    assert abs(float(m[2]) - position / float(co[2])) < 1e-3
    assert (f"without it {float(landing[1]):.2f} predicted and {float(landing[2]):.2f} under "
            "position servos") in flat
    assert _bought(log) in flat
    bound = re.search(r"^    the start chosen \(body height ([0-9.]+) mm, ([0-9.]+) × the default "
                      r"gait's\) .*?\(--body-high ([0-9.]+) or more", log, re.MULTILINE)
    assert bound and f"stands at {bound[1]} mm, {bound[2]} × the default gait's" in flat
    assert f"`hexaleg codesign --body-high {bound[3]}`" in flat
    box = (LOGS / "codesign_body_high_163.log").read_text(encoding="utf-8")
    assert f"codesign --body-high {bound[3]} " in box.splitlines()[0] + " "
    chosen = re.search(r"^  → \d\. duty factor ([0-9.]+), period ([0-9.]+) s: predicted ([0-9.]+) "
                       r"J/m, simulated feedforward ([0-9.]+), position ([0-9.]+)$", box,
                       re.MULTILINE)
    top = re.search(r"^  chosen gait: body_height ([0-9.]+) m", box, re.MULTILINE)
    assert chosen and top
    assert (f"stands at its top too ({top[1]} m) and its servo check chooses duty factor "
            f"{float(chosen[1]):g}, period {chosen[2]} s: {chosen[3]} J/m predicted, simulated "
            f"{chosen[4]} (feedforward) and {chosen[5]} (position)") in flat
    worse = max(float(chosen[4]), float(chosen[5]))
    assert (f"**{predicted / float(chosen[3]):.3f}× predicted and {position / worse:.3f}× under "
            "the worse servo**") in flat
    for name, iterations in (("codesign_motion_optimal_starts_130.log", 100),
                             ("codesign_motion_optimal_starts_130_it200.log", 200)):
        probe = (LOGS / name).read_text(encoding="utf-8")
        assert f"after {iterations} iterations" in probe
        spread = re.search(r"^optimal motion, its springs: judged ([0-9., ]+) J/m, spread "
                           r"([0-9.]+) J/m$", probe, re.MULTILINE)
        assert spread
        values = [float(v) for v in spread[1].split(", ")]
        assert f"{float(spread[2]):.3f} J/m" in flat or f"{float(spread[2]):.2f} J/m" in flat
        if iterations == 100:
            assert f"the answer {values[0]:.2f}" in flat
            assert f"({min(values):.2f} to {max(values):.2f}: the row prints 8 ±1" in flat
    kept = re.search(r"^optimal motion, its springs: predicted [0-9.]+ J/m, spread ([0-9.]+) J/m",
                     log, re.MULTILINE)
    assert kept and f"At × 1.25 the spread is {float(kept[1]):.3f} J/m" in flat


def test_solo12s_starts_are_the_kept_log():
    """On Solo-12's trot the starts' paragraph prints its command's log: the starts the legs
    cannot reach, the start chosen against the gait, the sprung trot's answer and its walks
    against the co-design's worse servo, and the trot without springs past the margin."""
    doc = " ".join(DOC.read_text(encoding="utf-8").split())
    text = doc[doc.index("**On Solo-12's trot**"):doc.index("**Why the lattice stops at")]
    log = re.sub(r"^\d\d:\d\d:\d\d ", "", (LOGS / "codesign_motion_optimal_solo12_starts.log")
                 .read_text(encoding="utf-8"), flags=re.MULTILINE)
    line = re.search(r"^    starts of the optimal motion .*?: (.*)$", log, re.MULTILINE)
    assert line
    tried = dict(part.removeprefix("→ ").rsplit(": ", 1) for part in line[1].split("; "))
    chosen = next(p.removeprefix("→ ").rsplit(": ", 1) for p in line[1].split("; ")
                  if p.startswith("→ "))
    assert [k for k, v in tried.items() if v == "—"] == [
        "body height × 1.05", "body height × 1.15", "body height × 1.25"]
    assert (f"chooses the {chosen[0].replace('step height', 'step height')} ({chosen[1]} J/m "
            f"with the co-design's springs, the gait {tried['the gait']})") in text
    landing = re.search(r"^optimal motion, its springs: landing cost's answers .*?kept 1: .*; "
                        r"weight 30: predicted ([0-9.]+) J/m, simulated feedforward ([0-9.]+), "
                        r"position ([0-9.]+)$", log, re.MULTILINE)
    assert landing
    co = _optimal_table(log)["parametric co-design (its gait and springs)"]
    worse = max(float(co[1]), float(co[2]))
    assert (f"({float(landing[1]):.2f}; the gait's start gave 16.78) and walks for "
            f"{float(landing[2]):.2f} under feedforward and {float(landing[3]):.2f} under "
            f"position servos: {float(landing[3]) / worse:.3f}× the co-design's worse "
            f"({worse:.2f})") in text
    margin = re.search(r"the least friction that admits forces here is μ = ([0-9.]+)", log)
    assert margin and f"needs μ {margin[1]} at one instant" in text


def test_the_same_answer_of_the_starts_is_the_kept_log():
    """The starts' same-answer paragraph prints its log: the rows' predictions and the
    simulated figures of each run, and the two springs to buy with the front's two families."""
    doc = " ".join(DOC.read_text(encoding="utf-8").split())
    text = doc[doc.index("**The same answer, and what is not.**"):doc.index(
        "**Why the lattice stops at")]
    log = (LOGS / "same_answer_codesign_motion_optimal_starts.log").read_text(encoding="utf-8")
    figures = re.findall(r"^(?:as given|moved): optimal motion, its springs: predicted ([0-9.]+) "
                         r"J/m \(spread [0-9.]+\), simulated feedforward [0-9.]+, position "
                         r"([0-9.]+)$", log, re.MULTILINE)
    assert len(figures) == 2
    (given, given_pos), (moved, moved_pos) = figures
    assert f"({given} and {moved} J/m, inside the row's ±0.1)" in text
    assert (f"({float(given_pos):.1f} and {float(moved_pos):.1f} under position servos: "
            f"{float(given_pos):.3f} and {float(moved_pos):.3f})") in text
    fronts = re.findall(r"^[-+]hexaleg codesign: Pareto front of (\w+) ", log, re.MULTILINE)
    assert fronts == ["preloaded", "linear"]
    buys = re.findall(r"^[-+]    springs to buy \(full spring rules on the optimal motion: .*?\): "
                      r"(.*?) on coxa, femur, tibia, ([0-9.]+) J/m", log, re.MULTILINE)
    assert buys == [("linear", "8.61"), ("linear, spring torque ≤ 0.05958 N·m", "8.71")]
    assert ("linear, 8.61 J/m, on one run; linear with its spring torque bounded at 0.05958 N·m, "
            "8.71 J/m, on the other") in text
    assert "preloaded on one run and linear on the other" in text
    after = (LOGS / "same_answer_codesign_motion_optimal_starts_front.log").read_text(
        encoding="utf-8")
    assert "Pareto front of" not in after.split("diff without progress lines")[1]
    buys = re.findall(r"^[-+]    springs to buy \(full spring rules on the optimal motion: .*?\): "
                      r"linear, spring torque ≤ ([0-9.]+) N·m on coxa, femur, tibia, ([0-9.]+) "
                      r"J/m, electrical saving \+([0-9.]+) % \(\+([0-9.]+) % net", after,
                      re.MULTILINE)
    assert len(buys) == 2 and buys[0][1:3] == buys[1][1:3]
    (bound, per_metre, saving, net), (bound2, _, _, net2) = buys
    assert f"{per_metre} J/m, +{saving} %" in text
    assert f"the torque bound ({bound} and {bound2} N·m)" in text
    assert f"the net saving (+{net} and +{net2} %)" in text
    wires = [re.findall(r"^[-+]      \w+ \w+: (\w+) d ([0-9.]+) mm, D [0-9.]+ mm, ([0-9.]+) turns",
                        part, re.MULTILINE) for part in after.split("springs to buy (full")[1:3]]
    assert wires[0] == wires[1] and len(wires[0]) == 4  # the same wires and turns


def test_the_wide_box_is_its_kept_log():
    """The wide box's section prints its kept command log: the rows, the co-design's search and
    chosen gait, the start chosen, the ratios against the co-design (predicted, and under the
    worse servo the kept answer walks for), the springs to buy and their simulation, the
    command's time; and the one-box ratios it sums up are those the sections before derive."""
    doc = DOC.read_text(encoding="utf-8")
    text = doc[doc.index("## One wide box"):doc.index("## How it compares")]
    flat = " ".join(text.split())
    log = re.sub(r"^\d\d:\d\d:\d\d ", "", (LOGS / "codesign_motion_optimal_wide_box.log")
                 .read_text(encoding="utf-8"), flags=re.MULTILINE)
    assert "codesign --motion optimal --body-high 1.7 --duty-high 0.9 --out out" in log
    assert "`hexaleg codesign --motion optimal --body-high 1.7 --duty-high 0.9`" in flat
    rows = _optimal_table(log)
    spreads = dict(re.findall(r"^    (optimal motion, (?:no springs|its springs)) +\S+ (±\S+) ",
                              log, re.MULTILINE))
    shown = text[text.index("| row (the command's own table) |"):].split(
        "\n\n")[0].splitlines()[2:]
    assert shown == [f"| {label} | {' '.join([figures[0], spreads.get(label, '')]).strip()} | "
                     + " | ".join(figures[1:]) + " |" for label, figures in rows.items()]
    search = re.search(r"^  search: .*?, (\d+) evaluations, [0-9.]+ s, restarts ([0-9.]+) J/m "
                       r"apart", log, re.MULTILINE)
    top = re.search(r"^  chosen gait: body_height ([0-9.]+) m, .*?duty_factor ([0-9.]+), period "
                    r"([0-9.]+) s$", log, re.MULTILINE)
    best = re.search(r"^    1\. duty factor ([0-9.]+), period ([0-9.]+) s: .*?position ([0-9.]+)$",
                     log, re.MULTILINE)
    assert search and top and best
    assert f"({search[1]} evaluations, restarts {search[2]} J/m apart)" in flat
    assert f"new top of the body height ({top[1]} m, 1.7 × the default gait's)" in flat
    assert f"chooses duty factor {top[2]}, period {top[3]} s" in flat
    assert (f"duty factor {float(best[1]):g} and period {float(best[2]):g} s, walks for "
            f"{best[3]} under position servos") in flat
    start = re.search(r"→ body height × ([0-9.]+): ", log)
    bound = re.search(r"^    the start chosen \(body height ([0-9.]+) mm, ([0-9.]+) × the default "
                      r"gait's\) lies above the parametric search's box \(1\.7 ×\)", log,
                      re.MULTILINE)
    assert start and bound
    assert (f"body height × {start[1]} of that gait ({bound[1]} mm, {bound[2]} × the default "
            "gait's: above this box too") in flat
    for factor in ("1.15", "1.25"):
        assert f"body height × {factor}: —" in log
    judged = re.search(r"^optimal motion, its springs: predicted ([0-9.]+) J/m, spread", log,
                       re.MULTILINE)
    landing = re.search(r"^optimal motion, its springs: landing cost's answers .*?kept 1: .*?"
                        r"weight 30: predicted [0-9.]+ J/m, simulated feedforward ([0-9.]+), "
                        r"position ([0-9.]+)$", log, re.MULTILINE)
    assert judged and landing and float(landing[2]) > float(landing[1])
    co = rows["parametric co-design (its gait and springs)"]
    predicted, position = float(judged[1]), float(landing[2])
    assert (f"predicts {predicted:.3f} J/m, **{predicted / float(co[0]):.3f}× the co-design's "
            f"{co[0]}**") in flat
    assert (f"for {position:.2f} J/m, **{position / float(co[2]):.3f}× the co-design's "
            f"{co[2]}**") in flat
    assert f"and in this wide box {predicted / float(co[0]):.3f}× and " \
           f"{position / float(co[2]):.3f}×" in flat
    assert _bought(log) in flat
    assert _timed(log) in flat
    assert "0.975× predicted and 0.921× under the worse servo (`--body-high 1.63`)" in flat
    earlier = doc[doc.index("## Starts above the search box"):doc.index("## One wide box")]
    assert "**0.975× predicted and 0.921× under the worse servo**" in " ".join(earlier.split())


def _timed(log: str) -> str:
    """A kept log's ``/usr/bin/time -v`` as the docs print it: "M min SS s wall and C s of CPU"
    (user plus system, rounded)."""
    user, system, wall = (re.search(pattern, log) for pattern in (
        r"User time \(seconds\): ([0-9.]+)", r"System time \(seconds\): ([0-9.]+)",
        r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (\d+):([0-9.]+)"))
    assert user and system and wall
    return (f"{wall[1]} min {round(float(wall[2])):02d} s wall and "
            f"{round(float(user[1]) + float(system[1]))} s of CPU")


def test_how_far_the_springs_to_buy_move_is_its_kept_log():
    """The paragraph on how far the springs to buy move prints its kept log's line (how many
    repeats buy the same springs, each kind's range), the log's rows and springs to buy are the
    starts log's (the same command, the spread added), and the command's times quoted are the
    two logs'."""
    doc = DOC.read_text(encoding="utf-8")
    flat = " ".join(doc.split())
    text = doc[doc.index("**How far the springs to buy move, said.**"):doc.index(
        "**Why the lattice stops at × 1.25.**")]
    said = " ".join(text.split())
    logs = {name: (LOGS / f"{name}.log").read_text(encoding="utf-8")
            for name in ("codesign_motion_optimal_rules_spread", "codesign_motion_optimal_starts")}
    log = re.sub(r"^\d\d:\d\d:\d\d ", "", logs["codesign_motion_optimal_rules_spread"],
                 flags=re.MULTILINE)
    line = re.search(r"^      on the row's repeats \(its start moved by -2e-09, -1e-09, \+1e-09, "
                     r"\+2e-09 m\) the full rules buy the same springs \(family, groups, each "
                     r"part's wire and turns\) on (\d) of (\d); over those their figures move by "
                     r"up to: (.*) — the digits above finer than that are not the method's$", log,
                     re.MULTILINE)
    assert line
    moved = {kind: value for kind, value, _unit in (
        re.fullmatch(r"([a-z -]+?) ([0-9.e-]+)(°| N·m| J/m| %| mm|)", part).groups()  # type: ignore[union-attr]
        for part in line[3].split(", "))}
    assert f"the same springs on {line[1]} of {line[2]}" in said
    assert (f"{moved['torque bound']} N·m (the torque bound), {moved['coil diameter']} mm (coil "
            f"diameters), {moved['hard stop']}° (hard stops), {moved['net saving']} points (the "
            f"net saving) and {moved['energy per metre']} J/m") in said

    def table(text: str) -> list[str]:
        plain = re.sub(r"^\d\d:\d\d:\d\d ", "", text, flags=re.MULTILINE)
        block = plain[plain.index("hexaleg at 0.06 m/s: electrical energy per metre"):
                      plain.index("wrote ")]
        return [x for x in block.splitlines() if "search: duty factor" not in x
                and "on the row's repeats" not in x and "search box's edge" not in x]

    assert table(logs["codesign_motion_optimal_rules_spread"]) == table(
        logs["codesign_motion_optimal_starts"])
    spread_time, starts_time = (_timed(logs[n]) for n in (
        "codesign_motion_optimal_rules_spread", "codesign_motion_optimal_starts"))
    assert f"It costs the command four more runs of the full rules: {spread_time}" in said
    assert f"({starts_time.split(' wall')[0]} before)" in said
    assert flat.count(f"its default, {starts_time} with nothing else running") == 1
    assert f"four repeats (how far they move, said beside them), {spread_time}" in flat
    assert f"codesign_motion_optimal_starts.log`; {starts_time} on the 2-core" in flat


def test_each_optimal_row_from_its_own_start_is_the_kept_logs():
    """The paragraph on each row's own start prints the two robots' kept logs: the lattice
    without springs' choice and figures, the default robot's rows as the spread log's to every
    digit, Solo-12's trot without springs from its own start (its prediction, spread and
    friction use, the answer kept and its simulations), its sprung rows as before."""
    doc = DOC.read_text(encoding="utf-8")
    text = doc[doc.index("**Each optimal row from its own start.**"):doc.index(
        "**Why the lattice stops at × 1.25.**")]
    said = " ".join(text.split())

    def read(name: str) -> str:
        return re.sub(r"^\d\d:\d\d:\d\d ", "", (LOGS / f"{name}.log").read_text(
            encoding="utf-8"), flags=re.MULTILINE)

    def lattice(log: str) -> dict[str, str]:
        line = re.search(r"^    starts of the optimal motion \(J/m predicted rebuilt, no "
                         r"springs\): (.*)$", log, re.MULTILINE)
        assert line
        return dict(part.rsplit(": ", 1) for part in line[1].split("; "))

    own, before = read("codesign_motion_optimal_own_starts"), read(
        "codesign_motion_optimal_rules_spread")
    bare = lattice(own)
    assert bare["→ body height × 1.25"] == "12.297" and bare["the gait"] == "16.384"
    assert "chooses the same start, body height × 1.25 (12.297 J/m against the gait's 16.384)" \
        in said
    assert "→ body height × 1.25: 8.913" in own  # the sprung lattice's choice: the same start
    assert _optimal_table(own) == _optimal_table(before)
    solo, solo_before = read("codesign_motion_optimal_solo12_own_starts"), read(
        "codesign_motion_optimal_solo12_starts")
    bare = lattice(solo)
    predicted = {k: v for k, v in bare.items() if v != "—"}
    assert predicted == {"→ body height × 0.95": "36.758"}
    assert "only body height × 0.95 has forces inside the margin without springs (36.758 J/m" \
        in said
    rows = _optimal_table(solo)
    row = re.search(r"^    optimal motion, no springs +(\S+ ±\S+) \(friction ([0-9.]+)\)", solo,
                    re.MULTILINE)
    landing = re.search(r"^optimal motion, no springs: landing cost's answers .*?kept 0: weight "
                        r"0: predicted [0-9.]+ J/m, simulated feedforward ([0-9.]+), position "
                        r"([0-9.]+);", solo, re.MULTILINE)
    assert row and landing and "beyond" not in row[0]
    assert (f"predicts {row[1]} J/m inside the margin (friction use {row[2]}) and walks under "
            f"both servos, for {float(landing[1]):.2f} (feedforward) and "
            f"{float(landing[2]):.2f} (position) J/m") in said
    assert "μ 0.441" in solo_before and "falls short" in doc
    old_rows = _optimal_table(solo_before)
    for label in ("default gait, no springs", "parametric co-design (its gait and springs)",
                  "optimal motion, its springs"):
        assert rows[label] == old_rows[label], label


def test_the_springs_to_buy_move_within_their_stated_spread():
    """In the kept same-answer log of the command with its input moved by 1e-9, both runs buy
    the same springs, and every figure of them that moves between the two runs (the torque
    bound, each coil diameter, hard stop and wound-up diameter, the net saving) moves by no more
    than the range the line beside them states on the first run; docs/optimal.md says so."""
    log = (LOGS / "same_answer_codesign_motion_optimal_rules_spread.log").read_text(
        encoding="utf-8")
    diff = log[log.index("the diff without progress lines:"):]

    def run(sign: str) -> tuple[str, list[str], str]:
        buy = re.search(rf"^\{sign}    springs to buy \(full spring rules on the optimal "
                        r"motion: [^)]*\): (.*)$", diff, re.MULTILINE)
        parts = re.findall(rf"^\{sign}      ((?:coxa|femur|tibia) (?:above|below): .*)$", diff,
                           re.MULTILINE)
        spread = re.search(rf"^\{sign}      on the row's repeats .*? on (\d) of (\d); over those "
                           r"their figures move by up to: (.*) — ", diff, re.MULTILINE)
        assert buy and parts and spread and spread[1] == spread[2]
        return buy[1], parts, spread[3]

    (buy_a, parts_a, said), (buy_b, parts_b, _) = run("-"), run("+")
    ranges = {m[0]: float(m[1]) for m in re.findall(r"([a-z -]+?) ([0-9.]+)(?:°| N·m| J/m| %| "
                                                   r"mm|)(?:, |$)", said)}
    names = re.compile(r"^(\w+), spring torque ≤ [0-9.]+ N·m on (.*?), ([0-9.]+) J/m")
    same = [names.match(b) for b in (buy_a, buy_b)]
    assert same[0] and same[1] and same[0].groups() == same[1].groups()
    bound = [float(re.search(r"≤ ([0-9.]+) N·m", b)[1]) for b in (buy_a, buy_b)]  # type: ignore[index]
    net = [float(re.search(r"\(\+([0-9.]+) % net", b)[1]) for b in (buy_a, buy_b)]  # type: ignore[index]
    assert 0 < abs(bound[0] - bound[1]) <= ranges["torque bound"]
    assert abs(net[0] - net[1]) <= ranges["net saving"] + 0.005  # printed to 0.01
    kinds = {"coil diameter": r"D ([0-9.]+) mm", "hard stop": r"hard stop at ([-+0-9.]+)°",
             "wound-up inner diameter": r"clears its arbor \(([0-9.]+) mm"}
    assert len(parts_a) == len(parts_b) == 4
    for a, b in zip(parts_a, parts_b, strict=True):
        assert re.sub(r"[0-9.]+", "#", a.split(";")[0].split(", D")[0]) == \
            re.sub(r"[0-9.]+", "#", b.split(";")[0].split(", D")[0])  # the same wire and turns
        assert a.split(", D")[0] == b.split(", D")[0]
        for kind, pattern in kinds.items():
            x, y = (float(re.search(pattern, p)[1]) for p in (a, b))  # type: ignore[index]
            step = 0.05 if kind == "hard stop" else 0.005  # half the printed digit
            assert abs(x - y) <= ranges[kind] + step, (kind, x, y)
    flat = " ".join(DOC.read_text(encoding="utf-8").split())
    assert ("each of their figures that moves between the runs moves within the range the line "
            f"states (the torque bound by {abs(bound[0] - bound[1]):.5f} N·m of "
            f"{ranges['torque bound']:g}") in flat
