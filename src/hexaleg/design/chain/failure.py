"""A design stage that failed after others finished: :class:`StageFailure`, and the keys that
set each stage (:data:`STAGE_KEYS`).

The first stage (the candidates: every family's optimum) is the design; when it fails there is
nothing to keep and its error ends the run. A later stage's failure ends the stages after it,
and the design is written with the stages before it (issue #55: "a design never refuses what
it chose … each stage's result is written as it goes and a later stage's failure keeps them").
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

STAGE_KEYS: dict[str, str] = {
    "pareto": "[design] pareto_fractions (the Pareto points) and max_torque",
    "ranking": "[design] controller (--controller: the servo the designs are simulated under)",
    "tolerance": "[design] stop_tolerance (0: no tolerance design)",
    "envelope": "[design] life_cycles, safety_factor and materials (the parts' checks)",
    "fold": "[mission] metres_per_fold and the robot's stand and sphere poses",
    "maps": "[design] map_period, map_stride, map_payload, map_mu, map_slope and map_pattern; "
            "robustness = false leaves the maps and the robust design out",
    "robust": "[design] robust_period, robust_stride, robust_payload, robust_mu and "
              "robust_mode; robustness = false leaves the maps and the robust design out",
    "proof": "[design] controller (--controller: the servo the recommendation is simulated "
             "under) and the gait it walks ([gait])",
}
"""Each stage after the candidates → the keys that set it, which a refusal names (the error
itself names the value it refused)."""


@dataclass(frozen=True)
class StageFailure:
    """A stage that failed, and what it leaves out.

    Attributes:
        stage: The stage (:data:`hexaleg.design.chain.chain.STAGES`).
        error: The error, as ``"Type: message"``.
        keys: The keys that set the stage (:data:`STAGE_KEYS`).
        left_out: The stages after it, not run.
    """

    stage: str
    error: str
    keys: str
    left_out: tuple[str, ...]

    def line(self) -> str:
        """One sentence: what failed, what the design holds, what changes it."""
        rest = f"; {', '.join(self.left_out)} not run" if self.left_out else ""
        return (f"the {self.stage} stage failed ({self.error}){rest}; the design holds the "
                f"stages before it; the keys that set the {self.stage} stage: {self.keys}")

    def table(self) -> dict[str, Any]:
        """``design.json``'s ``failed``: the stage, the error, the keys, the stages left out."""
        return {"stage": self.stage, "error": self.error, "keys": self.keys,
                "left_out": list(self.left_out)}


__all__ = ["STAGE_KEYS", "StageFailure"]
