"""``hexaleg view --simulation``: a run of ``hexaleg simulate`` replayed through the viewer's own
drawing path — the keyframes are the simulated steps, the arrows sit on MuJoCo's feet, bad input
is named, and a browser draws it."""

from __future__ import annotations

import dataclasses
import re
import signal
import subprocess
import sys
import urllib.request
from pathlib import Path

import numpy as np
import pytest
from browser import chromium, finish, start_screenshot
from matplotlib.image import imread
from meshcat_scene import at, clips, draw, page_commands

from hexaleg.cli import main
from hexaleg.errors import InvalidParameterError
from hexaleg.outputs.viewer.colours import N_LEVELS, value_bins
from hexaleg.outputs.viewer.keyframes import resample
from hexaleg.outputs.viewer.show import replay_motion
from hexaleg.simulation.motion_file import FILES, read_motion, write_motion, write_motions

SPIDER = Path(__file__).resolve().parents[2] / "data" / "spider.toml"
"""The test hexapod's description (tests/conftest.py)."""


@pytest.fixture(scope="module")
def out(feedforward, tmp_path_factory):
    """The short feedforward simulation's motion files (3 cycles of 1 s, 100 rows per s)."""
    d = tmp_path_factory.mktemp("replay")
    write_motions(d, feedforward)
    return d


def test_keyframes_are_the_simulated_steps(feedforward, out):
    """At 50 keyframes per second keyframe j is simulation step 40 j (and a last one at the last
    row, step 5980 at 2.99 s): its configuration is the run's (MuJoCo's qpos mapped), the arrows
    stand on MuJoCo's foot sites where a contact force was recorded, the joint colours are the
    binned motor torques."""
    run = feedforward.with_springs
    traj, joints = run.trajectory, run.sim.joints
    shown = replay_motion(out, "springs", "torque")
    assert shown.joint_label == "simulated motor torque (N·m)"
    fr = resample(shown.robot, shown.motion, 50.0, shown.forces, shown.joint_values)
    steps = np.r_[np.arange(150) * 40, 5980]
    assert traj.n == 6000
    np.testing.assert_allclose(fr.frames, np.r_[np.arange(150), 149.5], atol=1e-9)
    q, _ = joints.to_pinocchio(traj.qpos[steps], traj.qvel[steps])
    np.testing.assert_allclose(fr.q, q, atol=1e-12)
    scene = clips(draw(shown.robot, shown.motion, forces=shown.forces,
                       joint_values=shown.joint_values, fps=50.0))
    bins = value_bins(traj.tau_motor[steps], np.abs(shown.joint_values).max())
    recorded = read_motion(out / FILES["springs"])
    for j in (0, 37, 150):
        for i, leg in enumerate(shown.robot.legs):
            arrow = scene[f"/meshcat/forces/{leg.name}"]
            np.testing.assert_allclose(arrow["position"]["values"][j], traj.feet[steps[j], i],
                                       atol=1e-12)
            f = recorded.forces[steps[j] // 20, i]
            assert at(arrow["visible"], j) == bool(np.linalg.norm(f) > 0)
        for c, name in enumerate(shown.robot.joint_names):
            lit = [b for b in range(N_LEVELS)
                   if at(scene[f"/meshcat/joint_values/{name}/bin{b}"]["visible"], j)]
            assert lit == [bins[j, c]]


def test_the_default_rate_spans_the_run(out):
    """30 keyframes per second over the 2.99 s of rows, the browser interpolating between."""
    shown = replay_motion(out, "baseline", "spring")
    assert shown.joint_label == "simulated spring torque (N·m)"
    assert not shown.joint_values.any()  # no springs in the baseline
    fr = resample(shown.robot, shown.motion, 30.0, None, None)
    assert fr.frames[-1] == pytest.approx(30 * 2.99) and len(fr.frames) == 91


def test_bad_input_is_named(out, tmp_path, capsys):
    page = str(tmp_path / "x.html")
    cases = [
        (["--simulation", str(out), "--motion", "transform"], ["'transform'", "simulation"]),
        (["--run", "baseline"], ["'baseline'", "--simulation"]),
        (["--simulation", str(tmp_path)], [str(tmp_path), "motion-springs.npz"]),
        (["--simulation", str(out), "--robot", str(SPIDER)],
         ["robot = 'hexaleg'", "'spider'"]),
    ]
    for args, names in cases:
        assert main(["view", *args, "--html", page]) == 2, args
        err = capsys.readouterr().err
        assert err.startswith("hexaleg view: error: ") and all(n in err for n in names), err
    with pytest.raises(SystemExit):
        main(["view", "--simulation", str(out), "--run", "with_springs"])
    assert "'with_springs' (choose from 'springs', 'baseline')" in capsys.readouterr().err


def test_an_unregistered_robot_needs_its_description(out, tmp_path):
    recorded = read_motion(out / FILES["springs"])
    write_motion(tmp_path / FILES["springs"], dataclasses.replace(recorded, robot="my_robot"))
    with pytest.raises(InvalidParameterError, match=r"robot = 'my_robot'.*--robot FILE\.toml"):
        replay_motion(tmp_path)


def _orange(img: np.ndarray) -> np.ndarray:
    """The shell's orange (as tests/commands/test_view.py)."""
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    return (r > 0.45) & (r - b > 0.35) & (g > 0.35 * r) & (g < 0.85 * r)


def test_served_and_offline(out, tmp_path):
    """``hexaleg view --simulation`` serves (its URL answers, Ctrl-C stops it) and ``--html``
    writes a page headless Chromium draws the robot and its force arrows on."""
    cmd = ["view", "--simulation", str(out)]
    proc = subprocess.Popen([sys.executable, "-m", "hexaleg.cli", *cmd], stdout=subprocess.PIPE,
                            text=True)
    try:
        page = tmp_path / "replay.html"
        assert main([*cmd, "--html", str(page)]) == 0
        line = proc.stdout.readline()
        assert line.startswith(f"serving the springs run of {out} at http://127.0.0.1:")
        url = re.search(r"http://127\.0\.0\.1:\d+/", line).group(0)
        with urllib.request.urlopen(url, timeout=10) as r:
            assert b"MeshCat" in r.read()
        proc.send_signal(signal.SIGINT)
        assert proc.wait(timeout=20) == 0
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    text = page.read_text()
    assert "simulated motor power (W)" in text
    assert "/meshcat/forces/LF" in clips(page_commands(text))
    if chromium() is None:
        pytest.skip("chromium not on PATH (apt-get install chromium)")
    finish(start_screenshot(page.as_uri(), tmp_path / "shot.png", size=(400, 300),
                            virtual_time_ms=600))
    img = imread(tmp_path / "shot.png")[..., :3]
    img[-60:] = 1.0  # the legend
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    assert _orange(img).sum() > 0.003 * r.size  # the shell (smaller: the camera sees the travel)
    assert ((g > 0.35) & (r < 0.6 * g) & (b < 0.6 * g)).sum() > 5e-5 * r.size  # arrows
