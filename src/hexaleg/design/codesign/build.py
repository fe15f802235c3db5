"""``hexaleg codesign``: the gait and its springs designed together for a required speed.

:func:`codesign` runs, for one robot, speed and pattern:

1. the robot's default gait at that speed (:func:`~hexaleg.motion.scaling.robot_gait`, the speed
winning over
   the stride), its static margin — the default ``min_static_margin`` — and its energy;
2. the **co-design**: the outer search (:func:`hexaleg.design.codesign.gait_search.search`,
restarted
   compass search) over body height, foot radius, step height, duty factor and period, each
   candidate with the inner spring program's optimum
   (:func:`hexaleg.design.search.optimal.optimal_springs` of ``family`` on every joint class,
   electrical metric: fast and convex), at ``samples``
   samples a cycle; and the gait alone (the same search without springs) for the row "best gait
   without springs";
3. the four rows at ``final_samples`` (:mod:`hexaleg.design.codesign.result`), the sequential
   design (the gait alone, then its springs) beside them;
4. the curve of energy per metre against speed for the default and the co-designed gait, with
   and without their springs (the gait's other parameters held, the stride ``v · period``);
5. with ``rules`` (the default), the full spring rules of ``hexaleg design`` (tolerance,
   envelope, fatigue, arbor, parsimony, simulated ranking:
   :class:`hexaleg.design.chain.chain.DesignChain`) applied to the chosen gait only — too
   slow for the inner loop — whose recommendation is the springs to buy
   (:func:`~hexaleg.design.codesign.full_rules.full_rules`); they start as soon as the
   co-design search has chosen the gait, in a process beside steps 2's gait-alone search, 3
   and 4 (:class:`~hexaleg.design.codesign.full_rules.Background`);
6. the co-designed gait simulated forward in MuJoCo with and without the springs to buy
   (:func:`hexaleg.simulation.run.simulate`), and their predicted saving on floors of other
   friction (:mod:`hexaleg.design.codesign.floors`).
"""

from __future__ import annotations

import dataclasses
import functools
import time
import warnings
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from hexaleg.checks import integer, one_of, real, typed
from hexaleg.config import from_mapping, keywords
from hexaleg.design.chain.checkpoint import StageFiles
from hexaleg.design.chain.config import DesignParams
from hexaleg.design.chain.groups import design_groups
from hexaleg.design.chain.ranking import under
from hexaleg.design.codesign.box import body_bound, default_space, duty_bound
from hexaleg.design.codesign.floors import over_floors
from hexaleg.design.codesign.full_rules import motion_rules, rule_params, started
from hexaleg.design.codesign.gait_evaluation import (
    PARAMETERS,
    Constraints,
    GaitPoint,
    evaluate_gait,
    with_values,
)
from hexaleg.design.codesign.gait_search import RESTARTS, SearchResult, search
from hexaleg.design.codesign.optimal_stage import keep_parametric, kept_parametric, with_optimal
from hexaleg.design.codesign.result import CodesignResult, Row, SpeedPoint
from hexaleg.design.codesign.servo import choose, screen
from hexaleg.design.codesign.starts import STARTS
from hexaleg.design.codesign.timing import TIMINGS
from hexaleg.design.families import FAMILIES
from hexaleg.design.search.optimal import Groups
from hexaleg.dynamics.plausibility import uses_generic
from hexaleg.errors import ConfigError, HexalegError, InvalidParameterError
from hexaleg.motion.body import body_height, nominal_footholds
from hexaleg.motion.legged import gait
from hexaleg.motion.params import GaitParams
from hexaleg.motion.patterns import check_pattern, pattern_offsets
from hexaleg.motion.scaling import robot_gait
from hexaleg.parallel.forked import fork_map, robot_objects
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet
from hexaleg.scenario.scenario import Scenario
from hexaleg.simulation.balance import MODES as FEEDBACK
from hexaleg.simulation.controllers import BOTH, SERVOS

MOTIONS = ("gait", "optimal")
"""What ``motion`` may be: the parametric gait alone, or also the optimal motion's rows."""
SPEED_FACTORS = (0.5, 0.75, 1.0, 1.25, 1.5)
"""The speed curve's speeds, as factors of the required speed."""


