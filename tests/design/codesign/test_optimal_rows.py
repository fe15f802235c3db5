"""The optimal motion's rows of ``hexaleg codesign --motion optimal``: the table, its JSON and
its proof; with Crocoddyl, the four rows of a small problem computed and simulated."""

from __future__ import annotations

import dataclasses
import itertools
import json
from types import SimpleNamespace

import numpy as np
import pytest

import hexaleg
from hexaleg.design.codesign.alternation import MOVES, Alternation, Prediction, Round, Spread
from hexaleg.design.codesign.optimal_rows import LABELS, MotionRow, OptimalRows
from hexaleg.quantities import json_text


def _solved(per_metre: float) -> SimpleNamespace:
    """The figures of an optimal cycle the table reads (an OptimalResult's)."""
    return SimpleNamespace(energy_per_metre=per_metre, residual=7e-15, iterations=100,
                           residual_check="euler_step", defect=0.0,
                           converged=False, stationarity=5e-5, threshold=1e-8, dynamic_gap=0.0,
                           periodicity=1e-3, friction_use=0.6, slip=4e-3, drift=2e-4,
                           torques=np.zeros((40, 18)), seconds=60.0, motion=None,
                           task_space=None)


def _rows(position: float | None) -> OptimalRows:
    springs = hexaleg.SpringSet({"femur": hexaleg.LinearSpring(stiffness=0.5)})
    start, best = _solved(9.2), _solved(9.0)
    alt = Alternation(None, 10.0, start, 9.3, best, springs,
                      (Round(springs, 8.9, 9.0, 9.1, True, 1.0),), 0.02, False)
    sims = [MotionRow(label, e, {"feedforward": 1.1 * e, "position": 1.3 * e},
                      {"feedforward": "walks", "position": "walks"},
                      {"feedforward": "open loop", "position": "balance feedback"})
            for label, e in zip(LABELS[:3], (28.4, 10.0, 9.6), strict=True)]
    last = MotionRow(LABELS[3], 9.0, {"feedforward": 9.5, "position": position},
                     {"feedforward": "walks",
                      "position": "walks" if position is not None else "fell: at 1 s"})
    return OptimalRows((*sims, last), springs, "linear", _solved(9.6), alt, hexaleg.load(),
                       "both", 200.0, "on")


def test_the_table_says_what_backs_the_springs():
    proven, unproven = _rows(11.0), _rows(None)
    assert proven.proven and not unproven.proven
    assert not any("unproven" in line for line in proven.lines())
    assert "unproven: it does not walk under position" in unproven.lines()[-1]
    data = json.loads(json_text(unproven.data()))
    assert [r["label"] for r in data["rows"]] == list(LABELS)
    assert data["rows"][3]["simulated"]["position"] is None
    assert data["rows"][3]["verdicts"]["position"].startswith("fell")
    assert data["residual"] == {"value": 7e-15, "unit": "N·m"}
    assert [e["value"] for e in data["alternation"]["energies"]] == [10.0, 9.3, 9.1]
    assert data["alternation"]["kept_gait"] is False
    assert data["feedback"] == "on" and "(balance feedback on)" in unproven.lines()[0]
    assert data["springs"][0]["joint"] == "femur" and data["proven"] is False
    assert data["rows"][0]["loops"] == {"feedforward": "open loop",
                                        "position": "balance feedback"}
    lines = proven.lines()
    assert "(balance feedback)" in lines[1] and "(open loop)" in lines[1]
    assert any("the solver's own J/m at its knots: 9.60 (no springs), 9.00" in line
               for line in lines)


