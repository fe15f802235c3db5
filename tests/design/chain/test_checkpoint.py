"""Tests of hexaleg.design.chain.checkpoint: a design's finished stages kept on disk, read back by
the same run only, and only as hexaleg's own data.

The whole command (a stage that fails, then the run that resumes; a design killed, then run
again) is tested in tests/commands/design/test_stages.py and tests/test_faults.py (slow)."""

from __future__ import annotations

import dataclasses
import io
import os
import pickle
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import hexaleg
from hexaleg.design.chain import chain as chain_module
from hexaleg.design.chain.chain import DesignChain
from hexaleg.design.chain.checkpoint import KEY_FILE, StageFiles, robot_key, run_key
from hexaleg.design.chain.config import design_params
from hexaleg.design.chain.config import mission as mission_of

QUAD = Path(__file__).resolve().parents[2] / "data" / "quad2dof.toml"
"""Another robot (a small quadruped of the tests' data)."""
LINEAR = {"design": {"samples": 100, "families": ["linear"], "pareto_fractions": [0.5]}}
"""A design of one family, cheap enough for the chain's candidates and Pareto front (~1 s)."""


def test_a_kept_stage_is_read_back_not_computed_again(tmp_path, monkeypatch):
    """The same run's second chain reads the candidates and the Pareto front from the files the
    first wrote, without a family's program (a program that would fail is never called), and
    they are the first's: the same springs, rows and robot objects of this process."""
    run = hexaleg.Scenario.from_tables("hexaleg", LINEAR)
    first = DesignChain(run, files=tmp_path / "stages").run(("candidates", "pareto"))
    assert sorted(p.name for p in (tmp_path / "stages").iterdir()) == [
        "candidates.pickle", "pareto.pickle", KEY_FILE]

    def never(*_a, **_k):
        raise AssertionError("a kept stage was computed again")

    monkeypatch.setattr(chain_module, "family_candidates", never)
    monkeypatch.setattr(chain_module, "pareto_front", never)
    said: list[str] = []
    second = DesignChain(run, said.append, files=tmp_path / "stages")
    again = second.run(("candidates", "pareto"))
    assert second.files is not None and second.files.written == ["candidates", "pareto"]
    assert sum("(kept from the earlier run)" in line for line in said) == 2
    for a, b in zip([*first.candidates, *(c for _, c in first.pareto)],
                    [*again.candidates, *(c for _, c in again.pareto)], strict=True):
        assert a.row == b.row and a.label == b.label
        np.testing.assert_array_equal(a.optimum.analysis.tau_spring,
                                      b.optimum.analysis.tau_spring)
    # the nominal gait and robot are this process's, not copies carried in the files
    assert again.recommended.optimum.analysis is not first.recommended.optimum.analysis
    assert _same_json(first, again)


def _same_json(a, b) -> bool:
    import json

    da, db = json.loads(a.to_json()), json.loads(b.to_json())
    da.pop("timings"), db.pop("timings")
    return da == db


def test_another_runs_stages_are_never_mixed_in(tmp_path):
    """A folder holding another run's stages (another key) reads as empty, and the first stage
    this run writes empties it first."""
    folder = tmp_path / "stages"
    other = StageFiles(folder, "a" * 64)
    other.save("candidates", [1, 2, 3], {})
    other.save("pareto", {"x": 1.5}, {})
    assert StageFiles(folder, "a" * 64).load("pareto", {}) == {"x": 1.5}
    mine = StageFiles(folder, "b" * 64)
    assert mine.load("candidates", {}) is None
    mine.save("ranking", (4,), {})
    assert sorted(p.name for p in folder.iterdir()) == sorted([KEY_FILE, "ranking.pickle"])


