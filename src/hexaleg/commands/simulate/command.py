"""The ``hexaleg simulate`` subcommand: its parser and its run (registered in
:data:`hexaleg.cli.SUBCOMMANDS`): the study built from the run
(:func:`hexaleg.commands.simulate.study.load_study`), simulated, its files published whole in
the output folder; a run that did not walk ends in a :class:`~hexaleg.errors.SimulationError`
after the files are written.
"""

from __future__ import annotations

import argparse

from hexaleg.commands.options import add_motion_option, add_quiet, print_warnings
from hexaleg.robot.registry import ROBOT_HELP  # loaded by `import hexaleg` already
from hexaleg.simulation.balance import MODES as FEEDBACK  # no MuJoCo: it loads with a model
from hexaleg.simulation.controllers import CONTROLLERS  # no MuJoCo either


def add(sub: argparse._SubParsersAction) -> None:
    """Add ``simulate`` to the subcommands."""
    p = sub.add_parser("simulate", help="forward simulation in MuJoCo with and without the "
                                        "springs: simulate.html, .json and .md, predicted vs "
                                        "simulated energy and saving, the motion of each run")
    p.add_argument("--robot", default="hexaleg", help=ROBOT_HELP + " (default %(default)s)")
    p.add_argument("--config", help="TOML file with optional [gait], [motor], [contact] and "
                                    "[simulate] tables (docs/simulate.md)")
    p.add_argument("--springs", help="design file (design.json: springs per joint as family and "
                                     "parameters, docs/simulate.md); default: the springs "
                                     "hexaleg report leads with (its answer)")
    p.add_argument("--controller", choices=CONTROLLERS,
                   help="servo: torque feedforward + PD, or position-only PD "
                        "(default: feedforward, or the config's)")
    p.add_argument("--feedback", choices=FEEDBACK,
                   help="balance feedback on the body: auto (where the gait stands on fewer "
                        "than three feet or open loop falls), on, off (open loop) (default: "
                        "auto, or the config's)")
    p.add_argument("--cycles", type=int, help="gait cycles simulated (default 4, the last 2 "
                                              "evaluated)")
    p.add_argument("--timestep", type=float, help="simulation timestep, s (default: 0.5 ms, "
                                                  "or less for a fine gait or stiff servos)")
    p.add_argument("--sensitivity", action="store_true",
                   help="also rerun with the servo gains ×0.25…×4, the ground 4× softer and "
                        "stiffer, half the friction, the no-slip pass and the other controller")
    p.add_argument("--out", default="hexaleg-simulate",
                   help="output directory (default: %(default)s)")
    add_quiet(p)
    add_motion_option(p, run, "simulate.json")


def run(args: argparse.Namespace) -> int:
    """Simulate the run with and without the springs and write its files."""
    import time

    from hexaleg.commands.options import load_run, progress_of
    from hexaleg.commands.simulate.study import load_study
    from hexaleg.commands.simulate.write import simulation_data, summary, write_simulation
    from hexaleg.errors import SimulationError
    from hexaleg.outputs.directory import OutputFolder
    from hexaleg.simulation.motion_file import write_motions

    overrides = {"controller": args.controller, "feedback": args.feedback,
                 "cycles": args.cycles, "timestep": args.timestep}
    if args.cycles is not None and args.cycles >= 2:
        overrides["evaluate"] = min(2, args.cycles - 1)
    say = progress_of(args, "simulate") or (lambda _line: None)
    start = time.perf_counter()
    run = load_run(args.robot, args.config, args.motion, args.cycle, args)
    study = load_study(run, args.springs, overrides)
    settings = study.settings
    say(f"the robot, its gait and the springs to simulate ({time.perf_counter() - start:.1f} s); "
        f"simulating {settings.cycles} cycles with the springs and without, side by side, "
        f"{settings.controller} servos")
    with OutputFolder(args.out, "simulation") as folder:  # locked; published whole at the end
        start = time.perf_counter()
        s = study.run()
        say(f"simulated: springs {s.with_springs.verdict}, baseline {s.baseline.verdict} "
            f"({time.perf_counter() - start:.1f} s)")
        rows = None
        if args.sensitivity and s.walks:
            from hexaleg.simulation.sensitivity import sensitivity

            say("the sensitivity reruns (servo gains, ground, friction, the other controller)")
            rows = sensitivity(s)
        data = simulation_data(s, design=study.design, notes=study.notes, sensitivity=rows,
                               warnings=study.warnings, gait_defaults=study.gait_defaults)
        js, md, html = (folder.directory / p.name
                        for p in write_simulation(folder.staging, data))
        motions = ", ".join(str(folder.directory / m.name)
                            for m in write_motions(folder.staging, s))
        folder.publish()
    for note in study.notes:
        print(f"note: {note}")
    print_warnings(study.warnings)
    print(summary(data))
    print(f"wrote {js}, {md}, {motions}; open {html} (replay: hexaleg view --simulation "
          f"{args.out})")
    if not s.walks:
        raise SimulationError("; ".join(f"{r.name} run {r.verdict}: {r.message}"
                                        for r in (s.with_springs, s.baseline) if not r.walks))
    return 0


__all__ = ["add", "run"]
