"""The ``hexaleg codesign`` subcommand: its parser and its run (registered in
:data:`hexaleg.cli.SUBCOMMANDS`).

``--config F`` reads a ``[codesign]`` table: ``speed``, ``pattern``, ``family``, ``samples``,
``final_samples``, ``max_evaluations``, ``restarts``, ``grouping``, ``rules``, ``curve``,
``simulate``, ``controller``, ``motion``, ``feedback``, ``timing``, ``starts``, ``duty_high``,
``body_high``, a ``[codesign.constraints]``
table of :class:`~hexaleg.design.codesign.gait_evaluation.Constraints` and a
``[codesign.design]`` table of
the full spring rules' ``[design]`` keys
(:func:`~hexaleg.design.codesign.full_rules.rule_params`); the command line's ``--speed``,
``--pattern``, ``--controller``, ``--motion``, ``--feedback``, ``--timing``, ``--starts``,
``--duty-high``, ``--body-high`` and ``--no-rules`` win over the file.
``--motion optimal`` adds the optimal motion's rows
(:mod:`hexaleg.design.codesign.optimal_rows`) and writes each optimal motion as a motion log
(``optimal_no_springs.csv``, ``optimal_springs.csv``) that every command's ``--motion`` reads.
"""

from __future__ import annotations

import argparse

from hexaleg.commands.options import add_quiet
from hexaleg.design.codesign.box import BODY_CEILING, BODY_FLOOR, BODY_HIGH, DUTY_CEILING, DUTY_HIGH
from hexaleg.design.codesign.starts import STARTS
from hexaleg.design.codesign.timing import TIMINGS
from hexaleg.simulation.balance import MODES as FEEDBACK  # no MuJoCo: it loads with a model
from hexaleg.simulation.controllers import SERVOS  # no MuJoCo either


def add(sub: argparse._SubParsersAction) -> None:
    """Add ``codesign`` to the subcommands."""
    p = sub.add_parser("codesign", help="the gait and its springs designed together for a "
                                        "required speed: the four rows, the chosen gait and "
                                        "springs, codesign.html, codesign.json")
    p.add_argument("--robot", default="hexaleg", help="a registered robot or a description "
                                                      "FILE.toml (default %(default)s)")
    p.add_argument("--speed", type=float, help="required speed, m/s (default 0.06)")
    p.add_argument("--pattern", help="gait pattern (default: the robot's)")
    p.add_argument("--config", help="TOML file with a [codesign] table (docs/codesign.md)")
    p.add_argument("--controller", choices=SERVOS,
                   help="the servo the robot runs: the search's finalists and the springs to buy "
                        "are simulated under it; both: each, judged by the worse (default both)")
    p.add_argument("--motion", choices=("gait", "optimal"),
                   help="gait (default): the parametric gait; optimal: also the motion itself "
                        "optimised from the chosen gait without and with its springs, each row "
                        "simulated (needs pip install \"hexaleg[optimal]\"; about a minute more)")
    p.add_argument("--feedback", choices=FEEDBACK,
                   help="with --motion optimal: balance feedback on the body in every optimal "
                        "row's simulation, as hexaleg simulate's: auto (where the gait stands on "
                        "fewer than three feet or open loop falls), on (every row closed loop), "
                        "off (open loop) (default: auto, or the config's)")
    p.add_argument("--timing", choices=TIMINGS,
                   help="with --motion optimal: the optimal motion's contact timing: gait (the "
                        "chosen gait's) or search (duty factor and period searched about it, "
                        "five solves more, each judged by its rebuilt cycle's prediction) "
                        "(default: gait, or the config's)")
    p.add_argument("--starts", choices=STARTS,
                   help="with --motion optimal: the optimal motion's starts: gait (the gait at "
                        "the timing used) or lattice (step height, body height and swing "
                        "weight moved, six or seven solves more, each judged by its rebuilt "
                        "cycle's prediction; the alternation from the best) (default: lattice, "
                        "or the config's)")
    p.add_argument("--duty-high", dest="duty_high", type=float,
                   help="the searches' highest duty factor, in [the default gait's + 0.05, "
                        f"{DUTY_CEILING:g}] (default {DUTY_HIGH:g}, or the config's)")
    p.add_argument("--body-high", dest="body_high", type=float,
                   help="the searches' highest body height, × the default gait's, in "
                        f"[{BODY_FLOOR:g}, {BODY_CEILING:g}] (default {BODY_HIGH:g}, or the "
                        "config's)")
    p.add_argument("--no-rules", dest="rules", action="store_false", default=None,
                   help="leave out hexaleg design's full spring rules (tolerance, envelope, "
                        "fatigue, arbor, parsimony) on the chosen gait, about a minute: the "
                        "search's answer alone, the inner program's springs recommended")
    p.add_argument("--out", default="hexaleg-codesign",
                   help="output directory (default: %(default)s)")
    add_quiet(p)
    p.set_defaults(func=run)


IGNORED = {
    "gait": "it searches the gait itself: set its pattern and speed in [codesign] (pattern, "
            "speed) or on the command line (--pattern, --speed)",
}
"""Tables of a config file that other commands read and codesign would ignore: refused, with
where their settings go."""


def run(args: argparse.Namespace) -> int:
    """Run the co-design and write its files."""
    from hexaleg.commands.codesign.write import write_codesign
    from hexaleg.commands.options import load_run, progress_of
    from hexaleg.design.codesign.build import codesign_settings
    from hexaleg.errors import ConfigError

    scenario = load_run(args.robot, args.config, args=args)
    for table, instead in IGNORED.items():  # a value codesign would not use is refused
        if scenario.tables.get(table):
            raise ConfigError(f"{scenario.where} [{table}]: hexaleg codesign does not read it "
                              f"— {instead}")
    kwargs = codesign_settings(scenario.table("codesign"), f"{scenario.where} [codesign]",
                               scenario)
    for key in ("speed", "pattern", "controller", "motion", "feedback", "timing", "starts",
                "duty_high", "body_high"):
        if getattr(args, key) is not None:
            kwargs[key] = getattr(args, key)
    if args.rules is not None:
        kwargs["rules"] = args.rules
    result, files = write_codesign(args.out, robot=scenario,
                                   progress=progress_of(args, "codesign"), **kwargs)
    print(result.summary())
    print(f"wrote {len(files)} files to {args.out}; open {args.out}/codesign.html")
    return 0


__all__ = ["add", "run"]