def test_a_stage_file_naming_anything_but_hexaleg_data_is_not_read(tmp_path):
    """A stage file that would call a function outside hexaleg, NumPy and the plain containers
    (here ``os.getpid``) is computed again, never run; so is a truncated one."""
    folder = tmp_path / "stages"
    files = StageFiles(folder, "c" * 64)
    files.save("candidates", np.arange(3.0), {})
    np.testing.assert_array_equal(StageFiles(folder, "c" * 64).load("candidates", {}),
                                  np.arange(3.0))

    class Runs:
        def __reduce__(self):
            return (os.getpid, ())

    (folder / "pareto.pickle").write_bytes(pickle.dumps(Runs()))
    assert StageFiles(folder, "c" * 64).load("pareto", {}) is None
    whole = (folder / "candidates.pickle").read_bytes()
    (folder / "candidates.pickle").write_bytes(whole[: len(whole) // 2])
    assert StageFiles(folder, "c" * 64).load("candidates", {}) is None
    buffer = io.BytesIO()
    pickle.dump(1, buffer)  # a plain number is data
    (folder / "ranking.pickle").write_bytes(buffer.getvalue())
    assert StageFiles(folder, "c" * 64).load("ranking", {}) == 1


@pytest.mark.parametrize("change", [
    {"gait": {"samples": 101}}, {"design": {"samples": 101}},
    {"mission": {"metres_per_fold": 5.0}}])
def test_the_run_key_changes_with_what_the_design_reads(change):
    base = hexaleg.Scenario.from_tables("hexaleg", {})
    other = hexaleg.Scenario.from_tables("hexaleg", change)

    def key(run, controller=None):
        return run_key(run, design_params(run, controller), mission_of(run))

    assert key(base) == key(hexaleg.Scenario.from_tables("hexaleg", {}))
    assert key(base) != key(other)
    assert key(base) != key(base, "position")  # --controller


def test_a_robot_is_keyed_by_its_content():
    """A robot loaded again, a pickled copy (what a forked process sends back) and one whose
    shapes' bounding boxes were filled in place (the co-design's run leaves its robot so) have
    the robot's key; the same model with another heading, or another robot, has another."""
    robot = hexaleg.load()
    assert robot_key(hexaleg.load()) == robot_key(robot)
    assert robot_key(pickle.loads(pickle.dumps(robot))) == robot_key(robot)
    checked = hexaleg.load()
    for g in checked.collision_model.geometryObjects:
        g.geometry.computeLocalAABB()
    assert pickle.dumps(checked.collision_model) != pickle.dumps(robot.collision_model)
    assert robot_key(checked) == robot_key(robot)
    turned = dataclasses.replace(robot, heading=np.array([0.0, 1.0, 0.0]))
    assert turned.model is robot.model and robot_key(turned) != robot_key(robot)
    assert robot_key(hexaleg.load(str(QUAD))) != robot_key(robot)


READ_BACK = """
import pickle, sys
import hexaleg
from hexaleg.design.chain.checkpoint import StageFiles
robot = hexaleg.load()
back = StageFiles(sys.argv[1], "k").load("stage", {"robot": robot})
assert back["mine"] is robot and all(r is robot for r in back["rules"]), back
assert back["model"] is robot.model and back["data"] is robot.data
assert back["number"] == 1.5
print("read back as this process's robot")
"""


def test_a_kept_stage_reads_back_the_new_processs_robot_for_every_copy(tmp_path):
    """A stage refers to the run's robot, to a copy of it (the co-design's spring rules send
    theirs back from a forked child) and to its Pinocchio model and data, none of which the file
    holds (the reader admits no Pinocchio class); another process reading it gets its own robot
    object in every place, by identity."""
    robot = hexaleg.load()
    copy = pickle.loads(pickle.dumps(robot))
    value = {"mine": robot, "rules": [copy, copy], "model": robot.model, "data": robot.data,
             "number": 1.5}
    StageFiles(tmp_path, "k").save("stage", value, {"robot": robot})
    assert b"pinocchio" not in (tmp_path / "stage.pickle").read_bytes()
    src = str(Path(hexaleg.__file__).resolve().parents[1])  # the code under test, not another
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([src, os.environ.get("PYTHONPATH", "")])}
    done = subprocess.run([sys.executable, "-c", READ_BACK, str(tmp_path)], capture_output=True,
                          text=True, timeout=120, check=False, env=env)
    assert done.returncode == 0, done.stderr
    assert "read back as this process's robot" in done.stdout


def test_a_stage_kept_for_one_robot_is_not_read_for_another(tmp_path):
    """A file naming a robot the run does not have (another robot, the same model with another
    heading, none at all) is not read: it is computed again, never resolved to the wrong one."""
    robot = hexaleg.load()
    StageFiles(tmp_path, "k").save("stage", [robot, 2.0], {"robot": robot})
    turned = dataclasses.replace(robot, heading=np.array([0.0, 1.0, 0.0]))
    for others in ({"robot": turned}, {"robot": hexaleg.load(str(QUAD))}, {}):
        assert StageFiles(tmp_path, "k").load("stage", others) is None
    back = StageFiles(tmp_path, "k").load("stage", {"robot": turned, "mine": robot})
    assert back is not None and back[0] is robot