def default_gait(robot: Robot, name: str, speed: float, pattern: str | None, samples: int
                 ) -> GaitParams:
    """The robot's default gait at ``speed`` with its body height and foot radius resolved
    (the stand pose's foot depth and mean horizontal foothold distance)."""
    base = robot_gait(name, table=None if pattern is None else {"pattern": pattern},
                      where="[codesign] pattern")
    if pattern is not None:
        pattern_offsets(pattern, robot.leg_names)  # a pattern for other legs named as such
        base = dataclasses.replace(base, pattern=check_pattern(pattern),
                                   duty_factor=None)  # type: ignore[arg-type]  # → β₀
    base = dataclasses.replace(base, samples=samples, speed=float(speed))
    radius = float(np.linalg.norm(nominal_footholds(robot, base)[:, :2], axis=1).mean())
    return dataclasses.replace(base, body_height=body_height(robot, base), foot_radius=radius)


@typed
def codesign(robot: str | Scenario = "hexaleg", speed: float = 0.06, pattern: str | None = None, *,
             constraints: Constraints | None = None, family: str = "linear",
             samples: int = 100, final_samples: int = 200, max_evaluations: int = 200,
             restarts: int = RESTARTS, grouping: str = "class", curve: bool = True,
             simulate: bool = True, rules: bool = True, design: DesignParams | None = None,
             controller: str = BOTH, motion: str = "gait", feedback: str = "auto",
             timing: str = "gait", starts: str | None = None, duty_high: float | None = None,
             body_high: float | None = None, optimal: Mapping[str, Any] | None = None,
             progress: Callable[[str], None] | None = None,
             stages: StageFiles | None = None) -> CodesignResult:
    """The gait and springs that cover a metre at ``speed`` for the least electrical energy
    (module docstring).

    Args:
        robot: The run (:class:`~hexaleg.scenario.scenario.Scenario`: its robot, its
            actuators — ``[motor]``, else the robot's own — and its floor, ``[contact]``,
            whose ``mu`` and ``torque_limits`` are the constraints'), or a registered robot or
            a description TOML (its own actuators, the default floor).
        speed: Required speed, m/s, > 0.
        pattern: A gait pattern (:data:`hexaleg.motion.patterns.PATTERNS`); None: the robot's.
        constraints: The constraints (default :class:`Constraints`: the default gait's margin).
        family: The inner spring family (``linear``: no geometry, the fastest).
        samples: Samples a cycle in the search (≥ 40). final_samples: in the rows (≥ samples).
        max_evaluations: The co-design search's budget (the gait-alone search gets the same).
        restarts: Compass-search runs of each search
            (:data:`~hexaleg.design.codesign.gait_search.RESTARTS`).
        grouping: One spring design per joint ``class`` (default), ``mirrored`` left/right
            pair, or ``joint`` (Solo-12's front and hind knees bend opposite ways: a class
            design cancels, so ``mirrored``).
        curve: Compute the energy-vs-speed curve. simulate: Simulate the search's finalists
            and choose among them (:mod:`hexaleg.design.codesign.servo`), and simulate the
            chosen gait; False: the search's best gait is chosen unsimulated.
        rules: Apply ``hexaleg design``'s full spring rules to the chosen gait and recommend
            what they choose (:func:`~hexaleg.design.codesign.full_rules.full_rules`, about a
            minute), and with ``motion="optimal"`` to the optimal motion with its springs
            (:func:`~hexaleg.design.codesign.full_rules.motion_rules`); False: the search's
            answer alone, the inner program's springs recommended (the alternation's for the
            optimal motion).
        design: The rules' ``[design]`` settings (default
            :func:`~hexaleg.design.codesign.full_rules.rule_params`); they run at
            ``final_samples``, ranked under ``controller``.
        controller: The servo the robot runs (:data:`~hexaleg.simulation.controllers.SERVOS`):
            the finalists and the full rules' designs are simulated under it (``"both"``,
            the default: under each controller, judged by the worse).
        motion: ``"gait"`` (default): the parametric gait only; ``"optimal"``: also the motion
            itself optimised from the chosen gait, without and with its springs, each row
            simulated (:mod:`hexaleg.design.codesign.optimal_rows`; needs the ``optimal``
            extra, checked before any work).
        feedback: The optimal motion's rows' balance feedback, the same for every row, as
            ``hexaleg simulate``'s (:data:`~hexaleg.simulation.balance.MODES`: ``"auto"``, where
            the gait needs it or open loop falls; ``"on"``, every row closed loop, a position
            servo asked for the plan's torque; ``"off"``, open loop); only with
            ``motion="optimal"`` (the parametric co-design's servo check runs ``"auto"``).
        timing: The optimal motion's contact timing (:data:`~hexaleg.design.codesign.timing.
            TIMINGS`): ``"gait"``, the chosen gait's; ``"search"``, a small deterministic
            search about it (:mod:`hexaleg.design.codesign.timing`: five solves more, each
            judged by the prediction of its rebuilt cycle); only with ``motion="optimal"``.
        starts: The optimal motion's starts (:data:`~hexaleg.design.codesign.starts.STARTS`):
            ``"gait"``, the gait at the timing used; ``"lattice"``, a small fixed lattice of
            starts about it (:mod:`hexaleg.design.codesign.starts`: step height, body height,
            swing weight; six or seven solves more, each judged by the prediction of its
            rebuilt cycle), the alternation run from the best; only with ``motion="optimal"``.
            None: ``"lattice"`` with ``motion="optimal"``, else none.
        duty_high: The co-design search's (and the gait-alone search's) highest duty factor
            (:func:`~hexaleg.design.codesign.box.default_space`), in [the default gait's duty
            factor + 0.05, 0.95]; None: :data:`~hexaleg.design.codesign.box.DUTY_HIGH`, or the
            default gait's + 0.05 where that is higher (a wave's 5/6). The optimal rows'
            parametric co-design is the one searched to it.
        body_high: The searches' highest body height, × the default gait's (the box's
            lowest stays 0.7 ×), in [:data:`~hexaleg.design.codesign.box.BODY_FLOOR`,
            :data:`~hexaleg.design.codesign.box.BODY_CEILING`]; None:
            :data:`~hexaleg.design.codesign.box.BODY_HIGH`. The optimal rows' parametric
            co-design is the one searched to it.
        optimal: The optimal motion's problem and solver settings, a ``[codesign.optimal]``
            table: keys of :class:`~hexaleg.optimal.problem.OptimalParams` (``nodes``,
            ``iterations``, ``servo_landing_weight``, …), the rest their defaults, the friction
            cone the floor's μ inside the constraints' ``friction_margin`` (``mu`` and
            ``friction_use`` are refused here); only with ``motion="optimal"``.
        progress: Called with one status line per stage.
        stages: Where the parametric co-design is kept when it is done, before the optimal
            motion's stage (``motion="optimal"``: minutes more), and read back from instead of
            computed again when the kept one is this run's (:class:`~hexaleg.design.chain.
            checkpoint.StageFiles`, keyed by the caller on the run and these settings:
            ``hexaleg codesign`` after a kill); None: nothing kept.

    Raises:
        InvalidParameterError: a speed not > 0, sample counts out of range, a ``duty_high``
            outside its range (named, with the range at this pattern), a ``body_high``
            outside its range (named, with the range); the default gait itself
            cannot be made at this speed (named, with its error).
        UnknownNameError: an unknown robot, pattern, family, controller, motion, feedback,
            timing or starts.
        ConfigError: a ``feedback`` other than ``"auto"``, or a ``timing`` or ``starts``
            other than ``"gait"``, or an ``optimal`` table, without ``motion="optimal"``.
        BackendError: ``motion="optimal"`` without a usable Crocoddyl (names the extra).
    """
    servo = one_of("[codesign] controller", controller, SERVOS)
    loop = one_of("[codesign] feedback", feedback, FEEDBACK)
    if one_of("[codesign] motion", motion, MOTIONS) != "optimal" and loop != "auto":
        raise ConfigError(f"[codesign] feedback = {loop!r} sets the optimal motion's rows' "
                          "balance feedback: it needs motion = \"optimal\" (--motion optimal); "
                          "the parametric co-design's servo check runs \"auto\"")
    if one_of("[codesign] timing", timing, TIMINGS) != "gait" and motion != "optimal":
        raise ConfigError(f"[codesign] timing = {timing!r} searches the optimal motion's "
                          "contact timing: it needs motion = \"optimal\" (--motion optimal)")
    if starts is None:
        starts = "lattice" if motion == "optimal" else "gait"
    elif one_of("[codesign] starts", starts, STARTS) != "gait" and motion != "optimal":
        raise ConfigError(f"[codesign] starts = {starts!r} tries other starts of the optimal "
                          "motion: it needs motion = \"optimal\" (--motion optimal)")
    if optimal is not None and motion != "optimal":
        raise ConfigError("[codesign.optimal] sets the optimal motion's problem: it needs "
                          "motion = \"optimal\" (--motion optimal)")
    if motion == "optimal":
        from hexaleg.optimal.backend import crocoddyl_module

        crocoddyl_module()  # before the search: a missing extra is said at once
        given = dict(optimal or {})
        floor = sorted({"mu", "friction_use"} & set(given))
        if floor:
            raise ConfigError(f"[codesign.optimal] {', '.join(floor)}: the optimal motion plans "
                              "on the run's floor, [contact] mu, inside [codesign.constraints] "
                              "friction_margin (set them there)")
    design = dataclasses.replace(design if design is not None else rule_params(),
                                 controller=servo)
    v = real("speed", speed, low=0.0, low_open=True, allowed="a speed > 0 (m/s)")
    n = integer("samples", samples, low=40, high=2000)
    n_final = integer("final_samples", final_samples, low=n, high=5000)
    run = robot if isinstance(robot, Scenario) else Scenario.load(robot)
    c = constraints or floor_constraints(run)
    family = one_of("[codesign] family", family, FAMILIES)
    params = None
    if motion == "optimal" and optimal is not None:  # checked before the search, on the floor
        from hexaleg.optimal.problem import OptimalParams

        params = from_mapping(OptimalParams, {"mu": c.mu, "friction_use": c.friction_margin,
                                              **optimal}, "[codesign.optimal]")
    say = progress or (lambda _msg: None)
    t0 = time.perf_counter()
    model = run.model
    motor = run.actuator  # [motor], else the robot's own, as hexaleg design uses
    base = default_gait(model, run.robot, v, pattern, n)
    duty_high = duty_bound(duty_high, base.duty_factor)
    body_high = body_bound(body_high)
    groups = design_groups(model, tuple(model.joint_classes),
                           one_of("grouping", grouping, ("class", "mirrored", "joint")))
    kept = kept_parametric(stages, model) if motion == "optimal" else None
    if kept is not None:
        say(f"co-design: {kept.rows[3].per_metre:.2f} J/m, read back from the kept stage of "
            f"this run ({stages.directory if stages is not None else ''})")
        return with_optimal(kept, model, motor, groups, servo, say, stages, loop, timing,
                            starts, functools.partial(motion_rules, run, c=kept.constraints,
                                                      say=say, design=design) if rules else None,
                            params)
    free = functools.partial(evaluate_gait, model, family=family, constraints=c, motor=motor)
    first = free(base, groups=groups, min_margin=0.0)
    if first.error is not None:
        hint = _whole_cone(free, base, groups, c)
        raise InvalidParameterError("speed", v, f"a speed the robot's default gait can walk "
                                    f"(it fails: {first.error}){hint}")
    margin = c.min_static_margin if c.min_static_margin is not None \
        else max(0.0, first.measures.get("static_margin", (0.0,))[0])
    c = dataclasses.replace(c, min_static_margin=margin)
    free = functools.partial(evaluate_gait, model, family=family, constraints=c,
                             min_margin=margin, motor=motor)
    space = default_space(base, c.min_foot_clearance, duty_high=duty_high,
                          body_high=body_high)
    say(f"{model.name}: default gait {first.per_metre:.2f} J/m at {v:g} m/s")
    spread = functools.partial(fork_map, shared=robot_objects(model))
    joint = search(functools.partial(free, groups=groups), base, v, space, springs=True,
                   reference=first.per_metre, max_evaluations=max_evaluations,
                   restarts=restarts, map_fn=spread,
                   progress=lambda line: say(f"co-design search: {line}"))
    say(f"co-design: {joint.value:.2f} J/m after {joint.evaluations} evaluations "
        f"({joint.wall:.1f} s)")
    finalists = screen(model, joint.finalists, servo, c, motor,
                       lambda g: free(dataclasses.replace(g, samples=n_final), groups=groups),
                       progress=lambda line: say(f"servo check: {line}")) if simulate else ()
    pick = choose(finalists)
    chosen = dataclasses.replace(joint.best.params if pick is None else pick.point.params,
                                 samples=n_final)
    if finalists:
        say(f"servo check: {len(finalists)} finalists simulated under {under(servo)}: "
            + (f"chose finalist {finalists.index(pick) + 1}, {pick.worst:.2f} J/m simulated"
               if pick is not None else "none walked, the search's best kept"))
    ruled = started(run, chosen, c, say, design) if rules else None
    try:
        alone = search(functools.partial(free, groups=None), base, v, space, springs=False,
                       reference=first.per_metre, max_evaluations=max_evaluations,
                       restarts=restarts, map_fn=spread,
                       progress=lambda line: say(f"gait-alone search: {line}"))
        say(f"gait alone: {alone.value:.2f} J/m after {alone.evaluations} evaluations")

        def at_rows(params: GaitParams) -> GaitPoint:
            return free(dataclasses.replace(params, samples=n_final), groups=groups)

        def final(params: GaitParams) -> GaitPoint:
            point = at_rows(params)
            if point.error is not None:
                raise InvalidParameterError("final_samples", n_final, "a sampling at which "
                                            f"the chosen gait still works ({point.error})")
            return point

        d_sprung, c_sprung = final(base), final(chosen)
        g_sprung = settled(alone, at_rows, n_final, say)
        rows = (Row.of("default gait, no springs", d_sprung, False, model.mass),
                Row.of("default gait, its best springs", d_sprung, True, model.mass),
                Row.of("best gait, no springs", g_sprung, False, model.mass),
                Row.of("chosen gait, its springs (co-design)", c_sprung, True, model.mass))
        sequential = Row.of("sequential: best gait alone, then its springs", g_sprung, True,
                            model.mass)
        say(f"rows at {n_final} samples ({time.perf_counter() - t0:.1f} s)")
        points = speed_curve(free, groups, base, chosen, v) if curve else ()
        buy = ruled.result() if ruled is not None else None
        bought = c_sprung.springs
        if buy is not None and not isinstance(buy, str) and buy.pays:
            bought = buy.recommended.optimum.springs
        simulation = simulated(model, chosen, bought, c, motor) if simulate else {}
        floors = over_floors(model, chosen, motor, bought, c.torque_limits)
        result = CodesignResult(
            robot=run.robot, title=model.name, mass=model.mass, speed=v, pattern=base.pattern,
            family=family, constraints=c, default=dataclasses.replace(base, samples=n_final),
            chosen=chosen, springs=c_sprung.springs, measures=c_sprung.measures,
            inner_saving=1.0 - c_sprung.sprung / c_sprung.baseline, rows=rows,
            sequential=sequential, search=joint, gait_search=alone, curve=points,
            simulation=simulation, rules=buy, samples=n, wall=time.perf_counter() - t0,
            generic=uses_generic(motor), servo=servo, finalists=finalists, floors=floors,
            optimal=None, duty_high=duty_high, body_high=body_high, box=space)
        if motion != "optimal":
            return result
        keep_parametric(stages, result, model)
        return with_optimal(result, model, motor, groups, servo, say, stages, loop, timing,
                            starts, functools.partial(motion_rules, run, c=c, say=say,
                                                      design=design) if rules else None,
                            params)
    finally:
        if ruled is not None:
            ruled.close()