def test_an_optimal_row_is_printed_to_the_digits_its_spread_leaves():
    """An optimal row whose prediction moves by 0.04 J/m with its start is printed to no
    decimal, predicted and simulated, with ``±1`` (its last digit's unit at least four times
    the spread); one that moves by 2e-4 to two with ``±0.01``; the parametric rows as before,
    without ±; the alternation's trail to the last row's digits and the solver's own figures to
    their own spread's; a round-off residual as ``≤ 1e-12``; codesign.json holds each spread.
    Catches a figure printed to digits its spread does not support."""
    table = _rows(11.0)
    bare = Spread(MOVES, (9.6, 9.6002, 9.6, 9.6001, 9.6), (9.6, 9.63, 9.6, 9.6, 9.6),
                  (5e-5,) * 5)
    last = Spread(MOVES, (9.0, 9.03, 8.99, 9.0, 9.01), (9.0,) * 5, (5e-5, 3e-2, 1e-3, 1e-3, 1e-3))
    rows = (*table.rows[:2], dataclasses.replace(table.rows[2], spread=bare),
            dataclasses.replace(table.rows[3], spread=last))
    lines = dataclasses.replace(table, rows=rows).lines()
    assert "    optimal motion, its springs" in lines[4] and "      9 ±1   10, 11" in lines[4]
    assert "   9.60 ±0.01   10.56 (open loop), 12.48 (balance" in lines[3]
    assert "  10.00   11.00 (open loop)" in lines[2] and "±" not in lines[1] + lines[2]
    assert lines[5].startswith("    ±: the prediction's spread over the row's answer repeated")
    assert "at its knots: 10 (no springs), 9.00 (its springs)" in lines[6]
    assert "stationarity up to 3e-02" in lines[7] and "10 → 9 → 9 J/m" in lines[7]
    assert "residual ≤ 1e-12 N·m" in lines[7]
    data = json.loads(json_text(dataclasses.replace(table, rows=rows).data()))
    assert data["rows"][3]["spread"]["value"] == {"value": pytest.approx(0.04), "unit": "J/m"}
    assert "spread" not in data["rows"][1]
    # moved starts without a prediction: said; with fewer than two predicted, no ± at all
    some = dataclasses.replace(last, judged=(9.0, None, 8.99, None, 9.0))
    none = dataclasses.replace(last, judged=(9.0, None, None, None, None))
    lines = dataclasses.replace(table, rows=(*table.rows[:3], dataclasses.replace(
        table.rows[3], spread=some))).lines()
    assert "    9.0 ±0.1 (2 of 5 not predicted)   9.5, 11.0" in lines[4]
    lines = dataclasses.replace(table, rows=(*table.rows[:3], dataclasses.replace(
        table.rows[3], spread=none))).lines()
    assert "   9.00 (no spread: 4 of 5 not predicted)   9.50, 11.00" in lines[4]


def test_a_row_without_a_prediction_says_why_not_nan():
    """A rebuilt trot whose stance feet cannot push the base's wrench (Solo-12's optimal trots)
    has no prediction: the row holds None and the analysis' error — the table prints a dash
    and the reason, codesign.json a null and the reason — never NaN; ``predicted_per_metre``
    returns the error's message where the force program has no answer."""
    from hexaleg.design.codesign.alternation import predicted_per_metre
    from hexaleg.dynamics.contact import ContactParams

    run = hexaleg.Scenario.load("hexaleg")
    motion = hexaleg.gait(run.model, hexaleg.GaitParams(samples=40))
    value, why = predicted_per_metre(run.model, motion, run.actuator, hexaleg.SpringSet(),
                                     ContactParams(mu=1e-3))
    assert value is None and why.startswith("InfeasibleForcesError: ")
    value, why = predicted_per_metre(run.model, motion, run.actuator, hexaleg.SpringSet(),
                                     run.contact)
    assert why == "" and value is not None and value > 0
    table = _rows(11.0)
    bare = MotionRow(LABELS[2], None, {"feedforward": None, "position": None},
                     {"feedforward": "raised", "position": "raised"},
                     unpredicted="InfeasibleForcesError: the stance feet LF, RH cannot produce "
                                 "the base wrench")
    rows = OptimalRows((*table.rows[:2], bare, table.rows[3]), table.springs, "linear",
                       table.bare, table.alternation, table.robot, "both", 1.0)
    line = rows.lines()[3]
    assert "nan" not in line and "— (no prediction: InfeasibleForcesError: the stance" in line
    data = json.loads(json_text(rows.data()))
    assert data["rows"][2]["predicted"] == {"value": None, "unit": "J/m"}
    assert data["rows"][2]["unpredicted"].startswith("InfeasibleForcesError")
    assert "unpredicted" not in data["rows"][0]


