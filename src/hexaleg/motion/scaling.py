"""Default gaits sized to the robot by dynamic similarity to the default hexapod.

hexaleg's default gait (:class:`~hexaleg.motion.params.GaitParams`: period 1 s, stride 6 cm, step
height 3 cm) was chosen for the built-in hexapod, whose hips stand :data:`REFERENCE_HIP_HEIGHT`
above the ground. A robot whose description sets no gait gets that gait **scaled**: Alexander &
Jayes ("A dynamic similarity hypothesis for the gaits of quadrupedal mammals", J. Zool. 201,
1983) found that animals of different sizes move in dynamically similar ways at equal Froude
numbers ``Fr = v² / (g h)``, ``h`` the hip height, and then take equal relative strides
``λ = s / h``. With ``k = h / h₀`` the sized gait keeps both numbers of the hexapod's:

* stride ``s = λ₀ h = k s₀``, step height ``k · 0.03 m`` (geometric similarity);
* speed ``v = √(Fr₀ g h)``, so period ``T = s / v = √k · T₀``;
* then, when a joint of the sized gait would run faster than its URDF velocity limit (checked
  at :data:`CHECK_SAMPLES` samples with the margin :data:`SPEED_MARGIN`), the period is
  lengthened by the ratio of the fastest joint's peak speed to its limit (time scaling of the
  same path divides every joint speed by the factor: Hollerbach, "Dynamic scaling of manipulator
  trajectories", ASME J. Dyn. Syst. Meas. Control 106(1), 1984), repeated while the balance sway
  (which depends on the period) keeps a joint over. The Froude number is then below the
  hexapod's, and the note says by how much;
* when a foot of the sized gait is out of reach (a balancing sway takes the body away from the
  legs) and the diagnosis (:mod:`hexaleg.motion.reach`) finds a shorter stride or a lower step
  that works, that value is taken, the period following from it by the Froude number, and the
  note says so;
* when the gait stands on two point feet (a trot, a pace, a bound), the period is then shortened,
  the stride kept, until its longest such stand lasts at most
  :data:`~hexaleg.motion.stands.HOLDS` time constants ``ω₀ T`` of the linear inverted pendulum
  across the feet's line (``ω₀ = √(g/h)``, h the centre of mass over the feet: Kajita et al.,
  "The 3D linear inverted pendulum mode", IROS 2001; :mod:`hexaleg.motion.stands`), what the
  simulated balance controller holds: the similar period is a slow walk whose stands it does not
  (the X-configured test quadruped's 2.34 s trot stood 5.4 and fell; at 0.86 s it walks). Where
  a joint's velocity limit forbids that period, the limit wins: the period is the shortest it
  allows, and the note says how long the stands then are and which limit won. A stand on one
  point foot is left as it is (no period makes it one the controller holds).

Only the keys a description leaves unset are sized: a set ``stride_length`` is kept and the
period follows the Froude number from it; a set ``period`` is never lengthened; a set ``speed``
fixes the Froude number itself, so period and stride are then left as they are. The
built-in hexapod is the reference and is not sized. :func:`sized_defaults` says what was chosen
(:meth:`SizedDefaults.note`, :meth:`SizedDefaults.as_dict`); the commands print it and write it
into their JSON.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import pinocchio as pin

from hexaleg.errors import GaitReachError, HexalegError, InvalidParameterError
from hexaleg.motion.body import body_height, reference_pose
from hexaleg.motion.legged import gait as make_gait
from hexaleg.motion.params import GaitParams, default_groups
from hexaleg.motion.sanity import speed_ratio
from hexaleg.motion.stands import HOLDS, longest_stand
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.description import RobotDescription
from hexaleg.robot.model import Robot
from hexaleg.robot.registry import description
from hexaleg.robot.sources import BUILTIN
from hexaleg.units import G

REFERENCE_HIP_HEIGHT = 0.0912703
"""Hip height of the built-in hexapod in its stand pose, m: the mean height of the legs' first
joints above their feet (:func:`hip_height`; pinned by a test)."""
REFERENCE = GaitParams()
"""The default hexapod's gait, the reference of the similarity."""
REFERENCE_FROUDE = (REFERENCE.stride / REFERENCE.period) ** 2 / (G * REFERENCE_HIP_HEIGHT)
"""``Fr₀ = v₀² / (g h₀)`` of the default hexapod's gait (0.0040)."""
REFERENCE_RELATIVE_STRIDE = REFERENCE.stride / REFERENCE_HIP_HEIGHT
"""``λ₀ = s₀ / h₀`` of the default hexapod's gait (0.657)."""
SIZED_KEYS: tuple[str, ...] = ("period", "stride_length", "step_height")
"""The gait parameters sized to the robot when its description leaves them unset."""
MAX_STRETCHES = 6
"""Times the period is lengthened at most to bring the joints within their speed limits."""
CHECK_SAMPLES = 200
"""Samples per cycle of the gait whose joint speeds are checked (the gait's own when fewer)."""
SPEED_MARGIN = 0.99
"""The checked peak speeds are brought to at most this fraction of the limits, so that the
peaks between the checked samples (finer sampling) stay within them."""
OVERSHOOT = 1e-3
"""A period lengthened back from the pendulum's for the speed limits is lengthened this fraction
more than the peak speed's ratio says: the ratio approaches :data:`SPEED_MARGIN` from above as
the sway follows the period, so without it the iteration would not end within the margin."""
HOLD_TOL = 1e-9
"""Relative tolerance of a stand's ω₀ T against :data:`~hexaleg.motion.stands.HOLDS` (the
rounding of a period shortened to it)."""
_CACHE: dict[tuple[str, str, int, int], SizedDefaults | None] = {}


