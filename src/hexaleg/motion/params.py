"""Parameters of the periodic leg-group gaits: :class:`GaitParams`, from code, TOML or a robot.

A robot's description (:class:`hexaleg.robot.description.RobotDescription`) holds only plain
overrides of these parameters (its ``gait`` mapping, e.g. Solo-12's trot);
:func:`~hexaleg.motion.scaling.robot_gait` turns them into parameters.
"""

from __future__ import annotations

import dataclasses
import importlib
import json
import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hexaleg.checks import is_real, named_arguments, real
from hexaleg.config import from_mapping, load_toml
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.limits import check_samples
from hexaleg.motion.patterns import PATTERNS, check_pattern, leg_places
from hexaleg.robot.registry import TROT

TRIPODS: tuple[tuple[str, ...], ...] = (("LF", "RM", "LH"), ("RF", "LM", "RH"))
"""The hexapod's two tripods, the default leg groups; group 0 touches down at t = 0."""


def default_groups(legs: Sequence[str], *, planar: bool = False
                   ) -> tuple[tuple[str, ...], ...] | None:
    """The alternating gait of a robot's legs, the default when its description gives no
    ``groups``: along each side, front to back, the legs alternate between two groups, and the
    two sides start in opposite groups — every leg's neighbours (ahead, behind, across) swing
    while it stands. That is the tripod on six legs (:data:`TRIPODS`) and the trot on four
    (:data:`hexaleg.robot.registry.TROT`); on two, the legs alternate. Planar legs (two joints,
    the foot in the leg's plane) cannot step or sway sideways, so there the legs at one place go
    together on both sides and the places alternate: the bound on four, whose support lines run
    across the body and whose sway runs along it, in the legs' planes.

    Args:
        legs: The robot's leg names in hexaleg's convention: side ``L``/``R`` then the place
            from front to back, ``F M H`` or ``1 2 3 …`` (:mod:`hexaleg.robot.discover`).
        planar: Every leg moves its foot in a plane (two joints).

    Returns:
        The two groups, or None when a name does not follow the convention.
    """
    places = leg_places(legs)
    if places is None:
        return None
    if planar:
        first = tuple(name for name, (_, rank) in zip(legs, places, strict=True) if rank % 2 == 0)
    else:
        for known in (TRIPODS, TROT):
            if sorted(legs) == sorted(leg for group in known for leg in group):
                return known
        first = tuple(name for name, (side, rank) in zip(legs, places, strict=True)
                      if (rank % 2 == 0) == (side == "L"))
    second = tuple(name for name in legs if name not in first)
    return tuple(g for g in (first, second) if g)


BALANCE_MODES: tuple[str, ...] = ("auto", "none", "sway", "shift", "zmp")
"""``GaitParams.balance``: ``"auto"`` sways the body (:mod:`hexaleg.motion.balance`) when some
sample stands on exactly two feet and none on fewer, sways and turns it so that the zero-moment
point is on the stance foot (:mod:`hexaleg.motion.zmp`) when some sample stands on one foot, and
shifts it over the support polygon (:mod:`hexaleg.motion.shift`) when every sample stands on
three or more feet but the static margin falls below ``min_static_margin``; ``"none"`` keeps
the constant-twist body; ``"sway"``, ``"zmp"`` and ``"shift"`` ask for one of the three (an
error where it does not apply)."""
ATTITUDES: tuple[str, ...] = ("plane", "level")
"""``GaitParams.attitude`` on a slope: the body parallel to the ground, or level."""
MARGIN_FRACTION = 0.1
"""The default ``min_static_margin``: this fraction of the nearest nominal foothold's horizontal
distance from the base (0.0189 m for hexaleg, 0.0258 m for Solo-12 with their own gaits)."""


PERIOD_RANGE = (0.01, 3600.0)
"""The gait cycles :class:`GaitParams` takes, s: from 10 ms (faster than any legged animal's
stride, a running cockroach's ≈ 40 ms) to an hour; beyond them the trajectories' arithmetic
overflows or underflows (a period of 1e300 s ended in an OverflowError)."""
MAX_LENGTH = 100.0
"""The largest stride, step or body height and foot radius :class:`GaitParams` takes, m: far
beyond any legged robot, and a bound that keeps the trajectories' arithmetic finite."""
MAX_YAW_RATE = 100.0
"""The largest turn rate :class:`GaitParams` takes, rad/s (16 turns a second)."""


