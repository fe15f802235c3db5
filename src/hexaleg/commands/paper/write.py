"""The paper study's files (``hexaleg paper``): ``paper.json``, the Figs 5–13 analogues,
the forward rerun of the Adams experiment beside them, and ``summary.md``."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from hexaleg.errors import InvalidParameterError
from hexaleg.outputs.directory import OutputFolder
from hexaleg.outputs.paper_figures import save_png
from hexaleg.paper.figures import forward_figures, make_figures
from hexaleg.paper.forward import (
    K_GRID,
    adams_model,
    forward_study,
    max_stiffness,
    stiffness_grid,
)
from hexaleg.paper.joint import PaperJoint
from hexaleg.paper.metrics import paper_samples
from hexaleg.paper.reproduce import reproduce, simulation_section
from hexaleg.paper.summary import markdown_summary
from hexaleg.quantities import file_data, json_text


def write_paper(out: str | Path, joint: PaperJoint | None = None, n: int = 8192,
                simulation: bool = True, grid: Sequence[float] | None = None) -> dict:
    """Write ``paper.json``, the Fig. 5–13 analogues (PNG) and ``summary.md`` into ``out``.

    Args:
        out: Output directory (created if missing).
        joint: The joint (default :class:`PaperJoint`).
        n: Samples per period.
        simulation: Rerun the paper's Adams experiment forward
            (:func:`~hexaleg.paper.forward.forward_study`): ``paper.json`` gets its
            ``simulation`` section, the figures ``sim_fig*``, the summary its optimum table.
        grid: Stiffnesses of the forward run, eq. 19 units (1e-6 N·m/rad); default
            :data:`~hexaleg.paper.forward.K_GRID`.

    Returns:
        The content of ``paper.json``.

    Raises:
        InvalidParameterError: ``n`` out of range, a bad ``grid`` or a grid without the
            simulation (before anything is written).
        OutputError: the directory or a file cannot be written (the directory is then as it
            was).
        DirectoryLockedError: another run writes into ``out``.
    """
    n = paper_samples(n)
    if grid is not None and not simulation:
        raise InvalidParameterError("stiffness grid", list(grid), "none without the forward run "
                                    "(the grid is the forward run's; drop --no-simulation)")
    j = joint or PaperJoint()
    ks = stiffness_grid(K_GRID if grid is None else grid, max_stiffness(adams_model(j)))
    # an unwritable or busy place is named before the work; the files are published together
    with OutputFolder(out, "paper report") as folder:
        r = reproduce(j, n)
        figures = make_figures(j, min(n, 2048))
        if simulation:
            study = forward_study(j, ks, min(n, 2048))
            r["simulation"] = simulation_section(study)
            figures |= forward_figures(study, min(n, 2048))
        r = file_data(r)  # as paper.json holds it
        for name, fig in figures.items():
            save_png(fig, folder.path(name))
        folder.write("paper.json", json_text(r, indent=2))
        folder.write("summary.md", markdown_summary(r, list(figures)))
        folder.publish()
    return r