def settled(found: SearchResult, evaluate: Callable[[GaitParams], GaitPoint], samples: int,
            say: Callable[[str], None]) -> GaitPoint:
    """The best gait of the search ``found`` that still works at the rows' sampling
    (``evaluate`` gives a gait's point there, ``samples`` a cycle): its best, else the next of
    its finalists that does, each one that fails said. A gait the search's coarser sampling
    allows may leave a joint's limit between its samples (Go2's gait alone at 0.3 m/s: its calf
    at -47.99° past -48.0° at 200 samples); the servo check screens the co-design's finalists at
    the rows' sampling, this screens the gait alone's.

    Raises:
        InvalidParameterError: none works there (``final_samples`` named, the best's error).
    """
    tried = [found.best, *(f for f in found.finalists if f is not found.best)]
    errors = []
    for k, point in enumerate(tried):
        done = evaluate(point.params)
        if done.error is None:
            return done
        errors.append(done.error)
        say(f"gait alone: its gait {k + 1} of {len(tried)} fails at {samples} samples "
            f"({done.error})" + ("; the next taken" if k + 1 < len(tried) else ""))
    raise InvalidParameterError("final_samples", samples, "a sampling at which one of the gait "
                                f"alone's {len(tried)} best gaits still works (the best fails: "
                                f"{errors[0]})")


