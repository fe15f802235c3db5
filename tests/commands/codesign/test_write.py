"""``codesign.json``, ``codesign.html`` and ``speed.png`` on disk."""

from __future__ import annotations

import json

import pytest

from hexaleg.commands.codesign.write import curves, write_result
from hexaleg.errors import OutputError


def test_writes_json_page_and_plot(codesigned, tmp_path):
    data, files = write_result(codesigned, tmp_path / "out")
    names = sorted(p.name for p in files)
    assert names == ["codesign.html", "codesign.json", "speed.png"]
    assert json.loads((tmp_path / "out" / "codesign.json").read_text()) == data
    page = (tmp_path / "out" / "codesign.html").read_text()
    assert "chosen gait, its springs" in page and "data:image/png;base64," in page
    # without the rules the page says its springs are the ideal ones, not the springs to buy
    assert "an upper bound" in page and "friction cone used by the planned forces" in page
    assert set(curves(codesigned)) == {"default", "co-design"}


def test_unwritable_directory_is_named(codesigned, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(OutputError, match="file"):
        write_result(codesigned, blocker / "out")


def test_the_page_leads_with_the_worse_servo_and_draws_each_spring(ruled, tmp_path):
    """Issue #57: codesign.html showed only the feedforward servo's simulated saving; the
    position-only one is on the page, the worse first, and each spring to buy is drawn."""
    data, files = write_result(ruled, tmp_path / "out")
    rules = data["full_rules"]
    rows = rules["simulation"]
    assert [r["controller"] for r in rows] == sorted(
        (r["controller"] for r in rows),
        key=lambda c: next(r["simulated_saving"]["value"] for r in rows
                           if r["controller"] == c))
    assert {r["controller"] for r in rows} == {"feedforward", "position"}
    page = (tmp_path / "out" / "codesign.html").read_text()
    answer = page[page.index('<p class="answer'):]
    answer = answer[:answer.index("</p>")]
    shown = [f"{r['label']} {r['simulated_saving']['value']:+.2f} %" for r in rows]
    assert shown[0] in answer and shown[1] in answer
    assert answer.index(shown[0]) < answer.index(shown[1])
    assert rules["proof"]["proven"] is ("Walk with the gait below and fit these springs"
                                        in answer)
    svgs = sorted(p.name for p in files if p.suffix == ".svg")
    assert svgs and len(svgs) == len({m["part"] for m in rules["mounting"]})
    for name in svgs:
        assert (tmp_path / "out" / name).read_text() in page


SOLVER = {"stationarity": {"value": 0.0097, "unit": "1"}, "iterations": 100,
          "threshold": {"value": 1e-8, "unit": "1"}, "friction_use": {"value": 0.7, "unit": "1"},
          "energy_per_metre": {"value": 8.87, "unit": "J/m"}}
"""codesign.json's figures of an optimal solve, as the pages' tests give them."""


def test_the_page_shows_the_optimal_motions_table(codesigned):
    """codesign.json's ``optimal`` key (``--motion optimal``) is a table on the page, the
    springs unproven where the last row did not walk under a servo, each simulation with the
    controller that ran it and the solver's own figures beside the rebuilt cycles'; a row with
    a spread to the digits the table prints it to, with its ±; each row's friction use, a row
    beyond the friction margin flagged with why, and why the springs are unproven."""
    from hexaleg.outputs.html import render_codesign_html

    def row(label, e, position):
        return {"label": label, "predicted": {"value": e, "unit": "J/m"}, "decimals": 2,
                "simulated": {"feedforward": {"value": 1.5 * e, "unit": "J/m"},
                              "position": position},
                "verdicts": {"feedforward": "walks", "position": "fell: at 1.2 s"},
                "loops": {"feedforward": "balance feedback", "position": "open loop"},
                "friction_use": {"value": 0.55, "unit": "1"}, "within_margin": True}

    solver = SOLVER
    data = codesigned.to_dict()
    data["optimal"] = {
        "rows": [row(f"row {k}", e, {"value": 2 * e, "unit": "J/m"} if k < 3 else None)
                 for k, e in enumerate((28.45, 9.99, 15.36, 9.14))],
        "springs": [{"family": "linear", "joint": "LF_femur", "parameters": {}}],
        "family": "linear", "proven": False, "unproven": "it does not walk under position",
        "friction_margin": {"value": 0.7, "unit": "1"},
        "residual": {"value": 8e-15, "unit": "N·m"},
        "springs_motion": solver,
        "no_springs": solver | {"energy_per_metre": {"value": 15.12, "unit": "J/m"}},
        "feedback": "on",
        "alternation": {"energies": [{"value": None, "unit": "J/m"},
                                     {"value": 9.14, "unit": "J/m"}], "rounds": 1,
                        "kept_gait": False}}
    page = render_codesign_html(data, {"speed": ""}, {})
    table = page[page.index("The optimal motion with its springs"):]
    assert "landing legs' position-servo effort" not in table  # no row was solved twice
    from hexaleg.design.codesign.landing_choice import Candidate, Landing
    from hexaleg.quantities import json_text

    def answer(weight, feedforward, position):
        sims = {"feedforward": feedforward, "position": position}
        return Candidate(weight, 10.4, sims, {k: "walks" if v else "fell" for k, v in sims.items()})

    data["optimal"]["rows"][3]["landing"] = json.loads(json_text(Landing(
        (answer(0.0, 10.26, 18.24), answer(30.0, 10.24, 13.85)), 1).data()))
    data["optimal"]["rows"][2]["landing"] = json.loads(json_text(Landing(
        (answer(0.0, 38.4, 33.51), answer(30.0, 78.25, None)), 0).data()))
    landed = " ".join(render_codesign_html(data, {"speed": ""}, {}).split())
    assert ("row 2, the answer without the cost (without it 38.40 J/m under the worse servo, "
            "with it not walking under both servos); row 3, the answer with the cost (without it "
            "18.24 J/m under the worse servo, with it 13.85 J/m under the worse servo).") in landed
    assert "balance feedback setting: <b>on</b>, every row closed loop" in table
    assert "— → 9.140 J/m" in table and "the last row is that gait" not in table
    assert "Unproven — it does not walk under position —" in table and "LF_femur" in table
    assert "fell: at 1.2 s" in table
    assert "predicted, forces inside 0.7 of the friction cone</th><th>friction use" in table
    assert "<td>0.55</td>" in table and "beyond" not in table
    assert "13.71 J/m" in table and "0.32" in table  # 1.5 × 9.14, 9.14 / 28.45
    assert "13.71 J/m (balance feedback)" in table
    assert "15.12" in table and "8.87 J/m" in table  # the solver's own figures
    data["optimal"]["rows"][2] |= {"predicted": {"value": None, "unit": "J/m"},
                                   "unpredicted": "InfeasibleForcesError: no forces"}
    table = render_codesign_html(data, {"speed": ""}, {})
    assert "— no prediction: InfeasibleForcesError: no forces" in table and "nan" not in table
    data["optimal"]["rows"][2] |= {"predicted": {"value": 31.2, "unit": "J/m"},
                                   "friction_use": {"value": 0.93, "unit": "1"},
                                   "within_margin": False, "beyond": "no admissible forces"}
    table = render_codesign_html(data, {"speed": ""}, {})
    assert ("<td>0.93 — beyond the 0.7 margin, predicted in the whole cone: no admissible "
            "forces</td>") in table
    data["optimal"]["rows"][3] |= {"decimals": 1,
                                   "spread": {"value": {"value": 0.0117, "unit": "J/m"},
                                              "solver_value": {"value": 0.0, "unit": "J/m"}}}
    table = render_codesign_html(data, {"speed": ""}, {})
    assert "9.1 ±0.1 J/m" in table and "13.7 ±0.1 J/m (balance feedback)" in table
    data["optimal"]["rows"][3]["spread"]["value"]["value"] = None  # fewer than two predicted
    assert "9.1 J/m" in render_codesign_html(data, {"speed": ""}, {})


def test_the_page_buys_the_optimal_motions_springs_by_the_full_rules(ruled):
    """Where the full spring rules ran on the optimal motion, the page's answer for it is
    their recommendation (its energy per metre, saving and simulation), proven or not as their
    proof says; the alternation's own springs are named as the last row's."""
    from hexaleg.design.codesign.optimal_table import ON
    from hexaleg.design.codesign.rules import rule_data
    from hexaleg.outputs.html import render_codesign_html

    rules = rule_data(ruled.rules, 0.1, ON)
    solver = SOLVER
    data = ruled.to_dict()
    data["optimal"] = {
        "rows": [{"label": f"row {k}", "predicted": {"value": 9.0 + k, "unit": "J/m"},
                  "decimals": 2, "simulated": {"feedforward": None}, "verdicts":
                  {"feedforward": "fell"}, "loops": {},
                  "friction_use": {"value": 0.55, "unit": "1"}, "within_margin": True}
                 for k in range(4)],
        "friction_margin": {"value": 0.7, "unit": "1"},
        "springs": [{"family": "linear", "joint": "LF_femur", "parameters": {}}],
        "family": "linear", "proven": True, "residual": {"value": 8e-15, "unit": "N·m"},
        "springs_motion": solver, "no_springs": solver, "feedback": "auto",
        "alternation": {"energies": [{"value": 9.5, "unit": "J/m"}], "rounds": 1,
                        "kept_gait": False}, "full_rules": rules}
    page = render_codesign_html(data, {"speed": ""}, {})
    part = page[page.index("The optimal motion with its springs"):]
    assert "Walk the optimal motion and fit these springs:" in part
    assert f"<b>{rules['per_metre']['value']:.2f} J/m</b>" in part
    assert "the alternation's own springs (linear on\nLF_femur)" in part
    data["optimal"] |= {"proven": False, "full_rules": {"applied_to": ON, "pays": False,
                                                         "error": "InvalidParameterError: x"}}
    part = render_codesign_html(data, {"speed": ""}, {})
    part = part[part.index("The optimal motion with its springs"):]
    assert "Unproven" in part and "The full spring rules could not run on it" in part


@pytest.mark.slow  # two small co-design searches: ~5 s of CPU
def test_a_kill_in_the_optimal_stage_resumes_from_the_kept_co_design(tmp_path, monkeypatch):
    """``--motion optimal`` keeps the finished parametric co-design before the optimal motion's
    minutes: a kill there publishes nothing and leaves that stage, which the same run reads back
    instead of searching again (the optimal stage gets the same gait, springs and rows), and the
    kill's line counts the optimal stage's solves kept with it; another speed is another run,
    searched afresh."""
    from hexaleg.commands.codesign.write import STAGES, write_codesign
    from hexaleg.design.codesign import build, optimal_rows
    from hexaleg.optimal import backend
    from hexaleg.parallel.interrupt import kept

    monkeypatch.setattr(backend, "crocoddyl_module", lambda: None)  # the stage is stubbed
    handed = []

    def killed(*args, **kwargs):
        handed.append(args)
        kwargs["keep"](("no springs", len(handed)), lambda: 1.5)  # a solve finished, kept
        raise KeyboardInterrupt

    monkeypatch.setattr(optimal_rows, "optimal_rows", killed)
    run = {"robot": "hexaleg", "speed": 0.06, "samples": 40, "final_samples": 40,
           "max_evaluations": 10, "restarts": 1, "rules": False, "curve": False,
           "simulate": False, "motion": "optimal"}
    out = tmp_path / "out"
    with pytest.raises(KeyboardInterrupt) as stopped:
        write_codesign(out, **run)
    assert (out / STAGES / "parametric.pickle").is_file()
    assert kept(stopped.value)[-1:] == [f"but its parametric co-design and 1 optimal-control solve "
                                   f"are kept in {out / STAGES} for the same command to resume "
                                   "from"]
    assert not (out / "codesign.json").exists()

    class Searched(Exception):
        pass

    def search(*_, **__):
        raise Searched

    monkeypatch.setattr(build, "search", search)
    lines: list[str] = []
    with pytest.raises(KeyboardInterrupt):
        write_codesign(out, progress=lines.append, **run)
    assert "read back from the kept stage" in lines[0]
    first, again = handed
    assert first[3:5] == again[3:5]  # gaits
    assert repr(first[5]) == repr(again[5])  # springs
    with pytest.raises(Searched):
        write_codesign(out, **{**run, "speed": 0.05})


def test_the_optimal_note_prints_the_solver_and_the_alternation_as_the_text_does(codesigned):
    """codesign.html's note under the optimal table printed the solver's own J/m to two decimals
    and the alternation's trail to three whatever their spread, while the text table prints
    each to the digits its spread leaves (:func:`~hexaleg.design.codesign.alternation.decimals`):
    the same figures now read the same on the page and in the terminal. Catches the fixed
    ``%.2f``/``%.3f`` (15.12 and 9.14 J/m beside a spread of 0.03 J/m)."""
    import dataclasses

    from optimal_records import solved

    import hexaleg
    from hexaleg.design.codesign.alternation import MOVES, Alternation, Round, Spread
    from hexaleg.design.codesign.optimal_table import LABELS, MotionRow, OptimalRows
    from hexaleg.outputs.html import render_codesign_html
    from hexaleg.quantities import json_text

    springs = hexaleg.SpringSet({"femur": hexaleg.LinearSpring(stiffness=0.5)})
    alt = Alternation(None, 10.0, solved(9.2), 9.3456, solved(9.0123), springs,
                      (Round(springs, 8.9, 9.0, 9.1234, True, 1.0),), 0.02, False)
    spreads = {  # the solver's figure moves by 0.03 without springs (no decimal left), by 1e-4
        # with them (two), the last row's prediction by 0.01 (one, for the trail)
        2: Spread(MOVES, (9.6, 9.6002, 9.6, 9.6001, 9.6), (15.12, 15.15, 15.12, 15.12, 15.12),
                  (5e-5,) * 5),
        3: Spread(MOVES, (9.0, 9.01, 9.0, 9.0, 9.0), (9.0123, 9.0124, 9.0123, 9.0123, 9.0123),
                  (5e-5,) * 5)}
    rows = tuple(MotionRow(label, e, {"feedforward": 1.1 * e}, {"feedforward": "walks"},
                           {"feedforward": "open loop"}, spread=spreads.get(k))
                 for k, (label, e) in enumerate(zip(LABELS, (28.4, 10.0, 9.6, 9.0),
                                                    strict=True)))
    table = OptimalRows(rows, springs, "linear", solved(15.12), alt, hexaleg.load(),
                        "feedforward", 200.0, "on")
    lines = table.lines()
    data = codesigned.to_dict() | {"optimal": json.loads(json_text(table.data()))}
    page = render_codesign_html(data, {"speed": ""}, {})
    note = page[page.index("The optimal motion with its springs"):]
    assert "at its knots: 15 (no springs), 9.01 (its springs)" in lines[6]
    assert "the solver's own figure at its knots: 15\nand 9.01 J/m" in note
    assert "alternation 10.0 → 9.3 → 9.1 J/m predicted" in lines[7]
    assert "10.0 → 9.3 → 9.1 J/m" in note
    # without a spread (the rows of a run that measured none), the figures' most digits
    bare = dataclasses.replace(table, rows=tuple(dataclasses.replace(r, spread=None)
                                                 for r in rows))
    page = render_codesign_html(codesigned.to_dict() | {
        "optimal": json.loads(json_text(bare.data()))}, {"speed": ""}, {})
    assert "15.12\nand 9.01 J/m" in page and "10.000 → 9.346 → 9.123 J/m" in page
    assert any("knots: 15.12 (no springs), 9.01" in line for line in bare.lines())
    assert any("alternation 10.000 → 9.346 → 9.123 J/m" in line for line in bare.lines())


def test_the_page_says_the_start_chosen_and_a_start_above_the_box(codesigned):
    """codesign.json's ``optimal.beyond_box`` is the terminal's bound lines (a start chosen
    above the parametric search's box, the co-design row then from a narrower family), and
    the page prints them and every start with its prediction, the chosen one marked; without
    starts the page says the motion started from the chosen gait. Catches a page that hides
    where the optimal motion's gain came from."""
    import dataclasses
    from types import SimpleNamespace

    from hexaleg.outputs.html import render_codesign_html

    assert codesigned.default.body_height is not None
    body = codesigned.default.body_height * 1.625
    table = {"rows": [], "springs": [], "family": "linear", "proven": True,
             "friction_margin": {"value": 0.7, "unit": "1"}, "timing": None,
             "starts": {"starts": [
                 {"start": "the gait", "predicted": {"value": 10.506, "unit": "J/m"}},
                 {"start": "body height × 1.25", "predicted": {"value": 8.913, "unit": "J/m"}},
                 {"start": "body height × 1.5", "predicted": {"value": None, "unit": "J/m"},
                  "unpredicted": "GaitReachError: out of reach"}], "chosen": 1}}
    stand_in = SimpleNamespace(data=lambda: dict(table), timing=None, starts=SimpleNamespace(
        chosen=SimpleNamespace(params=SimpleNamespace(body_height=body))))
    data = dataclasses.replace(codesigned, optimal=stand_in).to_dict()
    said = data["optimal"]["beyond_box"]
    assert said == [line.strip() for line in dataclasses.replace(
        codesigned, optimal=stand_in).bound_lines()]
    assert len(said) == 1 and "1.625 × the default gait's" in said[0]
    assert "--body-high 1.63" in said[0]
    both = SimpleNamespace(**vars(stand_in), bare_starts=SimpleNamespace(
        chosen=SimpleNamespace(params=SimpleNamespace(body_height=body * 1.02))))
    own = dataclasses.replace(codesigned, optimal=both).bound_lines()
    assert len(own) == 2 and own[1].startswith(
        "    the start chosen without springs (body height ") and "1.657 ×" in own[1]
    figures = {"predicted": {"value": 9.0, "unit": "J/m"}, "decimals": 2,
               "simulated": {"feedforward": {"value": 9.5, "unit": "J/m"}},
               "verdicts": {"feedforward": "walks"}, "loops": {"feedforward": "open loop"},
               "friction_use": {"value": 0.7, "unit": "1"}, "within_margin": True}
    data["optimal"] |= {"rows": [figures | {"label": f"row {k}"} for k in range(4)],
                        "residual": {"value": 6e-15, "unit": "N·m"}, "springs_motion": SOLVER,
                        "no_springs": SOLVER, "feedback": "auto",
                        "alternation": {"energies": [], "kept_gait": False}}
    page = render_codesign_html(json.loads(json.dumps(data)), {"speed": ""}, {})
    import re

    text = re.sub(r"<[^>]+>", "", page[page.index("The optimal motion with its springs"):])
    assert "from the best start about the chosen gait (body height × 1.25)" in text
    assert said[0][1:].replace("'", "&#39;") in text
    assert ("the gait: 10.506; body height × 1.25: 8.913 (chosen); body height × 1.5: — "
            "(GaitReachError: out of reach)") in " ".join(text.split())
    data["optimal"]["starts_no_springs"] = {"starts": [
        {"start": "the gait", "predicted": {"value": 12.9, "unit": "J/m"}},
        {"start": "body height × 1.25", "predicted": {"value": 12.261, "unit": "J/m"}}],
        "chosen": 1, "springs": "no springs"}
    bare = " ".join(re.sub(r"<[^>]+>", "", render_codesign_html(data, {"speed": ""}, {}))
                    .split())
    assert ("from the best start about the chosen gait (body height × 1.25; the motion without "
            "springs from its own, body height × 1.25)") in bare
    assert ("Starts of the optimal motion without springs, the same lattice solved without "
            "them (the row without springs runs from the one chosen; J/m): the gait: 12.900; "
            "body height × 1.25: 12.261 (chosen).") in bare
    data["optimal"] |= {"starts": None, "beyond_box": [], "starts_no_springs": None}
    plain = render_codesign_html(data, {"speed": ""}, {})
    assert "from the chosen gait (contact timing the gait's)" in " ".join(
        re.sub(r"<[^>]+>", "", plain).split())
    assert "Starts of the optimal motion" not in plain


def test_a_chosen_gait_on_the_box_s_edge_is_said_everywhere(codesigned):
    """A co-design whose chosen gait lies on its search box's top of body height and duty
    factor says so in the terminal, codesign.json (``box.edges``, with the box's bounds) and
    codesign.html, each edge with the option that widens it; a chosen gait inside the box says
    nothing. Catches an answer on an edge printed as if the search had found it free, or the
    page and the file disagreeing with the terminal."""
    import dataclasses
    import re

    from hexaleg.outputs.html import render_codesign_html

    assert codesigned.box is not None and codesigned.edges == ()
    assert "search box's edge" not in codesigned.summary()
    (_, body), (_, duty) = (codesigned.box.bounds[n] for n in ("body_height", "duty_factor"))
    edged = dataclasses.replace(codesigned, chosen=dataclasses.replace(
        codesigned.chosen, body_height=body, duty_factor=duty))
    line = [x for x in edged.summary().splitlines() if "search box's edge" in x]
    assert line == [
        f"  on the search box's edge: body height {body:.4g} m at the box's top (--body-high, "
        "up to 2 × the default gait's); duty factor 0.8 at the box's top (--duty-high, up to "
        "0.95) — the co-design is this box's optimum; a cheaper gait may lie past an edge"]
    data = json.loads(json.dumps(edged.to_dict()))
    assert data["box"]["edges"] == [
        {"parameter": "body_height", "side": "top", "value": {"value": body, "unit": "m"},
         "moved_by": "--body-high, up to 2 × the default gait's"},
        {"parameter": "duty_factor", "side": "top", "value": {"value": duty, "unit": "1"},
         "moved_by": "--duty-high, up to 0.95"}]
    assert data["box"]["bounds"]["duty_factor"] == [{"value": 0.5, "unit": "1"},
                                                    {"value": 0.8, "unit": "1"}]
    text = " ".join(re.sub(r"<[^>]+>", "", render_codesign_html(data, {"speed": ""}, {}))
                    .split())
    assert (f"On the search box's edge. The chosen gait lies on it: body height {body:.4g} m "
            "at the box's top (--body-high, up to 2 × the default gait's); duty factor 0.8 at "
            "the box's top (--duty-high, up to 0.95).") in text.replace("&#39;", "'")
    plain = render_codesign_html(json.loads(json.dumps(codesigned.to_dict())), {"speed": ""}, {})
    assert "On the search box" not in plain