@pytest.mark.slow
def test_the_four_rows_of_a_small_problem():
    """The default gait as the 'chosen' one (no search), 16 knots, 40 iterations, one round:
    every row predicted and simulated under both servos, the residual at round-off, the
    alternation never rising, the optimal motions written and read back; every row predicted
    inside 0.7 of the cone (the gaits' rows as the co-design's inner program computes them)."""
    pytest.importorskip("crocoddyl")
    from hexaleg.design.codesign.build import default_gait
    from hexaleg.optimal.problem import OptimalParams

    run = hexaleg.Scenario.load("hexaleg")
    robot = run.model
    base = default_gait(robot, "hexaleg", 0.06, None, 100)
    planning = dataclasses.replace(run.contact, mu=0.7 * run.contact.mu)
    prepared = hexaleg.prepare(robot, hexaleg.gait(robot, base), motor=run.actuator,
                               contact=planning)
    design = hexaleg.optimal_springs(prepared, list(robot.joint_classes), family="linear",
                                     metric="electrical")
    e0 = prepared.evaluate(hexaleg.SpringSet()).metrics["total"]["electrical"]
    e1 = design.analysis.metrics["total"]["electrical"]
    from hexaleg.design.codesign.alternation import predicted_per_metre
    from hexaleg.design.codesign.optimal_rows import optimal_rows

    lines: list[str] = []
    d = prepared.motion.distance
    table = optimal_rows(robot, run.actuator, run.contact, base, base, design.springs,
                         margin=0.7, params=OptimalParams(nodes=16, iterations=40),
                         rounds=1, say=lines.append)
    assert table.rows[0].predicted == pytest.approx(e0 / d, rel=1e-9)
    assert table.rows[1].predicted == pytest.approx(e1 / d, rel=1e-9)
    assert [r.label for r in table.rows] == list(LABELS)
    assert all(set(r.simulated) == {"feedforward", "position"} for r in table.rows)
    assert table.rows[0].walks and table.rows[1].walks  # the gaits walk under both servos
    assert max(table.bare.residual, table.best.residual) <= 1e-6
    energies = table.alternation.energies
    assert all(b <= a for a, b in itertools.pairwise(energies))
    # The optimal rows are predicted by hexaleg's pipeline on the cycle rebuilt in task space,
    # the motion they simulate, the figure the alternation judges (never above the gait's).
    assert table.alternation.predicted == energies[-1] and energies[-1] <= energies[0]
    for row, played, springs in ((table.rows[2], table.bare.task_space, hexaleg.SpringSet()),
                                 (table.rows[3], table.alternation.motion, table.springs)):
        value, why = predicted_per_metre(robot, played, run.actuator, springs, planning)
        assert why == row.unpredicted == "" and row.predicted == pytest.approx(value, rel=1e-12)
        assert set(row.loops.values()) <= {"open loop", "balance feedback"}
    assert table.motions["optimal_springs"] is table.alternation.motion
    assert any(line.startswith("alternation: start") for line in lines)
    data = json.loads(json_text(table.data()))
    assert data["residual"]["value"] <= 1e-6 and len(data["rows"]) == 4


