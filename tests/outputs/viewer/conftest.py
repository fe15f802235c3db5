"""Fixtures of the viewer tests: the synthetic walk, its forces and its scene."""

from __future__ import annotations

import numpy as np
import pytest
from meshcat_scene import PERIOD, T, clips, draw, synthetic_forces, synthetic_walk

from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot


@pytest.fixture(scope="session")
def motion(robot: Robot) -> Motion:
    """The synthetic walk (:func:`meshcat_scene.synthetic_walk`)."""
    return synthetic_walk(robot)


@pytest.fixture(scope="session")
def forces(robot: Robot, motion: Motion) -> np.ndarray:
    """Its foot forces (:func:`meshcat_scene.synthetic_forces`)."""
    return synthetic_forces(robot, motion)


@pytest.fixture(scope="session")
def scene(robot: Robot, motion: Motion, forces: np.ndarray) -> list[dict]:
    """The synthetic walk's scene with one keyframe per sample (fps = T / period), joints
    coloured by velocity."""
    return draw(robot, motion, forces=forces, joint_values=motion.v[:, 6:],
                joint_label="joint velocity (rad/s)", fps=T / PERIOD)


@pytest.fixture(scope="session")
def scene_clips(scene: list[dict]) -> dict[str, dict[str, dict]]:
    """The animation tracks of ``scene``."""
    return clips(scene)