def _whole_cone(free: Callable[..., GaitPoint], base: GaitParams, groups: Groups,
                c: Constraints) -> str:
    """Where the default gait fails only for the co-design's narrowed friction cone
    (``friction_margin`` < 1: the force programs plan within ``friction_margin · μ``,
    ``Constraints.planning_contact``), the key that changes it, as a refusal's last clause;
    else "" (one more evaluation of the gait, made only on the way to a refusal)."""
    if c.friction_margin >= 1:
        return ""
    whole = free(base, groups=groups, min_margin=0.0,
                 constraints=dataclasses.replace(c, friction_margin=1.0))
    if whole.error is not None:
        return ""
    return (f"; it walks with its forces in the whole friction cone: [codesign.constraints] "
            f"friction_margin = 1 (now {c.friction_margin:g}), or a lower speed")


def speed_curve(free: Callable[..., GaitPoint], groups: Groups, base: GaitParams,
                chosen: GaitParams, speed: float) -> tuple[SpeedPoint, ...]:
    """Energy per metre of the default and the chosen gait against speed
    (:data:`SPEED_FACTORS`), with and without their inner-program springs (NaN where a gait
    fails at that speed, e.g. a joint too fast)."""
    out = []
    for factor in SPEED_FACTORS:
        v = factor * speed
        for label, params in (("default", base), ("co-design", chosen)):
            values = {p: getattr(params, p) for p in PARAMETERS}
            point = free(with_values(dataclasses.replace(params, samples=base.samples), v,
                                     values), groups=groups)
            ok = point.feasible
            out.append(SpeedPoint(label, v, point.per_metre if ok else float("nan"),
                                  point.per_metre_springs if ok else float("nan")))
    return tuple(out)