def hip_height(robot: Robot, gait: GaitParams) -> float:
    """The mean height of the legs' first joints above the ground, m, with the base at the gait's
    body height (:func:`hexaleg.motion.body.body_height`) in the stand pose.

    Args:
        robot: The robot (its ``stand`` pose, or the neutral configuration).
        gait: Its gait (``body_height``, None for the stand pose's).
    """
    q = reference_pose(robot)
    data = robot.model.createData()
    pin.forwardKinematics(robot.model, data, q)
    hips = np.array([data.oMi[leg.joint_ids[0]].translation[2] for leg in robot.legs])
    return float(body_height(robot, gait) + hips.mean())


@dataclass(frozen=True)
class SizedDefaults:
    """What the sized defaults chose for one robot (module docstring).

    Attributes:
        robot: The robot's name.
        hip_height: Its hip height h, m.
        keys: The gait parameters sized (those its description leaves unset).
        period: The chosen period, s (lengthened where the speed limits need it).
        stride: The stride, m.
        step_height: The step height, m.
        stretch: How much the period was lengthened for the speed limits (1: not at all).
        fastest: The joint that set the stretch, or None.
        speed_ratio: The fastest joint's peak speed over its limit in the chosen gait (None:
            not checked, see ``unchecked``).
        unchecked: Why the speed limits could not be checked (the gait could not be made), or
            None.
        reach: The sized keys set below their similar values because a foot was out of reach
            at them (the working values of :class:`~hexaleg.errors.GaitReachError`, e.g. a
            stride a balancing sway leaves the legs room for), or None.
    """

    robot: str
    hip_height: float
    keys: tuple[str, ...]
    period: float
    stride: float
    step_height: float
    stretch: float = 1.0
    fastest: str | None = None
    speed_ratio: float | None = None
    unchecked: str | None = None
    reach: str | None = None
    pendulum: float = 1.0
    stand: float | None = None
    feet: int = 0
    bound: str | None = None

    @property
    def scale(self) -> float:
        """``k = h / h₀``."""
        return self.hip_height / REFERENCE_HIP_HEIGHT

    @property
    def froude(self) -> float:
        """The chosen gait's Froude number ``(s / T)² / (g h)``."""
        return (self.stride / self.period) ** 2 / (G * self.hip_height)

    @property
    def relative_stride(self) -> float:
        """``s / h``."""
        return self.stride / self.hip_height

    def kept(self, gait: GaitParams) -> tuple[str, ...]:
        """The sized keys that ``gait`` (the run's, after a config file's ``[gait]``) still
        holds at their chosen value."""
        values = {"period": self.period, "stride_length": self.stride,
                  "step_height": self.step_height}
        return tuple(k for k in self.keys if getattr(gait, k) == values[k]
                     and (k != "stride_length" or gait.speed is None))

    def note(self, overridden: Iterable[str] = ()) -> str | None:
        """One line: what the defaults chose, or None when ``overridden`` (keys a config file
        sets) covers every sized key."""
        keys = [k for k in self.keys if k not in set(overridden)]
        if not keys:
            return None
        values = {"period": f"period {self.period:.3g} s", "stride_length":
                  f"stride {self.stride:.3g} m", "step_height": f"step height "
                  f"{self.step_height:.3g} m"}
        line = (f"gait defaults sized to {self.robot} (hip height {self.hip_height:.3g} m, "
                f"x{self.scale:.3g} the default hexapod's) by dynamic similarity (Alexander & "
                f"Jayes 1983: Froude number {REFERENCE_FROUDE:.2g}, relative stride "
                f"{REFERENCE_RELATIVE_STRIDE:.3g}): {', '.join(values[k] for k in keys)}")
        if self.stretch > 1.0 and "period" in keys:
            line += (f"; period lengthened x{self.stretch:.3g} so that {self.fastest} stays "
                     f"within its URDF velocity limit (Froude number {self.froude:.2g})")
        if self.reach is not None:
            line += (f"; shortened to {self.reach} (the feet were out of reach at the similar "
                     "values), the period following by the Froude number")
        if self.unchecked is not None and "period" in keys:
            line += f"; joint speeds not checked against the limits: {self.unchecked}"
        if self.stand is not None and "period" in keys:
            on = "one point foot" if self.feet == 1 else "two point feet"
            if self.pendulum < 1.0 and self.bound is None:
                line += (f"; period shortened x{self.pendulum:.3g} so that its stands on {on} "
                         f"last {self.stand:.3g} time constants of the inverted pendulum "
                         f"(ω₀T, ω₀ = √(g/h), Kajita et al. 2001; the balance controller holds "
                         f"{HOLDS:g}; Froude number {self.froude:.2g})")
            if self.bound is not None:
                shortened = (f"period shortened x{self.pendulum:.3g} (Froude number "
                             f"{self.froude:.2g}), but " if self.pendulum < 1.0 else "")
                line += (f"; {shortened}its stands on {on} last {self.stand:.3g} time constants "
                         f"of the inverted pendulum (ω₀T, ω₀ = √(g/h), Kajita et al. 2001), more "
                         f"than the {HOLDS:g} the balance controller holds: {self.bound} won (a "
                         "shorter period would exceed it)")
        return line

    def as_dict(self) -> dict[str, Any]:
        """JSON form, numbers as ``{value, unit}``."""
        def one(value: float, unit: str) -> dict[str, Any]:
            return {"value": value, "unit": unit}

        return {"robot": self.robot, "sized": list(self.keys),
                "hip_height": one(self.hip_height, "m"), "scale": one(self.scale, "1"),
                "period": one(self.period, "s"), "stride_length": one(self.stride, "m"),
                "step_height": one(self.step_height, "m"),
                "froude": one(self.froude, "1"), "reference_froude": one(REFERENCE_FROUDE, "1"),
                "relative_stride": one(self.relative_stride, "1"),
                "period_stretch": one(self.stretch, "1"), "fastest_joint": self.fastest,
                "speed_ratio": None if self.speed_ratio is None else one(self.speed_ratio, "1"),
                "unchecked": self.unchecked, "reach": self.reach,
                "pendulum_shortening": one(self.pendulum, "1"),
                "stand": None if self.stand is None else one(self.stand, "1"),
                "stand_feet": self.feet, "holds": one(HOLDS, "1"), "pendulum_bound": self.bound,
                "source": "dynamic similarity, Alexander & Jayes, J. Zool. 201, 1983"}


