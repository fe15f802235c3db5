"""The paper study's files (``hexaleg paper``): ``paper.json``, the Figs 5–13 analogues and
``summary.md``."""

from __future__ import annotations

import json
from pathlib import Path

from hexaleg.errors import OutputError
from hexaleg.outputs.paper_figures import save_png
from hexaleg.studies.paper.figures import make_figures
from hexaleg.studies.paper.joint import PaperJoint
from hexaleg.studies.paper.reproduce import paper_samples, reproduce
from hexaleg.studies.paper.summary import markdown_summary


def write_paper(out: str | Path, joint: PaperJoint | None = None, n: int = 8192) -> dict:
    """Write ``paper.json``, the Fig. 5–13 analogues (PNG) and ``summary.md`` into ``out``.

    Args:
        out: Output directory (created if missing).
        joint: The joint (default :class:`PaperJoint`).
        n: Samples per period.

    Returns:
        The content of ``paper.json``.

    Raises:
        InvalidParameterError: ``n`` out of range (before anything is written).
        OutputError: the directory or a file cannot be written.
    """
    n = paper_samples(n)
    j = joint or PaperJoint()
    out = Path(out)
    try:
        out.mkdir(parents=True, exist_ok=True)
        r = reproduce(j, n)
        files = []
        for name, fig in make_figures(j, min(n, 2048)).items():
            save_png(fig, out / name)
            files.append(name)
        (out / "paper.json").write_text(json.dumps(r, indent=2, ensure_ascii=False))
        (out / "summary.md").write_text(markdown_summary(r, files))
    except OSError as e:
        raise OutputError(f"cannot write the paper report to {out}: {e}") from e
    return r