def test_the_alternation_and_the_bare_cycle_run_from_the_start_chosen(monkeypatch, robot):
    """With ``starts="lattice"`` the multi-start's chosen start — its gait, solver settings and
    solved cycle — is where both optimal motions start (the alternation from that cycle), and
    the table and codesign.json say the starts; with ``"gait"`` no multi-start runs."""
    pytest.importorskip("crocoddyl")
    import dataclasses

    import hexaleg.optimal.problem
    import hexaleg.optimal.solve
    from hexaleg.design.codesign import optimal_rows as rows_module
    from hexaleg.design.codesign.build import default_gait
    from hexaleg.design.codesign.starts import Start, StartSearch

    run = hexaleg.Scenario.load("hexaleg")
    chosen = dataclasses.replace(default_gait(robot, "hexaleg", 0.06, None, 100),
                                 duty_factor=0.8)
    moved = dataclasses.replace(chosen, step_height=1.3 * chosen.step_height)
    settings = hexaleg.optimal.problem.OptimalParams(iterations=3)
    picked = _solved(8.5)
    seen: dict[str, object] = {}

    def starts(_robot, timed, _motor, _springs, _contact, params, min_step, **kwargs):
        seen["starts"] = (timed, params, min_step, kwargs["first"])
        return StartSearch((Start("the gait", timed, params, _solved(9.0), 9.4, ""),
                            Start("step height × 1.3", moved, settings, picked, 9.3, "")), 1)

    def alternate(_robot, motion, _motor, _contact, **kwargs):
        seen["alternation"] = (motion, kwargs["params"], kwargs["first"])
        return Alternation(motion, 9.5, picked, 9.3, picked, hexaleg.SpringSet(), (), 0.0,
                           False)

    def solve(_robot, built, **_kwargs):
        seen["bare"] = built
        return SimpleNamespace(**{**vars(_solved(15.0)), "task_space": built})

    monkeypatch.setattr(rows_module, "search_starts", starts)
    monkeypatch.setattr(rows_module, "alternate", alternate)
    monkeypatch.setattr(hexaleg.optimal.problem, "build_problem",
                        lambda _r, motion, _m, _s, params: (motion, params))
    monkeypatch.setattr(hexaleg.optimal.solve, "solve", solve)
    monkeypatch.setattr(rows_module, "simulated_run",
                        lambda *_args: (10.0, "walks", True))
    monkeypatch.setattr(rows_module, "predict", lambda *_args: Prediction(15.0, 0.5, True))
    monkeypatch.setattr(rows_module, "judged", lambda *_args: Prediction(15.0, 0.5, True))
    monkeypatch.setattr(rows_module, "gait", lambda _robot, g: SimpleNamespace(params=g))

    def spreads(_robot, cases, _keep):
        seen["spreads"] = [c[1] for c in cases]
        return [None] * len(cases)

    monkeypatch.setattr(rows_module, "spreads", spreads)
    table = rows_module.optimal_rows(robot, run.actuator, run.contact, chosen, chosen,
                                     hexaleg.SpringSet(), params=settings,
                                     starts="lattice", min_step=0.015)
    # both spreads repeat their row's own answer: at the start chosen, with its settings
    (bare_inputs, alt_inputs) = seen["spreads"]
    assert bare_inputs == ("no springs", settings, moved)
    assert alt_inputs[0] == "alternation" and alt_inputs[2] == settings and alt_inputs[-1] == moved
    timed, params, min_step, first = seen["starts"]
    assert timed == chosen and params == settings and min_step == 0.015 and first is None
    motion, params, first = seen["alternation"]
    assert motion.params == moved and params == settings and first is picked
    bare_motion, bare_params = seen["bare"]
    assert bare_motion.params == moved and bare_params == settings
    assert table.starts is not None and table.starts.chosen.label == "step height × 1.3"
    assert any("→ step height × 1.3: 9.300" in line for line in table.lines())
    assert json.loads(json_text(table.data()))["starts"]["chosen"] == 1
    seen.clear()
    plain = rows_module.optimal_rows(robot, run.actuator, run.contact, chosen, chosen,
                                     hexaleg.SpringSet(), params=settings)
    assert "starts" not in seen and plain.starts is None and plain.data()["starts"] is None


