"""Tests of hexaleg.paper.summary: the Markdown summary, a line per claim of the paper."""

from __future__ import annotations

from hexaleg.paper.metrics import JOINT_METRICS
from hexaleg.paper.summary import markdown_summary


def test_one_row_per_claim_and_per_metric(paper_result):
    text = markdown_summary(paper_result, ["fig05_rigid_torque.png"])
    lines = text.splitlines()
    assert lines[0] == "# hexaleg paper: the single elastic joint, reproduced"
    assert "| eq. 19, §4.2 | k_M = 713.547 N·mm/deg | 713.544 eq. 19 units" in text
    assert "| §4.2 | k_E = 784.717 |" in text and "| §4.2 | up to 52.81% energy saved |" in text
    for m in JOINT_METRICS:
        assert sum(line.startswith(f"| {m} | ") for line in lines) == 1, m
    assert lines[-1] == "Figures: fig05_rigid_torque.png"


def test_the_forward_optimum_table(paper_result, forward):
    """With ``simulation``, summary.md gets the optimum table (a row per model and the paper's
    readings, a column per metric), the unit question and a row per required torque; the one-line
    verdict names the forward mean-torque optimum."""
    from hexaleg.paper.reproduce import simulation_section
    from hexaleg.paper.summary import one_line

    r = {**paper_result, "simulation": simulation_section(forward)}
    text = markdown_summary(r, [])
    mean, eps = forward.optima["mean_abs"], forward.optima["epsilon"]
    assert "## The Adams experiment forward (MuJoCo)" in text
    assert (f"| analytic (closed form) | {mean.closed_form:.1f} ({100 * mean.saving[0]:.1f} %) | "
            f"{eps.closed_form:.1f} ({100 * eps.saving[0]:.1f} %) |") in text
    assert (f"| forward simulation | {mean.simulated:.0f} ({100 * mean.saving[1]:.1f} %) | "
            f"{eps.simulated:.0f} ({100 * eps.saving[1]:.1f} %) |") in text
    assert (f"| forward simulation with Table 2 friction | {mean.friction:.0f} "
            f"({100 * mean.saving[2]:.1f} %) | {eps.friction:.0f} ({100 * eps.saving[2]:.1f} %, "
            "grid end: not bracketed) |") in text
    assert "| the paper's Adams reading | 740 | 800 |" in text
    assert "| eq. 19 k_M, printed k_E | 713.547 | 784.717 |" in text
    assert "| the paper's reading taken as N·mm/deg | 42.40 N·m/rad = " in text
    assert "Unit question: The paper labels its stiffnesses N·mm/deg" in text
    assert sum(line.startswith(("| rigid |", "| Table 4, 400 |", "| k_M 713.5 |", "| 740 |"))
               for line in text.splitlines()) == 4
    assert f"forward (MuJoCo) mean-torque optimum: {mean.simulated:.0f}" in one_line(r)
    assert "forward" not in one_line(paper_result) and "MuJoCo" not in markdown_summary(
        paper_result, [])
