"""Tests of hexaleg.studies.view: the scene sent to Meshcat, the offline page, and what a browser
draws.

The scene tests decode the MessagePack commands embedded in the exported page and check them
against Pinocchio's kinematics; the browser tests render the page (and the live server) in
headless Chromium and look at the pixels.
"""

from __future__ import annotations

import base64
import re
import signal
import subprocess
import sys
import urllib.request

import numpy as np
import pinocchio as pin
import pytest
import umsgpack
from browser import chromium, finish, page_requests, start_screenshot
from matplotlib.image import imread

from hexaleg.cli import main
from hexaleg.dynamics.prepare import analyze
from hexaleg.errors import InvalidParameterError, OutputError
from hexaleg.motion.gait import transform_motion, tripod_gait
from hexaleg.motion.trajectory import Motion
from hexaleg.studies.view import N_LEVELS, ViewParams, animate, cool_warm, export_html, value_bins

T = 40
PERIOD = 1.0
DISTANCE = 0.1
AMP = 0.25
TRIPOD_A = ("LF", "LH", "RM")
ARROW = ViewParams().arrow_length


@pytest.fixture(scope="module")
def motion(robot):
    """One 1 s cycle: base walking 0.1 m along x at the stand height, every joint sinusoidal
    about ``stand`` (tripods in antiphase), exact v and a, tripod stance flags."""
    t = np.arange(T) * PERIOD / T
    w = 2 * np.pi / PERIOD
    q = np.tile(robot.pose("stand"), (T, 1))
    v = np.zeros((T, robot.model.nv))
    a = np.zeros_like(v)
    q[:, 0] = DISTANCE * t / PERIOD
    q[:, 2] = -robot.foot_positions(robot.pose("stand"))[:, 2].min()
    v[:, 0] = DISTANCE / PERIOD
    stance = np.zeros((T, len(robot.legs)), dtype=bool)
    for i, leg in enumerate(robot.legs):
        phase = 0.0 if leg.name in TRIPOD_A else np.pi
        for j, (iq, iv) in enumerate(zip(leg.q_index, leg.v_index, strict=True)):
            q[:, iq] += AMP * np.sin(w * t + phase + j)
            v[:, iv] = AMP * w * np.cos(w * t + phase + j)
            a[:, iv] = -AMP * w**2 * np.sin(w * t + phase + j)
        stance[:, i] = (t < PERIOD / 2) == (leg.name in TRIPOD_A)
    feet = np.array([robot.foot_positions(qk) for qk in q])
    return Motion(t=t, q=q, v=v, a=a, stance=stance, feet=feet, period=PERIOD,
                  distance=DISTANCE)


@pytest.fixture(scope="module")
def forces(robot, motion):
    """Weight shared by the stance feet, tilted forward on the left legs so arrows are not all
    vertical."""
    f = np.zeros((T, len(robot.legs), 3))
    f[..., 2] = np.where(motion.stance, robot.mass * 9.81 / 3, 0.0)
    left = [i for i, leg in enumerate(robot.legs) if leg.name.startswith("L")]
    f[:, left, 0] = 0.5 * f[:, left, 2]
    return f


def _scene(page: str) -> list[dict]:
    """The Meshcat commands embedded in an exported page, decoded, in order."""
    block = re.search(r"var commands = \[(.*?)\];", page, re.S).group(1)
    return [umsgpack.unpackb(base64.b64decode(s)) for s in re.findall(r'"([A-Za-z0-9+/=]+)"',
                                                                       block)]


def _clips(commands: list[dict]) -> dict[str, dict[str, dict]]:
    """path → track name → {"frames": [...], "values": [...]} of the (single) animation."""
    anims = [c for c in commands if c["type"] == "set_animation"]
    assert len(anims) == 1
    out = {}
    for a in anims[0]["animations"]:
        tracks = {}
        for tr in a["clip"]["tracks"]:
            tracks[tr["name"].lstrip(".")] = {"frames": [k["time"] for k in tr["keys"]],
                                               "values": [k["value"] for k in tr["keys"]]}
        out[a["path"]] = tracks
    return out


