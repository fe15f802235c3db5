"""The optimal motion's rows of ``hexaleg codesign --motion optimal`` computed: from the start
chosen, a cycle not rebuilt, every row judged inside the margin, each row's answer kept by the
worse servo; with Crocoddyl, the four rows of a small problem computed and simulated."""

from __future__ import annotations

import dataclasses
import itertools
import json
from types import SimpleNamespace

import pytest
from optimal_records import solved

import hexaleg
from hexaleg.design.codesign.alternation import Alternation, Prediction
from hexaleg.design.codesign.optimal_table import LABELS
from hexaleg.quantities import json_text


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
                         rounds=1, starts="gait", say=lines.append)
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


def test_the_alternation_and_the_bare_cycle_run_from_their_own_starts(monkeypatch, robot):
    """With ``starts="lattice"`` the lattice is solved twice, with the co-design's springs and
    without: the alternation runs from the start chosen with the springs (its gait, solver
    settings and solved cycle), the optimal motion without springs from the start chosen
    without them (that start's solve its answer without the landing cost, not solved again), and
    the table and codesign.json say both lattices; springs the alternation cannot hold (it then
    starts without springs) share one lattice; with ``"gait"`` no multi-start runs. Catches a
    row 3 taken from the sprung start (Solo-12's trot: beyond the friction margin there)."""
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
    freer = dataclasses.replace(settings, swing_weight=0.01 * settings.swing_weight)
    springs = hexaleg.SpringSet({"femur": hexaleg.LinearSpring(stiffness=0.5)})
    picked = solved(8.5)
    bare_picked = SimpleNamespace(**{**vars(solved(14.0)), "task_space": "its rebuilt cycle"})
    seen: dict[str, list] = {}

    def starts(_robot, timed, _motor, fitted, _contact, params, min_step, **kwargs):
        seen.setdefault("starts", []).append((timed, params, min_step, kwargs.get("first"),
                                              fitted))
        if fitted:  # the co-design's springs: the step height × 1.3 chosen
            return StartSearch((Start("the gait", timed, params, solved(9.0), 9.4, ""),
                                Start("step height × 1.3", moved, settings, picked, 9.3, "")),
                               1)
        return StartSearch((Start("the gait", timed, params, solved(15.0), 15.2, ""),
                            Start("swing weight × 0.01", timed, freer, bare_picked, 14.1, "")),
                           1, kwargs["springs_named"])

    def alternate(_robot, motion, _motor, _contact, **kwargs):
        seen.setdefault("alternation", []).append((motion, kwargs["params"], kwargs["first"]))
        return Alternation(motion, 9.5, picked, 9.3, picked, hexaleg.SpringSet(), (), 0.0,
                           False)

    def solve(_robot, built, **_kwargs):
        seen.setdefault("solved", []).append(built)
        return SimpleNamespace(**{**vars(solved(15.0)), "task_space": built})

    monkeypatch.setattr(rows_module, "search_starts", starts)
    monkeypatch.setattr(rows_module, "alternate", alternate)
    monkeypatch.setattr(hexaleg.optimal.problem, "build_problem",
                        lambda _r, motion, _m, _s, params: (motion, params))
    monkeypatch.setattr(hexaleg.optimal.solve, "solve", solve)
    monkeypatch.setattr(rows_module, "simulated_run",
                        lambda *_args: (10.0, "walks", True))
    monkeypatch.setattr(rows_module, "predict", lambda *_args: Prediction(15.0, 0.5, True))
    def judge(_robot, result, motion, *_args):
        seen.setdefault("judged", []).append((result, motion))
        return Prediction(15.0, 0.5, True)

    monkeypatch.setattr(rows_module, "judged", judge)
    monkeypatch.setattr(rows_module, "gait", lambda _robot, g: SimpleNamespace(params=g))

    def spreads(_robot, cases, _keep):
        seen["spreads"] = [c[1] for c in cases]
        seen["again"] = [cases[0][2](1e-9)]  # row 3's repeat, solved
        return [(None, ())] * len(cases)

    monkeypatch.setattr(rows_module, "spreads", spreads)
    monkeypatch.setattr(rows_module, "apart",  # the solves in this process, one by one
                        lambda jobs, _robot, _keep: [(job[1](), None) for job in jobs])
    table = rows_module.optimal_rows(robot, run.actuator, run.contact, chosen, chosen,
                                     springs, params=settings, starts="lattice", min_step=0.015)
    # row 3 is judged and repeated on its own start's gait, the alternation on its own
    judged_motions = {id(result): motion.params for result, motion in seen["judged"]}
    assert judged_motions[id(bare_picked)] == chosen and judged_motions[id(picked)] == moved
    repeated_bare = seen["again"][0].task_space
    assert repeated_bare[0].params == chosen and repeated_bare[1] == freer
    # both spreads repeat their row's own answer: at its own start chosen, with its settings
    # (every answer walks for the same here: the one without the landing cost is kept)
    landed = dataclasses.replace(settings, servo_landing_weight=rows_module.SERVO_LANDING)
    bare_landed = dataclasses.replace(freer, servo_landing_weight=rows_module.SERVO_LANDING)
    (bare_inputs, alt_inputs) = seen["spreads"]
    assert bare_inputs == ("no springs", freer, chosen)
    assert alt_inputs[0] == "alternation" and alt_inputs[2] == settings and alt_inputs[-1] == moved
    (timed, params, min_step, first, fitted), (*bare_call, bare_fitted) = seen["starts"]
    assert timed == chosen and params == settings and min_step == 0.015 and first is None
    assert fitted is springs and bare_call == [chosen, settings, 0.015, None]
    assert bare_fitted == hexaleg.SpringSet()
    # the alternation without the cost from the start chosen, the one with it from its own
    # start: the start chosen solved again with the cost; the bare motion's answer without the
    # cost is its lattice's solve, the one with the cost solved from its start
    (motion, params, first), (motion_landed, params_landed, first_landed) = seen["alternation"]
    assert motion.params == moved and params == settings and first is picked
    assert motion_landed.params == moved and params_landed == landed
    (bare_motion, bare_params), (start_motion, start_params), _repeat = seen["solved"]
    assert bare_motion.params == chosen and bare_params == bare_landed
    assert start_motion.params == moved and start_params == landed
    assert first_landed.task_space == seen["solved"][1]
    assert table.bare is bare_picked  # the answer without the landing cost: its start's solve
    assert table.starts is not None and table.starts.chosen.label == "step height × 1.3"
    assert table.bare_starts is not None
    assert table.bare_starts.chosen.label == "swing weight × 0.01"
    lines = table.lines()
    assert any("(J/m predicted rebuilt, the co-design's springs): the gait: 9.400; → step height "
               "× 1.3: 9.300" in line for line in lines)
    assert any("(J/m predicted rebuilt, no springs): the gait: 15.200; → swing weight × 0.01: "
               "14.100" in line for line in lines)
    data = json.loads(json_text(table.data()))
    assert data["starts"]["chosen"] == 1 and data["starts_no_springs"]["chosen"] == 1
    assert data["starts_no_springs"]["springs"] == "no springs"
    seen.clear()
    shared = rows_module.optimal_rows(robot, run.actuator, run.contact, chosen, chosen,
                                      springs, params=settings, starts="lattice",
                                      min_step=0.015, family="one_sided")
    assert len(seen["starts"]) == 1 and seen["starts"][0][-1] == hexaleg.SpringSet()
    assert shared.bare_starts is shared.starts and shared.starts.springs == "no springs"
    assert sum("starts of the optimal motion (J/m predicted rebuilt, no springs)" in line
               for line in shared.lines()) == 1  # one lattice, said once
    seen.clear()
    plain = rows_module.optimal_rows(robot, run.actuator, run.contact, chosen, chosen,
                                     springs, params=settings, starts="gait")
    assert "starts" not in seen and plain.starts is None and plain.data()["starts"] is None
    assert plain.bare_starts is None and plain.data()["starts_no_springs"] is None


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
        return SimpleNamespace(**{**vars(solved(15.0)), "unbuilt": why})

    def alternate(_robot, motion, _motor, _contact, **_kwargs):
        return Alternation(motion, 9.5, solved(9.0), None, solved(9.0), springs, (), 0.0,
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
    table = rows_module.optimal_rows(robot, run.actuator, run.contact, chosen, chosen, springs,
                                     starts="gait")
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
        return SimpleNamespace(**{**vars(solved(15.0)), "task_space": short})

    def alternate(_robot, motion, _motor, _contact, **_kwargs):
        return Alternation(motion, None, solved(9.0), None, solved(9.0), hexaleg.SpringSet(),
                           (), 0.0, True)

    monkeypatch.setattr(rows_module, "alternate", alternate)
    monkeypatch.setattr(hexaleg.optimal.problem, "build_problem", lambda *_args: None)
    monkeypatch.setattr(hexaleg.optimal.solve, "solve", solve)
    monkeypatch.setattr(rows_module, "simulated_run", lambda *_args: (10.0, "walks", True))
    monkeypatch.setattr(rows_module, "apart",
                        lambda jobs, _robot, _keep: [(job[1](), None) for job in jobs])
    monkeypatch.setattr(rows_module, "spreads",
                        lambda _robot, cases, _keep: [(None, ())] * len(cases))
    table = rows_module.optimal_rows(robot, run.actuator, floor, base, base, hexaleg.SpringSet(),
                                     margin=0.7, starts="gait")
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


@pytest.mark.parametrize("cheaper", [0.0, 30.0])
def test_each_optimal_row_keeps_its_answer_by_the_worse_servo(monkeypatch, robot, cheaper):
    """Both optimal rows are solved without and with the landing cost (the weight
    :data:`SERVO_LANDING`, the alternation's start solved with each), played under both servos,
    and each keeps the answer walking cheaper under the worse one — its cycle, springs, motion
    files and spread (the spread repeats the answer kept, with its settings). Catches a row that
    keeps the answer without the cost whatever it walks for, the other answer's cycle behind the
    kept one's figures, or a spread measured on the answer not kept."""
    pytest.importorskip("crocoddyl")
    import hexaleg.optimal.problem
    import hexaleg.optimal.solve
    from hexaleg.design.codesign import optimal_rows as rows_module
    from hexaleg.design.codesign.build import default_gait

    run = hexaleg.Scenario.load("hexaleg")
    chosen = dataclasses.replace(default_gait(robot, "hexaleg", 0.06, None, 100),
                                 duty_factor=0.8)
    springs = hexaleg.SpringSet({"femur": hexaleg.LinearSpring(stiffness=0.5)})
    seen: dict[str, list[object]] = {"spreads": []}

    def solve(_robot, built, **_kwargs):
        weight = built[1].servo_landing_weight
        return SimpleNamespace(**{**vars(solved(15.0 + weight / 100)),
                                  "task_space": ("cycle", weight)})

    def alternate(_robot, motion, _motor, _contact, **kwargs):
        weight = kwargs["params"].servo_landing_weight
        best = SimpleNamespace(**{**vars(solved(9.0)), "task_space": ("springs", weight)})
        return Alternation(motion, 9.9, kwargs["first"], 9.5, best, springs, (), 0.0, False)

    def simulated(_robot, motion, _motor, _springs, controller, *_args):
        if not isinstance(motion, tuple):  # the gaits' rows
            return 10.0, "walks", False
        worse = 13.8 if motion[1] == cheaper else 18.2
        return (10.0 if controller == "feedforward" else worse), "walks", False

    def spreads(_robot, cases, _keep):
        seen["spreads"] = [c[1] for c in cases]
        return [(None, ())] * len(cases)

    monkeypatch.setattr(rows_module, "alternate", alternate)
    monkeypatch.setattr(hexaleg.optimal.problem, "build_problem",
                        lambda _r, motion, _m, _s, params: (motion, params))
    monkeypatch.setattr(hexaleg.optimal.solve, "solve", solve)
    monkeypatch.setattr(rows_module, "simulated_run", simulated)
    monkeypatch.setattr(rows_module, "apart",
                        lambda jobs, _robot, _keep: [(job[1](), None) for job in jobs])
    monkeypatch.setattr(rows_module, "spreads", spreads)
    monkeypatch.setattr(rows_module, "gait", lambda _robot, g: SimpleNamespace(params=g))
    monkeypatch.setattr(rows_module, "predict", lambda *_args: Prediction(9.9, 0.5, True))
    monkeypatch.setattr(rows_module, "judged", lambda *_args: Prediction(9.5, 0.5, True))
    table = rows_module.optimal_rows(robot, run.actuator, run.contact, chosen, chosen, springs,
                                     starts="gait")
    kept = 1 if cheaper else 0
    bare, last = table.rows[2], table.rows[3]
    assert bare.landing is not None and last.landing is not None
    assert bare.landing.kept == kept and last.landing.kept == kept
    assert [c.weight for c in last.landing.candidates] == [0.0, rows_module.SERVO_LANDING]
    assert bare.simulated == last.simulated == {"feedforward": 10.0, "position": 13.8}
    assert table.bare.task_space == ("cycle", cheaper)
    assert table.motions["optimal_springs"] == ("springs", cheaper)
    assert table.alternation.start.task_space == ("cycle", cheaper)  # its own start
    bare_inputs, alt_inputs = seen["spreads"]
    assert bare_inputs[1].servo_landing_weight == alt_inputs[2].servo_landing_weight == cheaper
    assert table.rows[0].landing is None and table.rows[1].landing is None
