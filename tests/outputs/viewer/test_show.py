"""Tests of hexaleg.outputs.viewer.show: the drawing parameters are checked, and what is shown
is the motion's analysis (its forces as arrows, the chosen joint quantity as colours)."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.design.rules import paper_style_springs
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.prepare import analyze
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.outputs.viewer.show import ViewParams, animate, export_html, view_motion
from hexaleg.robot.catalogue import DEFAULT_MOTOR, motor


def test_view_params_validate():
    assert ViewParams().fps == 30.0
    with pytest.raises(InvalidParameterError, match="arrow_length"):
        ViewParams(arrow_length=-0.1)
    with pytest.raises(InvalidParameterError, match="fps"):
        ViewParams(fps=True)


def test_drawing_parameters_and_viewer_are_checked(robot, walk200, tmp_path):
    with pytest.raises(InvalidParameterError, match="fps"):
        export_html(robot, walk200, tmp_path / "x.html", fps=0)
    with pytest.raises(InvalidParameterError, match="viewer"):
        animate(robot, walk200, viewer="http://localhost:7000")


def test_view_motion_is_the_motions_analysis(robot, walk200):
    """The motion analysed with its springs, servos and contact; the joints coloured by the
    chosen quantity, the feet's forces the analysis' own."""
    springs = paper_style_springs(robot, walk200, "femur")
    servo, contact = motor(DEFAULT_MOTOR), ContactParams(mu=0.5)
    shown = view_motion(robot, walk200, springs, servo, joints="spring", contact=contact)
    result = analyze(robot, walk200, springs, motor=servo, objective="joule", contact=contact)
    assert shown.motion is walk200 and shown.joint_label == "spring torque (N·m)"
    np.testing.assert_array_equal(shown.joint_values, result.tau_spring)
    np.testing.assert_array_equal(shown.forces, result.forces)
    power = view_motion(robot, walk200, springs, servo, contact=contact)
    np.testing.assert_array_equal(power.joint_values, result.power)
    with pytest.raises(UnknownNameError, match="power, spring, torque"):
        view_motion(robot, walk200, springs, servo, joints="current")