def _at(track: dict, frame: float):
    """Value of a discrete (step) track at ``frame``."""
    i = np.searchsorted(track["frames"], frame, side="right") - 1
    return track["values"][i]


@pytest.fixture(scope="module")
def page(robot, motion, forces, tmp_path_factory):
    """Page of the synthetic motion with one keyframe per sample (fps = T / period)."""
    path = tmp_path_factory.mktemp("view") / "walk.html"
    export_html(robot, motion, path, forces=forces, joint_values=motion.v[:, 6:],
                joint_label="joint velocity (rad/s)", fps=T / PERIOD)
    return path.read_text()


@pytest.fixture(scope="module")
def clips(page):
    return _clips(_scene(page))


# --------------------------------------------------------------------------- colour scale


def test_cool_warm_anchors_and_symmetry():
    np.testing.assert_allclose(cool_warm(np.array([0.0, 0.5, 1.0])),
                               [[0.230, 0.299, 0.754], [0.865, 0.865, 0.865],
                                [0.706, 0.016, 0.150]])
    x = np.linspace(0, 0.5, 11)
    # Blue fades into grey on the way up: red channel rises monotonically, blue falls after grey.
    assert np.all(np.diff(cool_warm(x)[:, 0]) > 0)
    assert np.all(np.diff(cool_warm(0.5 + x)[:, 2]) < 0)