def test_a_cycle_not_rebuilt_is_a_row_that_says_why(monkeypatch, robot):
    """The optimal cycle without springs that cannot be rebuilt in task space does not stop the
    table: its row has no prediction nor simulation and says ``not rebuilt`` and why, the other
    rows are computed, its motion file is left out and, the alternation having kept the gait,
    the springs to buy are the co-design's. Catches rows that play or predict a missing
    cycle."""
    pytest.importorskip("crocoddyl")
    import dataclasses

    import hexaleg.optimal.problem
    import hexaleg.optimal.solve
    from hexaleg.design.codesign import optimal_rows as rows_module
    from hexaleg.design.codesign.build import default_gait

    run = hexaleg.Scenario.load("hexaleg")
    chosen = dataclasses.replace(default_gait(robot, "hexaleg", 0.06, None, 100),
                                 duty_factor=0.8)
    springs = hexaleg.SpringSet({"femur": hexaleg.LinearSpring(stiffness=0.5)})
    why = "leg RH at t = 0.57 s: out of reach between knots 26 and 27"
    played: list[object] = []

    def solve(_robot, _built, **_kwargs):
        return SimpleNamespace(**{**vars(_solved(15.0)), "unbuilt": why})

    def alternate(_robot, motion, _motor, _contact, **_kwargs):
        return Alternation(motion, 9.5, _solved(9.0), None, _solved(9.0), springs, (), 0.0,
                           True)

    def simulated(_robot, motion, *_args):
        played.append(motion)
        return 10.0, "walks", True

    monkeypatch.setattr(rows_module, "alternate", alternate)
    monkeypatch.setattr(hexaleg.optimal.problem, "build_problem", lambda *_args: None)
    monkeypatch.setattr(hexaleg.optimal.solve, "solve", solve)
    monkeypatch.setattr(rows_module, "simulated_run", simulated)
    monkeypatch.setattr(rows_module, "apart",  # the two solves in this process, one by one
                        lambda jobs, _robot, _keep: [(job[1](), None) for job in jobs])
    monkeypatch.setattr(rows_module, "gait", lambda _robot, g: SimpleNamespace(params=g))
    monkeypatch.setattr(rows_module, "predict",  # the gaits' rows: 28.0 bare, 9.9 with springs
                        lambda _r, _m, _a, fitted, *_args: Prediction(
                            9.9 if fitted else 28.0, 0.5, True))
    table = rows_module.optimal_rows(robot, run.actuator, run.contact, chosen, chosen, springs)
    bare = table.rows[2]
    assert bare.predicted is None and bare.unpredicted == f"not rebuilt: {why}"
    assert set(bare.simulated.values()) == {None} and not bare.walks
    assert set(bare.verdicts.values()) == {f"not rebuilt: {why}"}
    assert [r.predicted for r in table.rows] == [28.0, 9.9, None, 9.9]
    assert len(played) == 3 * 2 and None not in played  # three rows under two servos
    assert table.proven and list(table.motions) == ["optimal_springs"]
    lines = table.lines()
    assert any("optimal motion, no springs" in line and f"— (not rebuilt: {why})" in line
               for line in lines)
    assert ("    the optimal cycle with springs was not rebuilt in task space: the last row is "
            "that gait with its springs") in lines
    assert lines[-1] == "    springs to buy for it: the co-design's (above)"  # the gait kept
    assert json.loads(json_text(table.data()))["rows"][2]["unpredicted"].startswith(
        "not rebuilt")


def _bought(rows: OptimalRows, rules: object, motion: hexaleg.Motion) -> OptimalRows:
    """``rows`` whose alternation's answer is the cycle ``motion`` and whose springs to buy are
    the full rules' ``rules``."""
    best = dataclasses.replace(rows.alternation, best=SimpleNamespace(**{
        **vars(rows.alternation.best), "task_space": motion}))
    return dataclasses.replace(rows, alternation=best, rules=rules)