def simulated(robot: Robot, chosen: GaitParams, springs: SpringSet, c: Constraints,
              motor: Any = None) -> dict[str, Any]:
    """The chosen gait simulated forward in MuJoCo (feedforward + PD servos, default
    :class:`~hexaleg.simulation.run.Settings`) with and without ``springs`` (the springs to
    buy), the robot's ``motor`` (None: the catalogue's default): planned and walked distance per
    cycle, the predicted and simulated electrical saving; or the error."""
    from hexaleg.simulation.run import simulate

    try:
        motion = gait(robot, chosen)
        sim = simulate(robot, motion, motor, springs, contact=c.contact())
        predicted = sim.predicted("electrical")[2]
        simulated_ = sim.simulated("electrical")[2]
        walk = sim.with_springs.walk
        base_walk = sim.baseline.walk
    except HexalegError as err:
        return {"error": f"{type(err).__name__}: {err}"}
    assert walk is not None and base_walk is not None
    return {"planned": motion.distance, "walked": walk.distance_per_cycle,
            "walked_baseline": base_walk.distance_per_cycle, "predicted": predicted,
            "simulated": simulated_, "controller": sim.settings.controller,
            "feedback": sim.with_springs.feedback}


CODESIGN_KEYS = ("speed", "pattern", "family", "samples", "final_samples", "max_evaluations",
                 "restarts", "grouping", "rules", "curve", "simulate", "controller",
                 "motion", "feedback", "timing", "starts", "duty_high", "body_high",
                 "constraints", "design", "optimal")
