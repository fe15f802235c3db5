"""The full spring rules of ``hexaleg design`` on the co-designed gait, run beside the
co-design's remaining work.

:func:`full_rules` applies every rule of issue #30 (parsimony, stop tolerance, envelope and hard
stop, fatigue, arbor, the simulated ranking: :class:`hexaleg.design.chain.chain.DesignChain`)
to the gait the co-design chose (:func:`hexaleg.design.codesign.build.codesign`, step 5) — too
slow for its inner loop. :func:`started` runs it in a forked process (:class:`Background`) as
soon as the gait is chosen, beside the gait-alone search, the rows and the speed curve; its
result becomes the springs to buy (:mod:`hexaleg.design.codesign.rules` turns it into lines and
``codesign.json``).
"""

from __future__ import annotations

import dataclasses
import functools
import os
from collections.abc import Callable
from typing import Any

from hexaleg.config import from_mapping
from hexaleg.design.chain.config import DesignParams
from hexaleg.design.codesign.gait_evaluation import Constraints
from hexaleg.errors import HexalegError
from hexaleg.motion.params import GaitParams
from hexaleg.motion.trajectory import Motion
from hexaleg.parallel.workers import watch_parent
from hexaleg.scenario.scenario import Scenario

RULE_FAMILIES = ("preloaded", "one_sided", "linear")
"""The families the full rules compare on the chosen gait: ``hexaleg design``'s without
``dead_zone``. A dead-zone spring is the preloaded family with both preloads at zero (the same
``above``/``below`` terms, :mod:`hexaleg.design.families`), so at every geometry the preloaded
program's optimum is at least as good; it ranked last on the default gait (+12.08 % against
+16.36 %, analysis/logs/answer_hexaleg.log) and on the co-designed one (+39.90 % against
+42.66 %), where its geometry search alone took 27–70 s (docs/codesign.md). The slowest first:
the families run in this order on two worker processes."""


def rule_params(**table: Any) -> DesignParams:
    """The ``[design]`` settings of the full rules on the chosen gait: ``hexaleg design``'s
    defaults, the families :data:`RULE_FAMILIES` and ``robustness`` false (the maps and the
    robust box are not rules), with ``table``'s keys on top (a ``[codesign.design]`` table).

    Raises:
        UnknownNameError, ConfigError, InvalidParameterError: as ``[design]`` (named).
    """
    return from_mapping(DesignParams, {"families": list(RULE_FAMILIES), "robustness": False,
                                       **table}, "[codesign.design]")


class Background:
    """:func:`full_rules` running in a forked process beside the co-design's remaining work
    (the gait-alone search, the rows, the curve: about 10 s of a quiet run's 2 cores), or — where
    processes cannot fork — run at :meth:`result`. The same computation either way: the child
    is a copy of this process at the fork; its result comes back pickled (as the design's family
    workers' do). Its progress lines are printed by the child (a callback that collects them
    sees only those of this process)."""

    def __init__(self, run: Callable[[], Any]) -> None:
        import multiprocessing

        self._run = run
        self._process: Any = None
        self._pipe: Any = None
        if "fork" in multiprocessing.get_all_start_methods():
            ctx = multiprocessing.get_context("fork")
            self._pipe, child = ctx.Pipe(duplex=False)
            self._process = ctx.Process(target=_send, args=(run, child, os.getpid()))
            self._process.start()
            child.close()

    def result(self) -> Any:
        """The rules' result (waits for the child); re-raises what the child raised."""
        if self._process is None or self._pipe is None:
            return self._run()
        ok, value = self._pipe.recv()
        self._process.join()
        self._process = None
        if not ok:
            raise value
        return value

    def close(self) -> None:
        """Stop a child whose result was never asked for (the co-design failed first)."""
        if self._process is not None:
            self._process.terminate()
            self._process.join()
            self._process = None


def _send(run: Callable[[], Any], pipe: Any, parent: int) -> None:
    watch_parent(parent)  # ends with the co-design, also when it is killed; ignores Ctrl-C
    try:
        pipe.send((True, run()))
    except BaseException as err:  # handed to the parent, which raises it
        pipe.send((False, err))
    finally:
        pipe.close()


def started(run: Scenario, chosen: GaitParams, c: Constraints, say: Callable[[str], None],
            design: DesignParams | None) -> Background:
    """:func:`full_rules` on the chosen gait, started beside the co-design's remaining work."""
    return Background(functools.partial(full_rules, run, chosen, c, say, design))


def full_rules(run: Scenario | str, chosen: GaitParams, c: Constraints,
               say: Callable[[str], None],
               design: DesignParams | None = None) -> Any:
    """``hexaleg design`` (every rule of issue #30: parsimony, stop tolerance, envelope and hard
    stop, fatigue, arbor, the simulated ranking) on the chosen gait at its sampling, with
    ``design`` (default :func:`rule_params`: the families of :data:`RULE_FAMILIES`, no
    robustness maps nor robust box — neither is a rule, and on the co-designed gait the box
    alone cost a minute); its result, or the error's message when it cannot run there (the
    inner springs then stay recommended)."""
    params = design if design is not None else rule_params()
    # at the chosen gait's sampling: the design's run is its scenario at [design] samples
    params = dataclasses.replace(params, samples=chosen.samples)
    base = run if isinstance(run, Scenario) else Scenario.load(run)
    return _ruled(base.replace(gait=chosen, contact=c.contact()), params, say,
                  "the chosen gait")


def motion_rules(run: Scenario, motion: Motion, c: Constraints, say: Callable[[str], None],
                 design: DesignParams | None = None) -> Any:
    """:func:`full_rules` on a motion that is not a gait of the parametric family — the
    optimal motion with its springs (issue #56) — as ``hexaleg design --motion`` designs on a
    logged cycle: the motion at its own sampling, the rules of ``design`` (default
    :func:`rule_params`); its result, or the error's message when it cannot run there."""
    params = design if design is not None else rule_params()
    return _ruled(run.replace(recorded=motion, contact=c.contact()), params, say,
                  "the optimal motion")


def _ruled(run: Scenario, params: DesignParams, say: Callable[[str], None], on: str) -> Any:
    """The design chain of ``run`` under ``params`` (the rules' settings), said to be ``on``
    that motion; the error's message where it cannot run."""
    from hexaleg.design.chain.chain import DesignChain

    say(f"full spring rules on {on} (hexaleg design: {', '.join(params.families)})")
    try:
        return DesignChain(run, say, design=params).run()
    except HexalegError as err:
        say(f"full spring rules failed on {on}: {err}")
        return f"{type(err).__name__}: {err}"


__all__ = ["RULE_FAMILIES", "Background", "full_rules", "motion_rules", "rule_params",
           "started"]
