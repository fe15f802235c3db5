"""Robots no one here saw (issues #39, #55): test robots made for the purpose — a biped on point
feet (tests/data/biped), a quadruped with two-joint legs (quad2dof), one with four-joint legs
(quad4dof: redundant, an ankle below the knee), an X-configured quadruped whose front and hind
knees bend opposite ways (xquad), the hexapod facing +y with flipped hips (spider), a humanoid
with a waist and two arms (humanoid), a quadruped on wheels with an arm on its back (wheeled),
a quadruped whose hips turn pitch–roll–yaw (pryquad), a 6-kg hexapod with brushless actuators
(bldc_hexapod) — and a registered quadruped's crawl at duty factor 0.3, through every command:
each ends in a result or a named refusal (exit 2, ``error:`` and what to change), never a
traceback. The outcome of each is pinned, so a robot that starts or stops working is seen.

The quick commands (robot, gait) run in the README's suite; report, design, simulate and codesign
(seconds to a minute or two each) are marked slow and run in .ci/run.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from hexaleg.cli import main

DATA = Path(__file__).resolve().parent / "data"
ROBOTS = {"biped": str(DATA / "biped.toml"), "quad2dof": str(DATA / "quad2dof.toml"),
          "quad4dof": str(DATA / "quad4dof.toml"), "xquad": str(DATA / "xquad.toml"),
          "spider": str(DATA / "spider.toml"), "humanoid": str(DATA / "humanoid.toml"),
          "wheeled": str(DATA / "wheeled.toml"), "pryquad": str(DATA / "pryquad.toml"),
          "bldc_hexapod": str(DATA / "bldc_hexapod.toml"),
          "solo12 crawl": "solo12", "solo12 crawl, grippy": "solo12"}
"""Case → ``--robot``."""
CONFIGS = {
    "solo12 crawl": '[gait]\npattern = "crawl"\nduty_factor = 0.3\n',
    # its one-foot phases need μ ≥ 1.2 and more than the stall torque (docs/gait.md)
    "solo12 crawl, grippy": '[gait]\npattern = "crawl"\nduty_factor = 0.3\nsamples = 200\n'
                            '[contact]\nmu = 1.3\ntorque_limits = false\n',
    # the bound of two-joint legs sways along the body: it needs a short period and grippy feet
    "quad2dof bound": "[gait]\nperiod = 0.6\n[contact]\nmu = 1.0\n",
    "xquad crawl": '[gait]\npattern = "crawl"\n',
    "quad4dof crawl": '[gait]\npattern = "crawl"\n',
}
"""Case → its config file's text (the robot's defaults otherwise)."""
CODESIGN_CONFIGS = {"quad2dof bound": "[contact]\nmu = 1.5\n",
                    "xquad crawl": '[codesign]\npattern = "crawl"\n',
                    "quad4dof crawl": '[codesign]\npattern = "crawl"\n'}
"""Case → its config for codesign, which searches the gait itself (and refuses [gait]: the
solo12 crawl case shows it; its floor is [contact]). The bound's μ is 1.5: codesign plans within
0.7 of the cone (friction_margin), 1.05, what the bound needs (at μ 1.0 the chosen gait needed
0.707 of its 0.7 at the rows' sampling, a named refusal)."""
QUICK = '[gait]\nsamples = 60\n[report]\nstiffness_points = 3\npaper_samples = 8\n'
"""What the report's tests add to a case's config (fewer samples: the suite's time)."""
CASES = {**ROBOTS, "quad2dof bound": ROBOTS["quad2dof"], "xquad crawl": ROBOTS["xquad"],
         "quad4dof crawl": ROBOTS["quad4dof"]}
EXPECTED: dict[str, dict[str, str]] = {
    # a ZMP walking pattern on point feet; it tips over open loop, and with the balance
    # controller (the default on one foot) too: on one point foot for 0.71 s the body is an
    # inverted pendulum (×125 over the stand) no contact force rights; foot placement would
    "biped": {"robot": "ok", "gait": "ok", "report": "ok", "design": "ok",
              "simulate": "stands on one point foot for 0.709 s", "codesign": "ok"},
    "quad2dof": {"robot": "ok", "gait": "ok", "report": "the least friction that admits forces",
                 "design": "the least friction that admits forces",
                 "simulate": "the least friction that admits forces",
                 "codesign": "the least friction that admits forces"},
    # the bound walks in the analysis; open loop it bounced nearly in place, closed loop (the
    # default on two feet) it pitched over while its swing feet kept their footholds; set down
    # by Raibert's placement (#54) it walked backwards (-27 % and -36 % of its stride); with
    # two-joint legs swaying in their planes too it covered its stride (107 %) but its joints
    # missed the plan by 111 mrad RMS with its springs: untracked — at 0.15 ms, where the
    # chatter retry had taken it after its feet lost the ground in 58 % of their stance samples
    # at 0.3 ms. Without the retry it runs at 0.3 ms, inside the contact's bound at its start
    # (foot point 0.061 kg) but not at the bound's lightest sample (0.027 kg; #54, open), and
    # walks backwards again (-27 % and -36 %): stalled
    "quad2dof bound": {"robot": "ok", "gait": "ok", "report": "ok", "design": "ok",
                       "simulate": "springs run stalled", "codesign": "ok"},
    # redundant legs: its similar trot (1.55 s) tipped over open loop, and closed loop its
    # generic servos sat at their stall torque before it fell; its default trot, sized so that
    # its stands on two point feet last ω₀T = 2 (0.56 s, #54), walks closed loop; its crawl walks
    "quad4dof": {"robot": "ok", "gait": "ok", "report": "ok", "design": "ok",
                 "simulate": "ok", "codesign": "ok"},
    "quad4dof crawl": {"robot": "ok", "gait": "ok", "report": "ok", "design": "ok",
                       "simulate": "ok", "codesign": "ok"},
    # its similar trot (2.34 s) tipped over with the balance controller too: on two point feet
    # for 1.17 s, an inverted pendulum across their line (×227); its default trot, sized so
    # that the stands last ω₀T = 2 (0.86 s, #54), walks under both servos
    "xquad": {"robot": "ok", "gait": "ok", "report": "ok", "design": "ok",
              "simulate": "ok", "codesign": "ok"},
    "xquad crawl": {"robot": "ok", "gait": "ok", "report": "ok", "design": "ok",
                    "simulate": "ok", "codesign": "ok"},
    "spider": {"robot": "ok", "gait": "ok", "report": "ok", "design": "ok", "simulate": "ok",
               "codesign": "ok"},
    # issue #55: a waist and arms held at the stand by their own actuators; like the biped, its
    # one-foot gait falls even with the balance controller (#54: no foot placement)
    "humanoid": {"robot": "ok", "gait": "ok", "report": "ok", "design": "ok",
                 "simulate": "stands on one point foot for 0.817 s"},
    # wheels locked, walked on as round feet; its similar trot (1.44 s) ran short; its default
    # trot, sized so that its stands last ω₀T = 2 (0.53 s, #54), walks closed loop
    "wheeled": {"robot": "ok", "gait": "ok", "report": "ok", "design": "ok",
                "simulate": "ok"},
    # a stand found from inside the joint limits; its similar trot (1.44 s) fell with the
    # balance controller running too: on two point feet for 0.72 s (×245); its default trot,
    # sized so that the stands last ω₀T = 2 (0.52 s, #54), walks under both servos
    "pryquad": {"robot": "ok", "gait": "ok", "report": "ok", "design": "ok",
                "simulate": "ok"},
    # issue #55: six legs on Solo-12's brushless modules (2.5 N·m); its design's time and
    # memory are analysis/bench_robots.py's. Co-design's default speed asks a tripod of it,
    # whose middle femur needs 2.85 N·m: a named refusal
    "bldc_hexapod": {"robot": "ok", "gait": "ok", "report": "ok", "design": "ok",
                     "simulate": "ok", "codesign": "a speed the robot's default gait can walk"},
    "solo12 crawl": {"robot": "ok", "gait": "ok", "report": "one point foot's force points",
                     "design": "one point foot's force points",
                     "simulate": "one point foot's force points",
                     "codesign": "[gait]: hexaleg codesign does not read it"},
    "solo12 crawl, grippy": {"robot": "ok", "gait": "ok", "report": "ok", "design": "ok",
                             "simulate": "stalled",
                             "codesign": "[gait]: hexaleg codesign does not read it"},
}
"""Case → command → ``"ok"`` (exit 0) or a phrase of its named refusal (exit 2)."""
SLOW = {"report", "design", "simulate", "codesign"}
"""The commands that take seconds or more a robot: with the slow studies (the reports, 4–14 s
each, took a minute of the README's suite, which a fresh clone ran in 5 min 05 s of its 5)."""
SLOW_PAIRS = {("humanoid", "gait"), ("bldc_hexapod", "gait")}
"""A quick command of issue #55's robots run with the slow ones: the humanoid's walking pattern
is the biped's, whose gait runs in the README's suite; the brushless hexapod's is the spider's
(both six legs found from the tree)."""
IMPLAUSIBLE = {"xquad": {"codesign"}, "xquad crawl": {"report", "design", "codesign"},
               "quad4dof": {"codesign"}}
"""Case → the commands whose generic actuators put the baseline's cost of transport above the
plausible band (12–16 × the animal line), so they warn (issue #40): the X-configured and
four-joint quadrupeds' default trots, sized to hold their stands (#54), are 2.7–2.8 times faster
than the similar ones that warned, and their report and design no longer warn."""


SIMULATED_CODESIGN = {"spider"}
"""The one case whose codesign runs its MuJoCo runs (the finalists' servo check and the chosen
gait's run) and its speed curve on a robot other than the built-in one (whose co-design is
analysis/codesign_hexaleg.py's kept log); the others skip them (30 s of the biped's 57): their
own simulate case runs the simulation, and CI's time is bounded (15 minutes)."""


def _argv(case: str, command: str, tmp_path: Path) -> list[str]:
    argv = [command, "--robot", CASES[case]]
    text = CONFIGS.get(case, "") + (QUICK if command == "report" else "")
    if command == "design":  # one family, no maps, no stop tolerance: CI's time (the full
        # design of the X quadruped is tests/design/chain/test_groups.py's; the tolerance stage
        # is tests/design/search/test_tolerance.py's and the kept logs'; on these robots it was
        # a third to half of each design: 40-140 s, analysis/bench_robots.py), at 100 samples
        # a cycle
        text += ('[design]\nfamilies = ["one_sided"]\nrobustness = false\n'
                 'stop_tolerance = 0\nsamples = 100\n')
    if command == "codesign":
        text = CODESIGN_CONFIGS.get(case, text)
        text += "[codesign]\nmax_evaluations = 10\nsamples = 40\nfinal_samples = 60\n"
        if case not in SIMULATED_CODESIGN:
            text += "[codesign]\nsimulate = false\ncurve = false\n"
        argv.append("--no-rules")
    if command in ("report", "design", "simulate", "codesign"):
        argv += ["--out", str(tmp_path / command)]
    if text and command != "robot":
        config = tmp_path / "case.toml"
        config.write_text(_merge(text))
        argv += ["--config", str(config)]
    return argv


def _merge(text: str) -> str:
    """``text`` with each table's keys together (a TOML table may appear once), a key given
    twice taking its last value."""
    tables: dict[str, dict[str, str]] = {}
    current = ""
    for line in text.splitlines():
        if line.startswith("["):
            current = line
            tables.setdefault(current, {})
        elif line.strip():
            tables[current][line.split("=")[0].strip()] = line
    return "".join(f"{t}\n" + "".join(f"{v}\n" for v in keys.values())
                   for t, keys in tables.items())


UNPINNED = {("humanoid", "codesign"), ("wheeled", "codesign"), ("pryquad", "codesign")}
"""Issue #55's robots' codesign (all three "ok" by hand at this suite's budget: 390, 59 and
133 s on a loaded machine) is left out: the slow suite had reached 893 s of CI's 900."""
PAIRS = [pytest.param(case, c, marks=pytest.mark.slow)
         if c in SLOW or (case, c) in SLOW_PAIRS else (case, c)
         for case in CASES
         for c in ("robot", "gait", "report", "design", "simulate", "codesign")
         if (case, c) not in UNPINNED]


@pytest.mark.parametrize(("case", "command"), PAIRS)
def test_every_command_ends_in_a_result_or_a_named_refusal(case, command, tmp_path, capsys):
    rc = main(_argv(case, command, tmp_path))  # a traceback would raise out of main
    out, err = capsys.readouterr()
    if command in IMPLAUSIBLE.get(case, set()):
        assert "WARNING" in out and "energy implausibly high" in out, out
    expected = EXPECTED[case][command]
    if expected == "ok":
        assert rc == 0, err
    else:
        assert rc == 2 and "error:" in err and "Traceback" not in err, err
        assert expected in err, err


def test_joints_on_no_leg_hold_their_pose_and_their_torque_is_drawn():
    """The humanoid's arms stay at the stand through the gait, their links' inertia is in the
    dynamics (each elbow's motor torque is Pinocchio's RNEA of the whole tree: the feet load no
    arm joint), that torque matches the forearm's weight on its lever at rest (0.08 kg, centre
    4.5 cm from the elbow, the forearm 0.4 rad from vertical), and its own actuator draws
    energy for it (issue #55)."""
    import numpy as np
    import pinocchio as pin

    import hexaleg
    from hexaleg.motion.scaling import robot_gait
    from hexaleg.robot.description import RobotDescription

    desc = RobotDescription.from_toml(ROBOTS["humanoid"])
    robot = desc.load()
    motion = hexaleg.gait(robot, robot_gait(desc).updated({"samples": 60}, "test"))
    analysis = hexaleg.prepare(robot, motion, motor=desc.actuator(robot)).evaluate(
        hexaleg.SpringSet())
    stand = robot.pose("stand")
    model, data = robot.model, robot.model.createData()
    for joint in robot.other_joints:
        col = robot.column(joint)
        np.testing.assert_array_equal(motion.q[:, 7 + col], stand[7 + col])
        rnea = [pin.rnea(model, data, q, v, a)[6 + col]
                for q, v, a in zip(motion.q, motion.v, motion.a, strict=True)]
        np.testing.assert_allclose(analysis.tau_motor[:, col], rnea, rtol=1e-9, atol=1e-12)
    level = stand.copy()
    level[:7] = pin.neutral(model)[:7]
    gravity = pin.computeGeneralizedGravity(model, data, level)
    elbow = 6 + robot.column("L_elbow")
    g = float(np.linalg.norm(model.gravity.linear))
    assert abs(gravity[elbow]) == pytest.approx(0.08 * g * 0.045 * np.sin(0.4), rel=1e-9)
    joints = analysis.metrics["joint_names"]
    electrical = analysis.metrics["joint"]["electrical"][list(joints).index("L_elbow")]
    assert electrical > 0