def needs_sizing(desc: RobotDescription) -> tuple[str, ...]:
    """The keys of :data:`SIZED_KEYS` a description leaves unset (none for the built-in
    hexapod, the reference; ``period`` and ``stride_length`` count as set when ``speed``
    is)."""
    if desc.source == BUILTIN and desc.name == "hexaleg":
        return ()
    given = set(desc.gait) | ({"period", "stride_length"} if "speed" in desc.gait else set())
    return tuple(k for k in SIZED_KEYS if k not in given)


def sized_defaults(desc: RobotDescription, gait: GaitParams,
                   robot: Robot | None = None) -> SizedDefaults | None:
    """Size the unset gait parameters of a robot (module docstring).

    Args:
        desc: The robot's description.
        gait: Its gait before sizing: ``GaitParams()`` with the description's overrides and
            its leg groups.
        robot: The loaded robot, or None to load it (``desc.load()``).

    Returns:
        What was chosen, or None when the description sets every key of :data:`SIZED_KEYS`.
        Cached per description, gait and URDF file (its modification time and size).

    Raises:
        RobotModelError: the robot cannot be loaded (its files named).
    """
    keys = needs_sizing(desc)
    if not keys:
        return None
    try:
        stat = desc.urdf_path.stat()
    except OSError:  # loading names the missing file (RobotModelError)
        return _size(desc, gait, desc.load() if robot is None else robot, keys)
    key = (repr(desc), repr(gait), stat.st_mtime_ns, stat.st_size)
    if key not in _CACHE:
        _CACHE[key] = _size(desc, gait, desc.load() if robot is None else robot, keys)
    return _CACHE[key]


