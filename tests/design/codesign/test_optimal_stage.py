"""Tests of hexaleg.design.codesign.optimal_stage: the parametric co-design kept before the
optimal motion's stage and read back with this run's robot.

The whole command (a kill in the optimal stage, then the run that resumes) is tested in
tests/commands/codesign/test_write.py (slow)."""

from __future__ import annotations

import dataclasses
import io
import json
import pickle

import numpy as np

import hexaleg
from hexaleg.design.chain.checkpoint import StageFiles
from hexaleg.design.codesign.optimal_stage import PARAMETRIC, keep_parametric, kept_parametric
from hexaleg.robot.loaded import Robot


def robots_in(value: object) -> list[Robot]:
    """The robot objects ``value`` refers to, once each."""
    found: dict[int, Robot] = {}

    class Scan(pickle.Pickler):
        def persistent_id(self, obj: object) -> str | None:
            if isinstance(obj, Robot):
                found.setdefault(id(obj), obj)
                return "robot"
            return None

    Scan(io.BytesIO()).dump(value)
    return list(found.values())


def test_the_kept_co_design_is_read_back_with_this_runs_robot(ruled, tmp_path):
    """A co-design whose spring rules carry their own copy of the robot (as they come back from
    their forked child) is kept and read back whole, every robot in it this run's; a run of
    another robot, or with no stages, reads nothing."""
    robot = hexaleg.load()
    theirs = robots_in(ruled)
    assert theirs and all(r is not robot for r in theirs)  # the rules' own robot
    keep_parametric(StageFiles(tmp_path, "k"), ruled, robot)
    assert (tmp_path / f"{PARAMETRIC}.pickle").is_file()
    back = kept_parametric(StageFiles(tmp_path, "k"), robot)
    assert back is not None and robots_in(back) == [robot]
    assert json.dumps(back.to_dict(), default=repr) == json.dumps(ruled.to_dict(), default=repr)
    turned = dataclasses.replace(robot, heading=np.array([0.0, 1.0, 0.0]))
    assert kept_parametric(StageFiles(tmp_path, "k"), turned) is None
    assert kept_parametric(None, robot) is None
    keep_parametric(None, ruled, robot)  # nothing kept, nothing raised
