"""``codesign.json``: {value, unit} numbers, and the keys hexaleg.load_design reads."""

from __future__ import annotations

import json

import pytest

import hexaleg


def _numbers(node, path=""):
    if isinstance(node, dict):
        if set(node) == {"value", "unit"}:
            return
        for k, v in node.items():
            yield from _numbers(v, f"{path}.{k}")
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from _numbers(v, f"{path}[{i}]")
    elif isinstance(node, float):
        yield path


ALLOWED_PLAIN = ("settings", "search")


def test_every_float_is_a_quantity(codesigned):
    data = codesigned.to_dict()
    bare = [p for p in _numbers(data) if not p.startswith(tuple(f".{a}" for a in ALLOWED_PLAIN))]
    assert bare == []
    assert [r["label"] for r in data["rows"]][:4] == [r.label for r in codesigned.rows]
    json.dumps(data, allow_nan=False)


def test_load_design_reads_the_chosen_gait_and_springs(codesigned, tmp_path):
    path = tmp_path / "codesign.json"
    path.write_text(json.dumps(codesigned.to_dict()))
    loaded = hexaleg.load_design(path)
    assert loaded.gait is not None
    for name in ("body_height", "foot_radius", "step_height", "duty_factor", "period"):
        assert getattr(loaded.gait, name) == pytest.approx(getattr(codesigned.chosen, name))
    assert set(loaded.springs) == set(codesigned.springs)
    assert "inner program" in codesigned.recommended[1]
    # the inner springs' saving on the chosen gait (not against the gait-alone row's gait),
    # with the forces the search planned: inside friction_margin of the cone
    robot = hexaleg.load()
    prepared = hexaleg.prepare(robot, hexaleg.gait(robot, codesigned.chosen),
                               contact=codesigned.constraints.planning_contact())
    base = prepared.baseline("joule")["total"]["electrical"]
    sprung = prepared.evaluate(codesigned.springs, "joule").metrics["total"]["electrical"]
    saving = codesigned.to_dict()["recommended"]["saving"]["electrical"]["value"]
    assert saving == pytest.approx(100 * (1 - sprung / base), rel=1e-9)


def test_summary_names_the_rows(codesigned):
    text = codesigned.summary()
    assert "co-design" in text and "J/m" in text and "evaluations" in text


def test_a_timing_searched_past_the_duty_bound_is_said():
    """The optimal rows' timing chosen above the parametric search's duty-factor bound is said
    (the co-design row then comes from a narrower family); at or under it, or with the timing
    not searched, nothing is said."""
    from types import SimpleNamespace

    from hexaleg.design.codesign.result import CodesignResult

    def result(duty: float | None, bound: float) -> SimpleNamespace:
        timing = None if duty is None else SimpleNamespace(
            chosen=SimpleNamespace(params=SimpleNamespace(duty_factor=duty)))
        return SimpleNamespace(optimal=SimpleNamespace(timing=timing, starts=None),
                               duty_high=bound)

    said = CodesignResult.bound_lines(result(0.85, 0.8))  # type: ignore[arg-type]
    assert len(said) == 1 and "duty factor 0.85" in said[0] and "bound (0.8)" in said[0]
    assert "--duty-high 0.85" in said[0]
    for duty, bound in ((0.85, 0.9), (0.8, 0.8), (None, 0.8)):
        assert CodesignResult.bound_lines(result(duty, bound)) == []  # type: ignore[arg-type]


def test_a_start_above_the_body_box_is_said():
    """The optimal rows' start chosen with its body above the parametric search's box
    (``body_high`` × the default gait's) is said, with the ``--body-high`` that holds it
    (rounded up: 1.3 × 1.05 = 1.365 needs 1.37, not 1.36); within the box, or with the starts
    not searched, nothing is said. Catches a start compared with the box in metres against a
    factor, or a suggested bound rounded below the start."""
    from types import SimpleNamespace

    from hexaleg.design.codesign.result import CodesignResult

    def result(body: float | None, box: float) -> SimpleNamespace:
        starts = None if body is None else SimpleNamespace(
            chosen=SimpleNamespace(params=SimpleNamespace(body_height=body)))
        return SimpleNamespace(optimal=SimpleNamespace(timing=None, starts=starts),
                               body_high=box, default=SimpleNamespace(body_height=0.0913))

    said = CodesignResult.bound_lines(result(0.0913 * 1.3 * 1.05, 1.3))  # type: ignore[arg-type]
    assert len(said) == 1 and "1.365 × the default gait's" in said[0]
    assert "box (1.3 ×)" in said[0] and "--body-high 1.37 " in said[0]
    for body, box in ((0.0913 * 1.365, 1.5), (0.0913 * 1.3, 1.3), (None, 1.3)):
        assert CodesignResult.bound_lines(result(body, box)) == []  # type: ignore[arg-type]
