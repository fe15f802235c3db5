"""``hexaleg paper``: the paper's single joint written to a folder, saying on stderr what it
computes and how long it took (the command takes seconds: the forward run integrates the Adams
experiment at every stiffness of the grid). :func:`add` is its parser (registered in
:data:`hexaleg.cli.SUBCOMMANDS`), :func:`run` its run from the parsed options."""

from __future__ import annotations

import argparse
import functools
import time
from collections.abc import Callable, Sequence
from pathlib import Path

from hexaleg.commands.options import add_quiet, progress_of, say

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


def add(sub: argparse._SubParsersAction) -> None:
    """Add ``paper`` to the subcommands."""
    p = sub.add_parser("paper", help="reproduce the paper's single elastic joint: paper.json, "
                                     "Fig. 5-13 analogues (PNG), summary.md, and its Adams "
                                     "experiment forward in MuJoCo beside them")
    p.add_argument("--out", default=DEFAULT_OUT, help="output directory (default: %(default)s)")
    p.add_argument("--samples", type=int, default=8192,
                   help="samples per trajectory period (default: %(default)s)")
    # hexaleg.paper.forward.K_GRID, which is not imported to build the parser
    p.add_argument("--grid", type=float, nargs="+", metavar="K",
                   help="stiffnesses of the forward run, the paper's eq. 19 units (1e-6 N·m/rad), "
                        "at least 3, increasing (default: 100 to 1600 in steps of 100)")
    p.add_argument("--no-simulation", dest="simulation", action="store_false",
                   help="leave out the forward run (the analytic reproduction only)")
    add_quiet(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """``hexaleg paper``: :func:`run_paper` with the command line's options."""
    return run_paper(args.out, n=args.samples, simulation=args.simulation, grid=args.grid,
                     progress=progress_of(args, "paper"))


__all__ = ["DEFAULT_OUT", "PROGRESS", "add", "run", "run_paper"]