def test_the_springs_to_buy_for_the_optimal_motion_are_the_full_rules(ruled, walk200):
    """Where the full spring rules ran on the optimal motion, the springs to buy are theirs
    (their parts, per metre of that motion, their proof), the alternation's own springs only the
    row's: the table proves the springs by the rules' simulation, not by row 4's walk (which
    fails under position servos here while the rules' springs are proven)."""
    from hexaleg.design.codesign.optimal_rows import ON
    from hexaleg.design.codesign.rules import per_metre

    rules = ruled.rules
    assert rules.pays and not rules.unproven  # the chosen gait's one-sided design, proven
    table = _bought(_rows(None), rules, walk200)
    assert table.proven and not table.rows[-1].walks
    lines = table.lines()
    assert "    its springs (linear, the alternation's): femur" in lines
    head = next(line for line in lines if "full spring rules on the optimal motion" in line)
    assert head.startswith("    springs to buy (full spring rules on the optimal motion: ")
    assert f"{per_metre(rules, walk200.distance):.2f} J/m" in head
    assert any("simulated electrical saving, the worse servo first" in line for line in lines)
    data = json.loads(json_text(table.data()))
    assert data["proven"] is True and data["full_rules"]["applied_to"] == ON
    assert data["full_rules"]["per_metre"]["value"] == pytest.approx(
        per_metre(rules, walk200.distance), rel=1e-12)
    assert data["full_rules"]["recommended"]["label"] == rules.recommended.label
    failed = _bought(_rows(None), "InvalidParameterError: too few samples", walk200)
    assert not failed.proven and failed.data()["full_rules"]["error"].endswith("samples")
    assert any("full spring rules could not run on the optimal motion "
               "(InvalidParameterError: too few samples)" in line for line in failed.lines())
    assert "unproven: it does not walk under position" in failed.lines()[-1]


def test_a_kept_gait_buys_the_co_designs_springs():
    """Where the alternation kept the co-design's gait, no rules run on it a second time: the
    springs to buy are the co-design's."""
    table = _rows(11.0)
    kept = dataclasses.replace(table, alternation=dataclasses.replace(table.alternation,
                                                                      kept_gait=True))
    assert kept.lines()[-1] == "    springs to buy for it: the co-design's (above)"
    assert kept.data()["full_rules"] is None