"""The keys of a ``[codesign]`` table: :func:`codesign`'s keywords."""


FLOOR_KEYS: tuple[str, ...] = ("mu", "torque_limits")
"""The ``[contact]`` keys the co-design's constraints take (:func:`floor_constraints`); the
others plan every force program at their defaults, so a ``[contact]`` that sets them is
refused by name (:func:`codesign_settings`)."""


def floor_constraints(run: Scenario) -> Constraints:
    """The default constraints on the run's floor: ``[contact]`` ``mu`` and ``torque_limits``
    (the friction's one home)."""
    return Constraints(mu=run.contact.mu, torque_limits=run.contact.torque_limits)


def codesign_settings(table: Any, where: str = "[codesign]",
                      run: Scenario | None = None) -> dict[str, Any]:
    """The keywords of :func:`codesign` a ``[codesign]`` table gives, checked, on the floor of
    ``run`` (its ``[contact]``: :func:`floor_constraints`).

    ``[codesign.constraints] mu`` and ``torque_limits`` are deprecated: the floor's one home is
    ``[contact]``; they still work with a warning and are refused beside ``[contact]``'s.

    Raises:
        ConfigError: not a table, a value of the wrong type (checked against
            :func:`codesign`'s annotations, as ``[design]`` against its dataclass); a floor
            key in both ``[contact]`` and ``[codesign.constraints]``; a ``[contact]`` key the
            co-design does not plan with.
        UnknownNameError: a key that is not in :data:`CODESIGN_KEYS` or not a constraint
            (lists them).
    """
    if not isinstance(table, dict):
        raise ConfigError(f"{where} must be a table, got {table!r}")
    plain = {k: v for k, v in table.items() if k not in ("constraints", "design", "optimal")}
    out = {**table, **keywords(codesign, plain, where, CODESIGN_KEYS)}
    contact = run.table("contact") if run is not None else {}
    unplanned = sorted(set(contact) - set(FLOOR_KEYS))
    if run is not None and unplanned:
        raise ConfigError(f"{run.where} [contact] {', '.join(unplanned)}: hexaleg codesign "
                          f"plans its forces with the defaults of these; it reads "
                          f"{' and '.join(FLOOR_KEYS)} from [contact] (remove the others)")
    if "constraints" in out or run is not None:
        where_c = f"{where[:-1]}.constraints]"
        given = out.get("constraints", {})
        if not isinstance(given, dict):
            raise ConfigError(f"{where_c} must be a table, got {given!r}")
        for key in FLOOR_KEYS:
            if key in given and key in contact:
                raise ConfigError(f"{where_c} {key} beside [contact] {key}: the floor has one "
                                  f"home, [contact]; remove the [codesign.constraints] {key}")
            if key in given:
                warnings.warn(f"{where_c} {key} is deprecated: the floor's one home is "
                              f"[contact] (write [contact] {key} = {given[key]!r})",
                              DeprecationWarning, stacklevel=2)
        floor = {} if run is None else {"mu": run.contact.mu,
                                        "torque_limits": run.contact.torque_limits}
        out["constraints"] = from_mapping(Constraints, {**floor, **given}, where_c)
    if "design" in out:
        if not isinstance(out["design"], dict):
            raise ConfigError(f"{where[:-1]}.design] must be a table")
        if "controller" in out["design"]:
            raise ConfigError(f"{where[:-1]}.design] controller: the servo is set once, for the "
                              f"finalists and the spring rules alike, as {where} controller")
        out["design"] = rule_params(**out["design"])
    if "optimal" in out and not isinstance(out["optimal"], dict):
        raise ConfigError(f"{where[:-1]}.optimal] must be a table")
    return out


__all__ = ["CODESIGN_KEYS", "FLOOR_KEYS", "MOTIONS", "SPEED_FACTORS", "codesign",
           "codesign_settings", "default_gait", "floor_constraints", "simulated", "speed_curve"]
