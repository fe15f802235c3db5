"""Which answer an optimal row keeps: the least J/m walked under the worse servo."""

from __future__ import annotations

import dataclasses
import json

from optimal_records import answer, four_rows

from hexaleg.quantities import json_text


def test_a_row_keeps_the_answer_walking_cheaper_under_the_worse_servo():
    """The hexapod's case (the landing cost's answer walks under position servos for 13.8
    where the other walks for 18.2) keeps the answer with the cost; Solo-12's (78 / 76 with it
    against 38 / 34) the one without. Catches a choice by the better servo (the first pair:
    feedforward 10.0 against 11.0 would keep the answer without the cost), by the prediction,
    or by the feedforward servo alone."""
    from hexaleg.design.codesign.landing_choice import by_worse_servo

    assert by_worse_servo([answer(0.0, 10.0, 10.0, 18.2),
                           answer(30.0, 10.5, 11.0, 13.8)]) == 1
    assert by_worse_servo([answer(0.0, 31.0, 38.0, 34.0),
                           answer(30.0, 30.0, 78.0, 76.0)]) == 0
    # an answer that does not walk under one servo is never kept over one that walks
    assert by_worse_servo([answer(0.0, 9.0, 9.0, None), answer(30.0, 12.0, 20.0, 30.0)]) == 1
    # neither walks: the cheaper prediction; none predicted: the first (without the cost)
    assert by_worse_servo([answer(0.0, 12.0, None, 20.0), answer(30.0, 11.0, 9.0, None)]) == 1
    assert by_worse_servo([answer(0.0, None, None, None), answer(30.0, None, None, None)]) == 0


def test_a_tie_under_the_worse_servo_goes_to_the_cheaper_prediction():
    """Within the servo check's tie (0.2 % of the least, what a forward simulation's rounding
    may move on another machine) the cheaper prediction is kept, and on equal predictions the
    answer without the cost; beyond it the simulation decides. Catches a strict ``<`` on the
    simulated figures (13.81 against 13.80 would keep the dearer prediction)."""
    from hexaleg.design.codesign.landing_choice import by_worse_servo
    from hexaleg.design.codesign.servo import TIE

    assert TIE == 0.002
    assert by_worse_servo([answer(0.0, 10.5, 10.0, 13.80),
                           answer(30.0, 10.4, 10.0, 13.81)]) == 1
    assert by_worse_servo([answer(0.0, 10.4, 10.0, 13.81),
                           answer(30.0, 10.4, 10.0, 13.80)]) == 0
    assert by_worse_servo([answer(0.0, 10.0, 10.0, 13.80),
                           answer(30.0, 10.5, 10.0, 13.80 * (1 + 2 * TIE) + 0.01)]) == 0
    assert by_worse_servo([answer(0.0, 10.0, 10.0, 14.00),
                           answer(30.0, 10.5, 10.0, 13.90)]) == 1


def test_the_table_says_which_answer_each_optimal_row_kept():
    """Each optimal row's line of the landing cost: which answer it kept, each one's J/m under
    the worse servo and predicted; codesign.json holds both answers, the weight kept and the
    rule."""
    from hexaleg.design.codesign.landing_choice import Landing

    rows = four_rows(12.0)
    bare = Landing((answer(0.0, 15.0, 16.0, 20.8), answer(30.0, 15.1, 16.3, 20.5)), 1)
    last = Landing((answer(0.0, 10.4, 10.3, 18.2), answer(30.0, 10.4, 10.2, 13.8)), 1)
    solo = Landing((answer(0.0, 31.0, 38.0, 34.0), answer(30.0, 31.0, 78.0, 76.0)), 0)
    table = dataclasses.replace(rows, rows=(
        *rows.rows[:2], dataclasses.replace(rows.rows[2], landing=solo),
        dataclasses.replace(rows.rows[3], landing=last)))
    lines = table.lines()
    assert ("    each optimal row solved without and with the landing legs' position-servo "
            "effort in its cost (weight 30), kept the one walking cheaper under the worse "
            "servo:") in lines
    assert ("    optimal motion, no springs: kept the answer without the landing cost — without "
            "it 38.00 under the worse servo (31.00 predicted); with it 78.00 under the worse "
            "servo (31.00 predicted)") in lines
    assert ("    optimal motion, its springs: kept the answer with the landing cost — with it "
            "13.80 under the worse servo (10.40 predicted); without it 18.20 under the worse "
            "servo (10.40 predicted)") in lines
    data = json.loads(json_text(table.data()))["rows"]
    assert "landing" not in data[0] and "landing" not in data[1]
    assert data[3]["landing"]["kept"] == 1
    assert data[3]["landing"]["servo_landing_weight"] == {"value": 30.0, "unit": "W/(N·m)^2"}
    assert data[2]["landing"]["candidates"][1]["simulated"]["position"] == {
        "value": 76.0, "unit": "J/m"}
    assert bare.weight == 30.0 and solo.weight == 0.0
