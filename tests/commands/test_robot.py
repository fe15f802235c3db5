"""Tests of hexaleg.commands.robot: ``hexaleg robot`` prints the model's summary and its sanity
checks' findings as warnings (and ``hexaleg gait`` the same findings of its robot)."""

from __future__ import annotations

from hexaleg.cli import main


def test_robot_summary(capsys):
    assert main(["robot"]) == 0
    out = capsys.readouterr().out
    assert "nq = 25, nv = 24, actuated joints = 18" in out
    assert "LF_femur" in out


def test_robot_and_gait_print_the_sanity_checks(tmp_path, capsys):
    """A URDF whose coxa link has a 0.5 m radius of gyration gets a warning naming the link;
    the built-in robot gets none."""
    import xml.etree.ElementTree as ET

    from hexaleg.robot.model import DEFAULT_SRDF, DEFAULT_URDF

    tree = ET.parse(DEFAULT_URDF)
    link = next(e for e in tree.getroot().iter("link") if e.get("name") == "LF_coxa_link")
    inertia = link.find("inertial/inertia")
    assert inertia is not None
    for key in ("ixx", "iyy", "izz"):
        inertia.set(key, "0.01")
    tree.write(tmp_path / "heavy.urdf")
    assert main(["robot", "--urdf", str(tmp_path / "heavy.urdf"), "--srdf",
                 str(DEFAULT_SRDF)]) == 0
    out = capsys.readouterr().out
    assert "warning: radius_of_gyration: link LF_coxa_link" in out
    assert main(["robot"]) == 0 and "warning" not in capsys.readouterr().out
    assert main(["gait"]) == 0 and "warning" not in capsys.readouterr().out