def _size(desc: RobotDescription, gait: GaitParams, robot: Robot,
          keys: tuple[str, ...]) -> SizedDefaults:
    h = hip_height(robot, gait)
    k = h / REFERENCE_HIP_HEIGHT
    stride = REFERENCE.stride * k if "stride_length" in keys else gait.stride
    step = REFERENCE.step_height * k if "step_height" in keys else gait.step_height
    period = stride / math.sqrt(REFERENCE_FROUDE * G * h) if "period" in keys else gait.period
    sized = SizedDefaults(robot=desc.name, hip_height=h, keys=keys, period=period,
                          stride=stride, step_height=step)
    if "period" not in keys or stride == 0.0:
        return sized
    stretch, ratio, fastest, reach = 1.0, 0.0, None, None
    for _ in range(MAX_STRETCHES):
        trial = dataclasses.replace(gait, period=period * stretch, stride_length=stride,
                                    step_height=step, samples=min(gait.samples, CHECK_SAMPLES))
        try:
            motion = make_gait(robot, trial)
            ratio, joint = speed_ratio(robot, motion.v)
        except GaitReachError as err:
            fix = err.suggestion
            if not fix or not set(fix) <= {"stride_length", "step_height"} & set(keys):
                return dataclasses.replace(sized, period=period * stretch, stride=stride,
                                           step_height=step, stretch=stretch, fastest=fastest,
                                           reach=reach, unchecked=f"{type(err).__name__}: {err}")
            stride, step = fix.get("stride_length", stride), fix.get("step_height", step)
            period = stride / math.sqrt(REFERENCE_FROUDE * G * h)
            reach = ", ".join(f"{k} {v:.3g} m" for k, v in fix.items())
            continue
        except HexalegError as err:
            return dataclasses.replace(sized, period=period * stretch, stride=stride,
                                       step_height=step, stretch=stretch, fastest=fastest,
                                       reach=reach, unchecked=f"{type(err).__name__}: {err}")
        if ratio <= SPEED_MARGIN:
            break
        stretch, fastest = stretch * ratio / SPEED_MARGIN, joint
    sized = dataclasses.replace(sized, period=period * stretch, stride=stride, step_height=step,
                                stretch=stretch, fastest=fastest, speed_ratio=ratio, reach=reach)
    return _hold(robot, gait, sized, motion)


def _hold(robot: Robot, gait: GaitParams, sized: SizedDefaults, motion: Motion
          ) -> SizedDefaults:
    """``sized`` with its period shortened so that its longest stand on two point feet or fewer
    lasts at most :data:`~hexaleg.motion.stands.HOLDS` time constants of the inverted pendulum
    (module docstring), as far as the joints' velocity limits let it: ``motion`` is the gait at
    ``sized``'s period, at the checked samples. A stand on one point foot is left as it is: no
    period makes it one the balance controller holds (:mod:`hexaleg.motion.stands`)."""
    stand = longest_stand(robot, motion)
    if stand is None or stand.feet != 2 or stand.constants <= HOLDS * (1.0 + HOLD_TOL):
        return dataclasses.replace(sized, stand=None if stand is None else stand.constants,
                                   feet=0 if stand is None else stand.feet)
    period, fastest = stand.holding_period, None
    for _ in range(MAX_STRETCHES):
        trial = dataclasses.replace(gait, period=period, stride_length=sized.stride,
                                    step_height=sized.step_height,
                                    samples=min(gait.samples, CHECK_SAMPLES))
        try:
            shorter = make_gait(robot, trial)
            ratio, joint = speed_ratio(robot, shorter.v)
        except HexalegError as err:  # the shorter gait cannot be made: keep the longer one
            return dataclasses.replace(sized, stand=stand.constants, feet=stand.feet,
                                       bound=f"the gait at {period:.3g} s ({err})")
        if ratio <= SPEED_MARGIN:
            held = longest_stand(robot, shorter) or stand  # the same stance pattern
            if fastest is None and held.constants > HOLDS * (1.0 + HOLD_TOL):
                period = held.holding_period  # the sway moved the centre of mass: again
                continue
            return dataclasses.replace(sized, period=period, speed_ratio=ratio,
                                       pendulum=period / sized.period, stand=held.constants,
                                       feet=held.feet, bound=None if fastest is None else
                                       f"{fastest}'s URDF velocity limit")
        period, fastest = period * ratio / SPEED_MARGIN * (1.0 + OVERSHOOT), joint
        if period >= sized.period:
            break
    return dataclasses.replace(sized, stand=stand.constants, feet=stand.feet,
                               bound=f"{fastest}'s URDF velocity limit" if fastest is not None
                               else f"the sway, which moved the period {MAX_STRETCHES} times")