def test_value_bins_symmetric_and_edges():
    vmax = 2.0
    v = np.linspace(-vmax, vmax, 1001)
    b = value_bins(v, vmax)
    assert b[0] == 0 and b[-1] == N_LEVELS - 1
    assert value_bins(0.0, vmax) == N_LEVELS // 2
    assert np.all(np.diff(b) >= 0)
    # Away from bin edges, bin(−v) mirrors bin(v).
    inner = np.abs(((v + vmax) / (2 * vmax) * N_LEVELS) % 1 - 0.5) < 0.45
    np.testing.assert_array_equal(value_bins(-v[inner], vmax), N_LEVELS - 1 - b[inner])
    np.testing.assert_array_equal(value_bins(v, 0.0), N_LEVELS // 2)


# --------------------------------------------------------------------------- the exported scene


def test_page_is_self_contained(page):
    assert "<script src" not in page and "<link" not in page
    assert "MeshCat.Viewer" in page  # the viewer's JavaScript is inlined
    urls = set(re.findall(r"https?://[^\s\"'<>)]+", page))
    # The only URLs are XML namespace names inside the inlined JavaScript, never fetched.
    assert urls <= {"http://www.w3.org/1999/xhtml"}, urls


def test_visual_geometry_follows_the_motion(robot, motion, clips):
    """Keyframe k of every visual's position/quaternion track is its placement at sample k
    (fps = sample rate), and the closing keyframe returns to sample 0 shifted by the stride."""
    data, gdata = robot.model.createData(), pin.GeometryData(robot.visual_model)
    for k in (0, 7, T - 1):
        pin.forwardKinematics(robot.model, data, motion.q[k])
        pin.updateGeometryPlacements(robot.model, data, robot.visual_model, gdata)
        for g, obj in enumerate(robot.visual_model.geometryObjects):
            tr = clips[f"/meshcat/pinocchio/visuals/{obj.name}"]
            assert tr["position"]["frames"][k] == pytest.approx(k)
            np.testing.assert_allclose(tr["position"]["values"][k], gdata.oMg[g].translation,
                                       atol=1e-12)
            quat = pin.Quaternion(np.array(tr["quaternion"]["values"][k]))
            np.testing.assert_allclose(quat.toRotationMatrix(), gdata.oMg[g].rotation,
                                       atol=1e-12)
    body = clips["/meshcat/pinocchio/visuals/body_0"]["position"]
    assert len(body["frames"]) == T + 1 and body["frames"][-1] == pytest.approx(T)
    np.testing.assert_allclose(np.subtract(body["values"][-1], body["values"][0]),
                               [DISTANCE, 0, 0], atol=1e-12)


def test_resampling_interpolates_between_samples(robot, motion, tmp_path):
    """At twice the sample rate, odd keyframes are midway (on SE(3) × joint angles) between
    neighbouring samples: the foot sphere sits where it is at pin.interpolate's midpoint."""
    path = export_html(robot, motion, tmp_path / "x.html", fps=2 * T / PERIOD)
    clips = _clips(_scene(path.read_text()))
    foot = clips["/meshcat/pinocchio/visuals/LF_foot_0"]["position"]
    assert len(foot["frames"]) == 2 * T + 1
    g = robot.visual_model.getGeometryId("LF_foot_0")
    data, gdata = robot.model.createData(), pin.GeometryData(robot.visual_model)
    for k in (0, 11, T - 2):
        q_mid = pin.interpolate(robot.model, motion.q[k], motion.q[k + 1], 0.5)
        pin.forwardKinematics(robot.model, data, q_mid)
        pin.updateGeometryPlacements(robot.model, data, robot.visual_model, gdata)
        np.testing.assert_allclose(foot["values"][2 * k + 1], gdata.oMg[g].translation,
                                   atol=1e-12)
        # ... which is not the average of the neighbouring keyframes' positions (the legs
        # rotate), so this checks interpolation in configuration space.
        assert np.linalg.norm(np.add(foot["values"][2 * k], foot["values"][2 * k + 2]) / 2
                              - gdata.oMg[g].translation) > 1e-5


def test_force_arrows_point_along_the_forces(robot, motion, forces, clips):
    mags = np.linalg.norm(forces, axis=-1)
    fmax = mags.max()
    for i, leg in enumerate(robot.legs):
        node = f"/meshcat/forces/{leg.name}"
        tr = clips[node]
        head = clips[node + "/head"]["position"]["values"]
        for k in (0, T // 2 + 3):
            visible = _at(tr["visible"], k)
            assert visible == bool(motion.stance[k, i])
            if not visible:
                continue
            np.testing.assert_allclose(tr["position"]["values"][k],
                                       robot.foot_positions(motion.q[k])[i], atol=1e-12)
            R = pin.Quaternion(np.array(tr["quaternion"]["values"][k])).toRotationMatrix()
            # The arrow's axis is its local +y (three.js convention).
            np.testing.assert_allclose(R[:, 1], forces[k, i] / mags[k, i], atol=1e-12)
            length = ARROW * mags[k, i] / fmax
            shaft = clips[node + "/shaft"]
            assert shaft["scale"]["values"][k][1] == pytest.approx(length)
            assert shaft["position"]["values"][k][1] == pytest.approx(length / 2)
            assert head[k][1] > length


def test_joint_markers_show_one_binned_colour(robot, motion, clips):
    values = motion.v[:, 6:]
    bins = value_bins(values, np.abs(values).max())
    data = robot.model.createData()
    for k in (0, 13, T - 1):
        pin.forwardKinematics(robot.model, data, motion.q[k])
        for c, name in enumerate(robot.joint_names):
            node = f"/meshcat/joint_values/{name}"
            np.testing.assert_allclose(clips[node]["position"]["values"][k],
                                       data.oMi[robot.model.getJointId(name)].translation,
                                       atol=1e-12)
            shown = [b for b in range(N_LEVELS) if _at(clips[f"{node}/bin{b}"]["visible"], k)]
            assert shown == [bins[k, c]]


def test_legend_names_the_scales(page, robot, forces):
    assert "joint velocity (rad/s)" in page
    fmax = np.linalg.norm(forces, axis=-1).max()
    assert f"{ARROW * 100:.3g} cm = {fmax:.3g} N" in page


def test_real_gait_arrows_are_the_analysis_forces(robot, tmp_path):
    """Tripod gait with the analysis' foot forces (30 keyframes/s between 1000 samples/s): each
    arrow, read back as direction × length / arrow_length × max|f|, is the force linearly
    interpolated at the keyframe time, and the stance feet carry the weight (Σ f_z ≈ m g, up
    to the CoM's vertical acceleration)."""
    gait = tripod_gait(robot)
    result = analyze(robot, gait)
    path = export_html(robot, gait, tmp_path / "gait.html", forces=result.forces,
                       joint_values=result.power, joint_label="motor power (W)")
    clips = _clips(_scene(path.read_text()))
    fmax = np.linalg.norm(result.forces, axis=-1).max()
    frames = clips["/meshcat/forces/LF/shaft"]["scale"]["frames"]
    assert frames[-1] == pytest.approx(30 * gait.period)
    t_ext = np.append(gait.t, gait.period)
    for j in (0, 9, 21):
        t = frames[j] / 30.0
        total = np.zeros(3)
        for i, leg in enumerate(robot.legs):
            node = f"/meshcat/forces/{leg.name}"
            expected = [np.interp(t, t_ext, np.append(result.forces[:, i, c],
                                                      result.forces[0, i, c]))
                        for c in range(3)]
            if not _at(clips[node]["visible"], j):
                assert np.linalg.norm(expected) < 1e-6 * fmax
                continue
            R = pin.Quaternion(np.array(clips[node]["quaternion"]["values"][j]))
            length = clips[node + "/shaft"]["scale"]["values"][j][1]
            drawn = R.toRotationMatrix()[:, 1] * length / ARROW * fmax
            np.testing.assert_allclose(drawn, expected, atol=1e-9 * fmax)
            total += drawn
        assert total[2] == pytest.approx(robot.mass * 9.81, rel=0.1)


def test_transformation_ends_in_the_sphere_pose(robot, tmp_path):
    """A non-periodic motion (stand → sphere, 2 s) has keyframes up to its last sample, where
    the body shells sit as in the SRDF ``sphere`` pose (the body resting on the ground)."""
    motion = transform_motion(robot)
    path = export_html(robot, motion, tmp_path / "t.html", fps=10)
    clips = _clips(_scene(path.read_text()))
    q_end = robot.pose("sphere")
    q_end[:3] = motion.q[-1, :3]
    data, gdata = robot.model.createData(), pin.GeometryData(robot.visual_model)
    pin.forwardKinematics(robot.model, data, q_end)
    pin.updateGeometryPlacements(robot.model, data, robot.visual_model, gdata)
    for g, obj in enumerate(robot.visual_model.geometryObjects):
        tr = clips[f"/meshcat/pinocchio/visuals/{obj.name}"]["position"]
        assert len(tr["frames"]) == 21 and tr["frames"][-1] == pytest.approx(20)
        np.testing.assert_allclose(tr["values"][-1], gdata.oMg[g].translation, atol=1e-9)


def test_single_pose_is_drawn_without_animation(robot, tmp_path):
    """One sample: no animation, the scene is set to the pose (scale 1 from the URDF)."""
    q = robot.pose("stand")
    motion = Motion(t=np.zeros(1), q=q[None], v=np.zeros((1, robot.model.nv)),
                    a=np.zeros((1, robot.model.nv)), stance=np.ones((1, 6), dtype=bool),
                    feet=robot.foot_positions(q)[None], period=1.0, periodic=False)
    commands = _scene(export_html(robot, motion, tmp_path / "p.html").read_text())
    assert not [c for c in commands if c["type"] == "set_animation"]
    last = {c["path"]: c["matrix"] for c in commands if c["type"] == "set_transform"}
    M = np.array(last["/meshcat/pinocchio/visuals/LF_foot_0"]).reshape(4, 4).T
    data, gdata = robot.model.createData(), pin.GeometryData(robot.visual_model)
    pin.forwardKinematics(robot.model, data, q)
    pin.updateGeometryPlacements(robot.model, data, robot.visual_model, gdata)
    np.testing.assert_allclose(M, gdata.oMg[robot.visual_model.getGeometryId("LF_foot_0")]
                               .homogeneous, atol=1e-12)


# --------------------------------------------------------------------------- bad input


def test_wrong_shapes_name_the_expected_shape(robot, motion, tmp_path):
    with pytest.raises(InvalidParameterError, match=r"\(40, 6, 3\)"):
        export_html(robot, motion, tmp_path / "x.html", forces=np.zeros((T, 6)))
    with pytest.raises(InvalidParameterError, match=r"\(40, 18\)"):
        export_html(robot, motion, tmp_path / "x.html", joint_values=np.zeros((T - 1, 18)))
    bad = np.zeros((T, 18))
    bad[5, 3] = np.nan
    with pytest.raises(InvalidParameterError, match="sample 5"):
        export_html(robot, motion, tmp_path / "x.html", joint_values=bad)
    with pytest.raises(InvalidParameterError, match="fps"):
        export_html(robot, motion, tmp_path / "x.html", fps=0)
    other = Motion(t=motion.t, q=motion.q[:, :-3], v=motion.v[:, :-3], a=motion.a[:, :-3],
                   stance=motion.stance, feet=motion.feet, period=PERIOD)
    with pytest.raises(InvalidParameterError, match=r"q \(T, 25\) and v \(T, 24\)"):
        export_html(robot, other, tmp_path / "x.html")
    with pytest.raises(InvalidParameterError, match="viewer"):
        animate(robot, motion, viewer="http://localhost:7000")


def test_unwritable_path_is_output_error(robot, motion, tmp_path):
    for path in (tmp_path / "missing" / "x.html", tmp_path):
        with pytest.raises(OutputError, match=re.escape(str(path))):
            export_html(robot, motion, path)


def test_view_params_validate():
    assert ViewParams().fps == 30.0
    with pytest.raises(InvalidParameterError, match="arrow_length"):
        ViewParams(arrow_length=-0.1)
    with pytest.raises(InvalidParameterError, match="fps"):
        ViewParams(fps=True)


# --------------------------------------------------------------------------- command line


def test_cli_writes_page_with_config(tmp_path, capsys):
    config = tmp_path / "view.toml"
    config.write_text("[gait]\nperiod = 0.5\nsamples = 200\n\n[view]\nfps = 12\n")
    out = tmp_path / "gait.html"
    assert main(["view", "--config", str(config), "--html", str(out)]) == 0
    assert capsys.readouterr().out.strip() == f"wrote {out}"
    page = out.read_text()
    assert "motor power (W)" in page
    frames = _clips(_scene(page))["/meshcat/pinocchio/visuals/body_0"]["position"]["frames"]
    assert frames[-1] == pytest.approx(12 * 0.5)  # one 0.5 s cycle at 12 keyframes/s


def test_cli_errors_are_one_line(tmp_path, capsys):
    config = tmp_path / "bad.toml"
    config.write_text("[view]\nframes_per_second = 12\n")
    assert main(["view", "--config", str(config), "--html", str(tmp_path / "x.html")]) == 2
    err = capsys.readouterr().err
    assert "frames_per_second" in err and "fps" in err and "Traceback" not in err
    assert main(["view", "--motion", "transform", "--html",
                 str(tmp_path / "no" / "x.html")]) == 2
    assert str(tmp_path / "no" / "x.html") in capsys.readouterr().err


# --------------------------------------------------------------------------- in the browser

SHOT = (400, 300)
"""Screenshot size, px (small: SwiftShader renders on the CPU)."""
LEGEND = 60
"""Height of the strip at the bottom of a screenshot that holds the legend, px."""
needs_chromium = pytest.mark.skipif(chromium() is None,
                                    reason="chromium not on PATH (apt-get install chromium)")


def _orange(img: np.ndarray) -> np.ndarray:
    """Pixels of the shell's orange (URDF rgba 0.85 0.55 0.15) under any lighting."""
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    return (r > 0.45) & (r - b > 0.35) & (g > 0.35 * r) & (g < 0.85 * r)


def _red(img: np.ndarray) -> np.ndarray:
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    return (r > 0.45) & (g < 0.55 * r) & (b < 0.6 * r) & ~_orange(img)


def _blue(img: np.ndarray) -> np.ndarray:
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    return (b > 0.45) & (r < 0.8 * b) & (g < 0.85 * b)


def _green(img: np.ndarray) -> np.ndarray:
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    return (g > 0.35) & (r < 0.6 * g) & (b < 0.6 * g)


@pytest.fixture(scope="module")
def session(tmp_path_factory):
    """``hexaleg view`` (gait, joints coloured by motor torque) served by a CLI subprocess and
    written with ``--html`` by the same command in-process; the page rendered at 0.6 s (with a
    network log) and the live server at 0.9 s of the 1 s cycle; then Ctrl-C for the server."""
    d = tmp_path_factory.mktemp("session")
    cmd = ["view", "--joints", "torque"]
    proc = subprocess.Popen([sys.executable, "-m", "hexaleg.cli", *cmd], stdout=subprocess.PIPE,
                            text=True)
    out = {}
    try:
        assert main([*cmd, "--html", str(d / "page.html")]) == 0
        if chromium() is not None:
            finish(start_screenshot((d / "page.html").as_uri(), d / "static.png", size=SHOT,
                                    virtual_time_ms=600, net_log=d / "net.json"))
            out.update(static=imread(d / "static.png")[..., :3], net=d / "net.json")
        out["line"] = proc.stdout.readline()
        url = re.search(r"http://127\.0\.0\.1:\d+/static/", out["line"]).group(0)
        with urllib.request.urlopen(url, timeout=10) as r:
            out["index"] = r.read()
        if chromium() is not None:
            # The browser connects after the scene was sent: the server replays it.
            finish(start_screenshot(url, d / "served.png", size=SHOT, virtual_time_ms=900))
            out["served"] = imread(d / "served.png")[..., :3]
        proc.send_signal(signal.SIGINT)
        out["returncode"] = proc.wait(timeout=20)
        try:
            urllib.request.urlopen(url, timeout=5)
            out["server_gone"] = False
        except OSError:
            out["server_gone"] = True
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    return out


def test_cli_serves_on_localhost_until_interrupted(session):
    assert session["line"].startswith("serving the gait at http://127.0.0.1:")
    assert b"MeshCat" in session["index"]
    assert session["returncode"] == 0  # Ctrl-C is a normal exit ...
    assert session["server_gone"]  # ... that also stops the meshcat server


@needs_chromium
@pytest.mark.parametrize("which", ["static", "served"])
def test_browser_draws_robot_arrows_and_joint_colours(session, which):
    img = session[which].copy()
    assert img.shape[:2] == SHOT[::-1]
    img[-LEGEND:] = 1.0  # the static page's legend has red and blue swatches too
    n = img.shape[0] * img.shape[1]
    assert _orange(img).sum() > 0.005 * n  # the shell, ≈ 1.5 % of the picture
    # Joint markers at both ends of the colour scale, and force arrows.
    assert _red(img).sum() > 1e-4 * n and _blue(img).sum() > 1e-4 * n
    assert _green(img).sum() > 5e-5 * n
    assert img.std() > 0.1  # not a blank canvas


@needs_chromium
def test_browser_plays_the_animation(session):
    """Same scene and camera 0.3 s apart: the robot has moved (the legend strip is masked)."""
    a, b = session["static"].copy(), session["served"].copy()
    a[-LEGEND:] = b[-LEGEND:] = 0
    moved = np.abs(a - b).max(axis=-1) > 0.1
    assert moved.sum() > 0.002 * moved.size


@needs_chromium
def test_browser_page_fetches_nothing(session):
    assert page_requests(session["net"]) == []