@named_arguments
@dataclass(frozen=True)
class GaitParams:
    """Parameters of a periodic leg-group gait (SI).

    Attributes:
        period: Cycle duration, s, in :data:`PERIOD_RANGE`.
        duty_factor: β, the fraction of the cycle each foot is in stance, in (0, 1); None
            (the default): the pattern's conventional β₀ (:data:`hexaleg.motion.patterns.PATTERNS`),
            0.5 without a pattern. Stored resolved.
        stride_length: Body travel per cycle, m (≥ 0); also each foot's travel per swing. The
            stance stroke of a foot relative to the body is β · stride.
        speed: Forward speed, m/s. When given (not None) it **wins** over ``stride_length``:
            the stride becomes ``speed · period``. Default None: speed = stride / period.
        step_height: Apex height of the swing foot above the ground, m (> 0).
        body_height: Height of the base above the ground, m (> 0); None: the depth of the feet
            below the base in the robot's ``stand`` pose (0.0913 m for hexaleg).
        foot_radius: Horizontal distance of each nominal foothold from the base's z axis (stance
            width), m (> 0); None: the footholds of the ``stand`` pose (0.1889 m for hexaleg).
        yaw_rate: Turning rate about the vertical, rad/s; the body then follows a circular arc.
        samples: Samples per cycle, in [``MIN_SAMPLES``, ``MAX_SAMPLES``] (the upper bound
            follows from memory, :data:`hexaleg.motion.limits.MAX_SAMPLES`).
        groups: Legs that move together; group i touches down at t = i · period / len(groups)
            and every leg of the robot must be in exactly one group.
        balance: ``"auto"`` (default): when the gait stands on exactly two feet at some sample
            (a trot, a pace) and never on fewer, the body sways horizontally so that the two
            feet can carry the motion (see :func:`hexaleg.motion.legged.sample_gait`); gaits
            with three or more feet always (the hexapod's tripod) are unchanged. ``"none"``:
            never sway (the rigid constant-twist body, whose two-foot samples have no contact
            forces). ``"shift"``: shift the body over the support polygon of a gait on three or
            more feet (a crawl) to keep ``min_static_margin`` (:mod:`hexaleg.motion.shift`;
            ``"auto"`` does so when the margin falls below it); ``"sway"``: the two-foot sway;
            ``"zmp"``: the walking pattern of a gait on one foot at some sample (a biped, a
            crawl at β < 0.5; :mod:`hexaleg.motion.zmp`, ``"auto"`` picks it there).
        pattern: A named pattern (:data:`hexaleg.motion.patterns.PATTERNS`: ``tripod``,
            ``ripple``, ``wave``, ``crawl``, ``trot``, ``pace``) whose touch-down offsets come from
            the leg names; it wins over ``groups``. None: ``groups``.
        phases: Each leg's touch-down offset, a fraction of the period in [0, 1), in the
            robot's leg order (custom patterns); wins over ``pattern`` and ``groups``.
        heading: The walking direction in the base frame, rad: the angle from the robot's
            forward axis (:attr:`hexaleg.robot.model.Robot.heading`) about the base z axis,
            positive to the left; π/2 crab-walks to the left.
        slope: Inclination of the ground along the walking direction, rad, in (−π/2, π/2),
            positive uphill (:mod:`hexaleg.motion.ground`).
        cross_slope: Inclination of the ground across the walking direction, rad, in
            (−π/2, π/2), positive when the ground rises to the left.
        attitude: On a slope, ``"plane"`` (the body parallel to the ground, ``body_height``
            measured along its normal; default) or ``"level"`` (the body level,
            ``body_height`` measured vertically; needs ``yaw_rate`` = 0).
        min_static_margin: The static margin the body shift keeps, m (≥ 0); None: 10 % of the
            nearest nominal foothold's horizontal distance from the base
            (:data:`MARGIN_FRACTION`).
    """

    period: float = 1.0
    duty_factor: float = None  # type: ignore[assignment]  # None → β₀ in __post_init__
    stride_length: float = 0.06
    speed: float | None = None
    step_height: float = 0.03
    body_height: float | None = None
    foot_radius: float | None = None
    yaw_rate: float = 0.0
    samples: int = 1000
    groups: tuple[tuple[str, ...], ...] = TRIPODS
    balance: str = "auto"
    pattern: str | None = None
    phases: tuple[float, ...] | None = None
    heading: float = 0.0
    slope: float = 0.0
    cross_slope: float = 0.0
    attitude: str = "plane"
    min_static_margin: float | None = None

    def __post_init__(self) -> None:
        real("period", self.period, low=PERIOD_RANGE[0], high=PERIOD_RANGE[1],
             allowed=f"a cycle of {PERIOD_RANGE[0]:g} s to {PERIOD_RANGE[1]:g} s")
        if self.pattern is not None:
            check_pattern(self.pattern)
        if self.duty_factor is None:
            beta = PATTERNS[self.pattern].duty_factor if self.pattern is not None else 0.5
            object.__setattr__(self, "duty_factor", float(beta))
        real("duty_factor", self.duty_factor, low=0.0, high=1.0, low_open=True, high_open=True,
             allowed="β in (0, 1), or None for the pattern's own")
        if self.phases is not None:
            phases = self.phases
            if isinstance(phases, (str, bytes)) or not isinstance(phases, Sequence) \
                    or not all(is_real(x) and 0.0 <= x < 1.0 for x in phases):
                raise InvalidParameterError("phases", phases, "None or one touch-down offset "
                                            "per leg, each a fraction of the period in [0, 1)")
            if self.pattern is not None:
                raise InvalidParameterError("phases", phases, f"None when pattern = "
                                            f"{self.pattern!r} is given (give one of the two)")
            object.__setattr__(self, "phases", tuple(float(x) for x in phases))
        real("heading", self.heading, allowed="a finite angle (rad)")
        for name in ("slope", "cross_slope"):
            real(name, getattr(self, name), low=-math.pi / 2, high=math.pi / 2, low_open=True,
                 high_open=True, allowed="an angle in (−π/2, π/2) rad, positive uphill")
        if self.attitude not in ATTITUDES:
            raise InvalidParameterError("attitude", self.attitude, " or ".join(ATTITUDES))
        if self.attitude == "level" and self.yaw_rate != 0.0 and (self.slope or self.cross_slope):
            raise InvalidParameterError("attitude", self.attitude, "'plane' when turning on a "
                                        "slope (yaw_rate ≠ 0): a level body cannot follow the "
                                        "turn about the ground's normal; or yaw_rate = 0")
        if self.min_static_margin is not None:
            real("min_static_margin", self.min_static_margin, low=0.0,
                 allowed="None or a finite number ≥ 0 (m)")
        real("stride_length", self.stride_length, low=0.0, high=MAX_LENGTH,
             allowed=f"0 to {MAX_LENGTH:g} m")
        if self.speed is not None:
            real("speed", self.speed, low=0.0, high=MAX_LENGTH / PERIOD_RANGE[0],
                 allowed=f"None or 0 to {MAX_LENGTH / PERIOD_RANGE[0]:g} m/s")
        real("step_height", self.step_height, low=0.0, low_open=True, high=MAX_LENGTH,
             allowed=f"more than 0 and at most {MAX_LENGTH:g} m")
        for name in ("body_height", "foot_radius"):
            value = getattr(self, name)
            if value is not None:
                real(name, value, low=0.0, low_open=True, high=MAX_LENGTH,
                     allowed=f"None, or more than 0 and at most {MAX_LENGTH:g} m")
        real("yaw_rate", self.yaw_rate, low=-MAX_YAW_RATE, high=MAX_YAW_RATE,
             allowed=f"a turn rate within ±{MAX_YAW_RATE:g} rad/s")
        object.__setattr__(self, "samples", check_samples(self.samples))
        if isinstance(self.groups, str) or not isinstance(self.groups, Sequence) or any(
                isinstance(g, str) or not isinstance(g, Sequence) for g in self.groups):
            # a string is a sequence, but "LF" is not the groups ('L',), ('F',)
            raise InvalidParameterError("groups", self.groups, "a list of groups, each a list "
                                        "of leg names, e.g. [['LF', 'RM', 'LH'], ['RF', 'LM', "
                                        "'RH']]")
        groups = tuple(tuple(g) for g in self.groups)
        legs = [leg for g in groups for leg in g]
        if not groups or any(not g for g in groups) or len(set(legs)) != len(legs) \
                or not all(isinstance(leg, str) for leg in legs):
            raise InvalidParameterError("groups", self.groups,
                                        "non-empty groups of leg names, each leg in one group")
        object.__setattr__(self, "groups", groups)
        if self.balance not in BALANCE_MODES:
            raise InvalidParameterError("balance", self.balance, " or ".join(BALANCE_MODES))

    @property
    def stride(self) -> float:
        """Body travel per cycle, m (``speed · period`` when ``speed`` is given)."""
        return self.speed * self.period if self.speed is not None else self.stride_length

    @property
    def velocity(self) -> float:
        """Forward speed, m/s (``stride / period`` unless ``speed`` is given)."""
        return self.stride / self.period

    def balance_mode(self, fewest: int) -> str:
        """``"sway"``, ``"zmp"``, ``"shift"`` or ``"none"`` for this gait whose samples stand on
        at least ``fewest`` feet (``balance``; ``"auto"`` picks by ``fewest``).

        Args:
            fewest: The fewest stance feet of any sample of the cycle.

        Raises:
            InvalidParameterError: ``"sway"`` asked for a gait that is not on two feet at its
                fewest, ``"zmp"`` for one not on one foot at its fewest, or ``"shift"`` for one
                with fewer than three feet at some sample.
        """
        if self.balance == "none":
            return "none"
        if self.balance == "sway" and fewest != 2:
            raise InvalidParameterError("balance", "sway", f"a gait on exactly two feet at its "
                                        f"fewest (this one stands on {fewest}): 'auto', 'shift' "
                                        "or 'none'")
        if self.balance == "zmp" and fewest != 1:
            raise InvalidParameterError("balance", "zmp", f"a gait on one foot at its fewest "
                                        f"(this one stands on {fewest}): 'auto', 'sway', "
                                        "'shift' or 'none'")
        if self.balance == "shift" and fewest < 3:
            raise InvalidParameterError("balance", "shift", f"a gait on three or more feet at "
                                        f"every sample (this one stands on {fewest} at its "
                                        "fewest: no support polygon); 'auto', 'sway' or 'none'")
        if self.balance == "auto":
            return {0: "none", 1: "zmp", 2: "sway"}.get(fewest, "shift")
        return self.balance

    @classmethod
    def from_toml(cls, source: str | Path | Mapping[str, Any]) -> GaitParams:
        """Gait parameters from a TOML file or an already parsed table.

        Args:
            source: A TOML file (its ``[gait]`` table, or the top level when it has none) or a
                mapping of field names to values.

        Returns:
            The parameters; missing keys take their defaults.

        Raises:
            ConfigError: the file cannot be read, or a value has the wrong type.
            UnknownNameError: a key is not a field (the message lists the fields).
            InvalidParameterError: a value is out of range.
        """
        if isinstance(source, Mapping):
            return from_mapping(cls, source, "gait")
        data = load_toml(source)
        table = data.get("gait", data)
        return from_mapping(cls, table, f"{source} [gait]" if "gait" in data else str(source))

    @classmethod
    def for_robot(cls, robot: Any, *, sized: bool = True) -> GaitParams:
        """Deprecated (0.1; it leaves in the next release): the robot's default gait, now
        :func:`hexaleg.motion.scaling.robot_gait` (same arguments, same result), to which it
        delegates with a :class:`DeprecationWarning`. The sizing module imports this one, so
        it is imported by name when called, as ``hexaleg``'s deprecated names are."""
        warnings.warn("GaitParams.for_robot is deprecated and leaves in the next release: use "
                      "hexaleg.motion.scaling.robot_gait(robot, sized=...)", DeprecationWarning,
                      stacklevel=2)
        scaling = importlib.import_module("hexaleg.motion.scaling")
        return scaling.robot_gait(robot, sized=sized)

    def updated(self, table: Mapping[str, Any], where: str = "gait") -> GaitParams:
        """This gait with the keys of a TOML table on top (e.g. a file's ``[gait]`` over a
        robot's own gait); keys the table does not set keep this gait's values, except that a
        table choosing the legs' timing (``pattern``, ``phases`` or ``groups``) clears this
        gait's other two, and a ``pattern`` or ``phases`` without ``duty_factor`` takes the
        pattern's own β₀ (0.5 for phases).

        Raises:
            UnknownNameError, ConfigError, InvalidParameterError: as :meth:`from_toml`.
        """
        given = from_mapping(type(self), table, where)
        changes = {k: getattr(given, k) for k in table}
        leg_keys = ("pattern", "phases", "groups")
        if any(k in table for k in leg_keys):  # the table's choice of legs replaces this one's
            changes.update({k: None for k in leg_keys[:2] if k not in table})
            if "duty_factor" not in table and "groups" not in table:
                changes["duty_factor"] = None  # the pattern's own β₀
        return dataclasses.replace(self, **changes)


