"""``hexaleg paper``: the paper's single joint written to a folder, saying on stderr what it
computes and how long it took (the command takes seconds: the forward run integrates the Adams
experiment at every stiffness of the grid)."""

from __future__ import annotations

import functools
import time
from collections.abc import Callable, Sequence
from pathlib import Path

from hexaleg.commands.options import say

DEFAULT_OUT = "hexaleg-paper"
"""The command's output folder, named like every other command's (``hexaleg-<command>``)."""


PROGRESS = functools.partial(say, "paper")
"""The command's status lines on stderr (``hexaleg paper: …``)."""


def run_paper(out: str | Path = DEFAULT_OUT, *, n: int = 8192, simulation: bool = True,
              grid: Sequence[float] | None = None,
              progress: Callable[[str], None] | None = PROGRESS
              ) -> int:
    """Write the paper report (:func:`hexaleg.commands.paper.write.write_paper`) into ``out``
    and print its one-line summary and the files on stdout.

    Args:
        out: Output folder.
        n: Samples per trajectory period.
        simulation: Whether to rerun the Adams experiment forward in MuJoCo.
        grid: The forward run's stiffnesses, eq. 19 units; None for the default grid.
        progress: Called with a status line before the work and after it (default: stderr);
            None: quiet.

    Returns:
        The exit status, 0.
    """
    from hexaleg.commands.paper.write import write_paper
    from hexaleg.paper.forward import K_GRID
    from hexaleg.paper.summary import one_line

    say = progress or (lambda _msg: None)
    t0 = time.perf_counter()
    work = f"the paper's joint at {n} samples a period: closed forms, optima, Figs 5–13"
    if simulation:
        k = len(K_GRID if grid is None else grid)
        work += f"; its Adams experiment forward in MuJoCo at {k} stiffnesses"
    say(f"{work} …")
    r = write_paper(out, n=n, simulation=simulation, grid=grid)
    say(f"done in {time.perf_counter() - t0:.1f} s")
    print(one_line(r))
    print(f"wrote {out}/paper.json, summary.md and figures")
    return 0
