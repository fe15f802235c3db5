"""docs/motion.md's worked run, pinned: ``walk.csv`` made from a seed (the default gait, five
cycles at 100 Hz, joints quantised like a Dynamixel's encoder after noise, in degrees, time in
ms, with contacts and without a base pose), the page's commands run on it, and every line and
number the page quotes found in what they print and write."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

import hexaleg
from hexaleg.cli import main
from hexaleg.motion.recorded.write import log_columns

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "motion.md"
SEED = 0
"""The seed of the page's log."""
TICK = np.deg2rad(300.0) / 1024
"""A Dynamixel AX/MX position tick, rad (0.29°)."""
CONFIG = '[design]\nfamilies = ["linear", "one_sided", "preloaded"]\n'
"""The page's design config: the [design] families cut to three."""


def walk_log(path: Path, seed: int = SEED, cycles: int = 5) -> Path:
    """The page's ``walk.csv``: the default tripod gait at 100 samples per 1 s cycle, repeated,
    each joint plus Gaussian noise of half a tick rounded to whole ticks, written in degrees
    (2 decimals) with time in ms and the gait's stance as contact switches."""
    robot = hexaleg.load()
    gait = hexaleg.gait(robot, hexaleg.GaitParams(samples=100))
    one = log_columns(robot, gait, derivatives=False)
    rng = np.random.default_rng(seed)
    cols = {"time [ms]": np.arange(cycles * gait.n_samples) * gait.dt * 1e3}
    for name in robot.joint_names:
        q = np.tile(one[name], cycles)
        cols[f"{name} [deg]"] = np.rad2deg(np.round((q + rng.normal(0.0, TICK / 2, q.shape))
                                                    / TICK) * TICK)
    for leg in sorted(robot.leg_names):
        cols[f"contact_{leg}"] = np.tile(one[f"stance_{leg}"], cycles)  # as switches give it
    rows = np.stack(list(cols.values()), axis=1)
    text = [",".join(cols)] + [",".join(f"{v:.2f}" if "[deg]" in k else f"{v:.0f}"
                                        for k, v in zip(cols, r, strict=True)) for r in rows]
    path.write_text("\n".join(text) + "\n", encoding="utf-8")
    return path


def _block(after: str) -> str:
    """The first ```text block of the page after the heading or sentence ``after``."""
    page = PAGE.read_text(encoding="utf-8")
    return page[page.index(after):].split("```text\n", 1)[1].split("```", 1)[0]


def test_the_page_shows_the_head_of_the_log(tmp_path: Path) -> None:
    """The CSV excerpt: the header and first two rows of walk_log, cut after the sixth joint."""
    lines = walk_log(tmp_path / "walk.csv").read_text().splitlines()
    shown = _block("## The log: a worked CSV example").splitlines()
    assert len(shown) == 3
    for mine, theirs in zip(lines[:3], shown, strict=True):
        head, tail = theirs.split(",…,")
        assert mine.startswith(head + ",") and mine.endswith("," + tail)
        assert head.count(",") == 6  # time and six joints


@pytest.fixture(scope="module")
def run(tmp_path_factory: pytest.TempPathFactory) -> dict[str, object]:
    """The page's commands on its log, in a fresh directory: what they print and write."""
    import os

    here = tmp_path_factory.mktemp("walk")
    walk_log(here / "walk.csv")
    (here / "walk.toml").write_text(CONFIG, encoding="utf-8")
    cwd = os.getcwd()
    os.chdir(here)
    try:
        from contextlib import redirect_stdout
        from io import StringIO

        printed = {}
        for name, args in (
                ("design", ["design", "--config", "walk.toml", "--motion", "walk.csv",
                            "--out", "walk-design"]),
                ("simulate", ["simulate", "--motion", "walk.csv", "--springs",
                              "walk-design/design.json", "--out", "walk-sim"])):
            out = StringIO()
            with redirect_stdout(out):
                assert main(args) == 0
            printed[name] = out.getvalue()
        design = json.loads((here / "walk-design" / "design.json").read_text())
        simulate = json.loads((here / "walk-sim" / "simulate.json").read_text())
    finally:
        os.chdir(cwd)
    return {"printed": printed, "design": design, "simulate": simulate}


@pytest.mark.slow  # the page's design run, 25 s: the README suite stays within 5 minutes
def test_the_page_quotes_what_design_prints(run: dict) -> None:
    """The design's answer and its motion: lines, verbatim, in the order printed."""
    printed = run["printed"]["design"].splitlines()
    shown = _block("`hexaleg design --motion walk.csv` on it").splitlines()
    assert shown and all(line in printed for line in shown)
    assert [printed.index(line) for line in shown] == sorted(printed.index(line)
                                                            for line in shown)


def part_sentence(design: dict) -> str:
    """The page's sentence of the parts to buy, from design.json's recommendation."""
    parts = []
    for p in design["recommended"]["parts"]:
        s = p["torsion_spring"]
        parts.append(f"for the {p['group']} {1e3 * s['wire_diameter']['value']:.2f} mm "
                     f"{s['material'].split(',')[0]}, {1e3 * s['outer_diameter']['value']:.2f} "
                     f"mm outer diameter, {s['body_turns']['value']:g} body turns, "
                     f"{s['rate_nmm_per_deg']['value']:.4f} N·mm/deg, preloaded by "
                     f"{s['preload_angle']['value']:.0f}°")
    return "; ".join(parts)


@pytest.mark.slow  # the page's design run, 25 s: the README suite stays within 5 minutes
def test_the_page_names_the_parts_and_the_simulation(run: dict) -> None:
    """The parts of design.json and the figures hexaleg simulate prints (its line also holds
    the wall-time ratio, which the page leaves out)."""
    page = re.sub(r"\s+", " ", PAGE.read_text(encoding="utf-8"))
    assert part_sentence(run["design"]) in page
    line = next(x for x in run["printed"]["simulate"].splitlines() if "predicted saving" in x)
    m = re.search(r"predicted saving (\S+) % .*simulated (\S+) % .*distance (\S+) mm per cycle "
                  r"\(planned (\S+) mm\)", line)
    assert m is not None, line
    assert (f"predicted saving {m[1]} %, simulated {m[2]} %, {m[3]} mm per cycle of the {m[4]} "
            "mm the log walked") in page


def test_the_page_quotes_the_kept_log_of_the_simulated_walk() -> None:
    kept = (ROOT / "analysis" / "logs" / "logged_hexaleg.log").read_text(encoding="utf-8")
    assert _block("## Checked on a log no one here wrote") == kept