def test_every_row_is_judged_inside_the_margin_row_3_by_the_alternations_judge(monkeypatch,
                                                                               robot):
    """Every row is predicted inside the friction margin of the floor, by the same judge: on a
    floor of μ 0.1 the default gait's row is the force program's at 0.7 × 0.1 with its friction
    use (0.7 of the floor's cone) beside it — predicted in the whole cone it would be 6 % lower;
    the optimal cycle without springs, rebuilt short of its stride (90 %), gets no prediction
    and says why, as the alternation's judge refuses it for row 4 — a row 3 that skips the
    ``COVERED`` check would print its energy per metre of another task. codesign.json holds
    each row's friction use and whether it is inside the margin."""
    pytest.importorskip("crocoddyl")
    import hexaleg.optimal.problem
    import hexaleg.optimal.solve
    from hexaleg.design.codesign import optimal_rows as rows_module
    from hexaleg.design.codesign.alternation import predicted_per_metre
    from hexaleg.design.codesign.build import default_gait

    run = hexaleg.Scenario.load("hexaleg")
    floor = dataclasses.replace(run.contact, mu=0.1)
    base = default_gait(robot, "hexaleg", 0.06, None, 100)
    walk = hexaleg.gait(robot, base)
    short = hexaleg.gait(robot, dataclasses.replace(base, stride_length=0.9 * walk.distance,
                                                    speed=None))

    def solve(_robot, _built, **_kwargs):
        return SimpleNamespace(**{**vars(_solved(15.0)), "task_space": short})

    def alternate(_robot, motion, _motor, _contact, **_kwargs):
        return Alternation(motion, None, _solved(9.0), None, _solved(9.0), hexaleg.SpringSet(),
                           (), 0.0, True)

    monkeypatch.setattr(rows_module, "alternate", alternate)
    monkeypatch.setattr(hexaleg.optimal.problem, "build_problem", lambda *_args: None)
    monkeypatch.setattr(hexaleg.optimal.solve, "solve", solve)
    monkeypatch.setattr(rows_module, "simulated_run", lambda *_args: (10.0, "walks", True))
    monkeypatch.setattr(rows_module, "apart",
                        lambda jobs, _robot, _keep: [(job[1](), None) for job in jobs])
    monkeypatch.setattr(rows_module, "spreads", lambda _robot, cases, _keep: [None] * len(cases))
    table = rows_module.optimal_rows(robot, run.actuator, floor, base, base, hexaleg.SpringSet(),
                                     margin=0.7)
    first, _, bare, _ = table.rows
    inside, _ = predicted_per_metre(robot, walk, run.actuator, hexaleg.SpringSet(),
                                    dataclasses.replace(floor, mu=0.7 * 0.1))
    whole, _ = predicted_per_metre(robot, walk, run.actuator, hexaleg.SpringSet(), floor)
    assert first.predicted == inside and whole < 0.97 * inside and not first.beyond
    assert first.friction_use == pytest.approx(0.7, abs=1e-9)
    assert bare.predicted is None and "covers 90.0% of the gait's" in bare.unpredicted
    assert bare.walks  # played all the same: only its prediction is refused
    assert table.proven and table.margin == 0.7
    assert "inside 0.7 of the friction cone (their friction use)" in table.lines()[0]
    assert "(friction 0.70)" in table.lines()[1]
    data = json.loads(json_text(table.data()))
    assert data["friction_margin"] == {"value": 0.7, "unit": "1"}
    assert data["rows"][0]["friction_use"]["unit"] == "1"
    assert data["rows"][0]["within_margin"] is True and data["rows"][2]["within_margin"] is False
    assert data["rows"][2]["friction_use"] == {"value": None, "unit": "1"}


def test_springs_on_a_row_beyond_the_margin_are_unproven():
    """A last row whose cycle has no forces inside the friction margin is predicted in the
    whole cone and flagged — its friction use beside it, beyond the margin, and why — and its
    springs are unproven though it walks under both servos (the table's line and
    codesign.json). Catches a row beyond the margin printed as a silent number."""
    table = _rows(11.0)
    why = "no admissible forces within 0.7 of the friction cone (InfeasibleForcesError: …)"
    last = dataclasses.replace(table.rows[3], friction_use=0.93, beyond=why)
    rows = dataclasses.replace(table, rows=(*table.rows[:3], last))
    assert table.proven and not rows.proven and last.walks
    lines = rows.lines()
    assert "   9.00 (friction 0.93, beyond the 0.7 margin)   9.50, 11.00" in lines[4]
    assert f"    optimal motion, its springs: predicted in the whole friction cone, {why}" in lines
    assert lines[-1].endswith("— unproven: its forces need 0.93 of the friction cone, beyond "
                              "the 0.7 margin")
    data = json.loads(json_text(rows.data()))
    assert data["proven"] is False and data["unproven"].startswith("its forces need 0.93")
    assert data["rows"][3]["within_margin"] is False and data["rows"][3]["beyond"] == why
    assert data["rows"][3]["friction_use"] == {"value": 0.93, "unit": "1"}
    both = dataclasses.replace(rows, rows=(*table.rows[:3], dataclasses.replace(
        last, simulated={"feedforward": 9.5, "position": None})))
    assert both.unproven == ("its forces need 0.93 of the friction cone, beyond the 0.7 margin; "
                             "it does not walk under position")
