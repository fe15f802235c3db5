"""The optimal motion's table: its lines, its ``optimal`` JSON, what proves its springs."""

from __future__ import annotations

import dataclasses
import json
from types import SimpleNamespace

import pytest
from optimal_records import four_rows

import hexaleg
from hexaleg.design.codesign.alternation import MOVES, Spread
from hexaleg.design.codesign.optimal_table import LABELS, MotionRow, OptimalRows
from hexaleg.quantities import json_text


def test_the_table_says_what_backs_the_springs():
    proven, unproven = four_rows(11.0), four_rows(None)
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
    table = four_rows(11.0)
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
    table = four_rows(11.0)
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
    from hexaleg.design.codesign.optimal_table import ON
    from hexaleg.design.codesign.rules import per_metre

    rules = ruled.rules
    assert rules.pays and not rules.unproven  # the chosen gait's one-sided design, proven
    table = _bought(four_rows(None), rules, walk200)
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
    failed = _bought(four_rows(None), "InvalidParameterError: too few samples", walk200)
    assert not failed.proven and failed.data()["full_rules"]["error"].endswith("samples")
    assert any("full spring rules could not run on the optimal motion "
               "(InvalidParameterError: too few samples)" in line for line in failed.lines())
    assert "unproven: it does not walk under position" in failed.lines()[-1]


def test_a_kept_gait_buys_the_co_designs_springs():
    """Where the alternation kept the co-design's gait, no rules run on it a second time: the
    springs to buy are the co-design's."""
    table = four_rows(11.0)
    kept = dataclasses.replace(table, alternation=dataclasses.replace(table.alternation,
                                                                      kept_gait=True))
    assert kept.lines()[-1] == "    springs to buy for it: the co-design's (above)"
    assert kept.data()["full_rules"] is None


def test_springs_on_a_row_beyond_the_margin_are_unproven():
    """A last row whose cycle has no forces inside the friction margin is predicted in the
    whole cone and flagged — its friction use beside it, beyond the margin, and why — and its
    springs are unproven though it walks under both servos (the table's line and
    codesign.json). Catches a row beyond the margin printed as a silent number."""
    table = four_rows(11.0)
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