GAIT_UNITS: dict[str, str] = {
    "period": "s", "duty_factor": "1", "stride_length": "m", "speed": "m/s", "step_height": "m",
    "body_height": "m", "foot_radius": "m", "yaw_rate": "rad/s", "phases": "1", "heading": "rad",
    "slope": "rad", "cross_slope": "rad", "min_static_margin": "m"}
"""The SI unit of each numeric field of :class:`GaitParams` (``{value, unit}`` in JSON)."""


def gait_parameters(gait: GaitParams) -> dict[str, Any]:
    """The gait's set fields for JSON, numbers as ``{value, unit}`` (:data:`GAIT_UNITS`): what
    :func:`hexaleg.design.chain.design_file.design_gait` reads back to a :class:`GaitParams`
    that walks the same. With a ``speed`` the stride is ``speed × period`` (the speed wins),
    and ``stride_length`` is written as that: the stride the gait walks, not the field's unused
    default (#41: 0.06 m for a co-designed gait that walks 0.102 m a cycle)."""
    plain = json.loads(json.dumps({f.name: getattr(gait, f.name) for f in dataclasses.fields(gait)
                                   if getattr(gait, f.name) is not None}))
    plain["stride_length"] = gait.stride
    return {k: {"value": v, "unit": GAIT_UNITS[k]} if k in GAIT_UNITS else v
            for k, v in plain.items()}