STANCE_KEYS = ("pattern", "phases", "groups", "duty_factor")
"""The keys that set which feet stand when: the sizing checks the joints' speeds and the stands
on the run's own stance pattern (a crawl's swings are faster than a trot's at one period, its
stands on more feet), so a run that sets them is sized on them."""


def _with_stance(gait: GaitParams, run: GaitParams | None) -> GaitParams:
    """``gait`` with ``run``'s stance keys (:data:`STANCE_KEYS`), or as it is for None."""
    if run is None:
        return gait
    return dataclasses.replace(gait, **{k: getattr(run, k) for k in STANCE_KEYS})


def chosen_defaults(desc: RobotDescription, gait: GaitParams | None = None
                    ) -> SizedDefaults | None:
    """What :func:`robot_gait` sized for this description (None: nothing), for a run whose
    gait is ``gait`` (its stance keys, :data:`STANCE_KEYS`; None: the description's own)."""
    if not needs_sizing(desc):
        return None
    return sized_defaults(desc, _with_stance(robot_gait(desc, sized=False), gait))


def apply(gait: GaitParams, sized: SizedDefaults | None) -> GaitParams:
    """``gait`` with the sized keys set (unchanged for None)."""
    if sized is None:
        return gait
    values: dict[str, Any] = {"period": sized.period, "stride_length": sized.stride,
                              "step_height": sized.step_height}
    return dataclasses.replace(gait, **{k: values[k] for k in sized.keys})


def robot_gait(robot: RobotDescription | str, *, sized: bool = True,
               table: Mapping[str, Any] | None = None, where: str = "gait") -> GaitParams:
    """The default gait of a robot: ``GaitParams()`` with its description's overrides on top,
    and the period, stride and step height it leaves unset sized to the robot by dynamic
    similarity to the default hexapod (this module; Alexander & Jayes,
    J. Zool. 201, 1983: the same Froude number and relative stride, the period lengthened
    where a joint would exceed its URDF velocity limit, and shortened where its stands on two
    point feet would outlast what balance holds, :data:`~hexaleg.motion.stands.HOLDS`). The
    registered robots but hexaleg set their own; hexaleg is the reference.

    Args:
        robot: A robot description, or a name or ``.toml`` path for
            :func:`hexaleg.robot.registry.description`.
        sized: False leaves the unset keys at ``GaitParams()``'s (the gait the sizing
            starts from).
        table: The run's ``[gait]`` table, which the caller puts on top of the result: its
            stance keys (:data:`STANCE_KEYS`) are the ones the sizing checks (None: the
            description's own).
        where: Where ``table`` came from, for its errors.

    Returns:
        The parameters (e.g. Solo-12's trot: period 0.5 s, β = 0.6, groups ``TROT``).
        Sizing loads the robot and makes its gait once per description (cached).

    Raises:
        UnknownNameError: no such robot, or an override is not a field (the message names
            the robot and lists the fields).
        ConfigError, InvalidParameterError: an override has the wrong type or range, or the
            groups do not hold every leg of the robot exactly once.
    """
    desc = description(robot) if isinstance(robot, str) else robot
    gait = GaitParams().updated(desc.gait, f"robot {desc.name!r} gait")
    timed = gait.pattern is not None or gait.phases is not None  # groups unused
    if "groups" not in desc.gait:
        legs = desc.leg_names()
        groups = default_groups(legs, planar=desc.planar_legs())
        if groups is None and not timed:
            raise InvalidParameterError(
                f"{desc.name}: gait.groups", "none given",
                f"leg groups for the legs {', '.join(legs)} (their names do not say side and "
                "place, L/R then F M H or 1 2 …): give [robot.gait] groups = [[…], […]]")
        if groups is not None:
            gait = dataclasses.replace(gait, groups=groups)
    if not timed:
        desc.check_groups(gait.groups)
    if not (sized and needs_sizing(desc)):
        return gait
    run = gait.updated(table, where) if table else None
    return apply(gait, sized_defaults(desc, _with_stance(gait, run)))
