"""The command line's parser rules and help texts (:func:`hexaleg.cli.build_parser` applies them).

:class:`Parser` suggests the command or option meant on a usage error; :data:`GUIDE` gives each
command's time and examples for its ``--help`` (the README's command table quotes the times);
:data:`START` closes the top-level help; :func:`nonempty` refuses an empty value of the options
of :data:`TEXT_OPTIONS`.
"""

from __future__ import annotations

import argparse
import re
from typing import NoReturn

from hexaleg.errors import did_you_mean


class Parser(argparse.ArgumentParser):
    """argparse's parser whose usage errors suggest the command or option meant (``hexaleg
    desing`` → ``design``; ``--robt`` → ``--robot``)."""

    def error(self, message: str) -> NoReturn:
        choice = re.search(r"invalid choice: '([^']*)' \(choose from (.*)\)", message)
        if choice:
            message += did_you_mean(choice.group(1), re.findall(r"'([^']*)'", choice.group(2)))
        unknown = re.search(r"unrecognized arguments: (-[-\w]*)", message)
        if unknown:
            options = [o for a in self._all_actions() for o in a.option_strings]
            message += did_you_mean(unknown.group(1), options)
        super().error(message)

    def _all_actions(self) -> list[argparse.Action]:
        """This parser's actions and those of the subcommand parsers below it."""
        out = list(self._actions)
        for action in self._actions:
            if isinstance(action.choices, dict):
                for sub in action.choices.values():
                    out += sub._actions
        return out


GUIDE: dict[str, tuple[str, tuple[str, ...]]] = {
    "robot": ("under a second", ("hexaleg robot", "hexaleg robot --robot my_robot.toml")),
    "motors": ("under a second; --identify a few seconds", (
        "hexaleg motors", "hexaleg motors AX-18A XM430-W350",
        "hexaleg motors --identify walk.csv")),
    "gait": ("about 2 s", ("hexaleg gait", "hexaleg gait --robot solo12")),
    "paper": ("about 7 s", ("hexaleg paper", "hexaleg paper --out paper-results")),
    "report": ("about 5 s", ("hexaleg report", "hexaleg report --design "
                                               "hexaleg-design/design.json")),
    "design": ("about 20 s on the built-in robot, minutes on a heavy quadruped",
               ("hexaleg design", "hexaleg design --controller position --out my-design")),
    "view": ("about 2 s to draw", ("hexaleg view", "hexaleg view --html walk.html",
                                   "hexaleg view --simulation hexaleg-simulate")),
    "sweep": ("about 2 s for a 40-point grid", ("hexaleg sweep --joints femur --k 0:0.05:41 "
                                                "--dead-zone 0.4", "hexaleg sweep spec.toml")),
    "simulate": ("about 3 s", ("hexaleg simulate", "hexaleg simulate --springs "
                                                   "hexaleg-design/design.json --controller "
                                                   "position")),
    "codesign": ("about 5 minutes", ("hexaleg codesign",
                                                           "hexaleg codesign --speed 0.1")),
}
"""Per command: how long it takes on the built-in robot (measured on two cores, nothing else
running) and examples. ``--help`` shows both; the README's command table quotes the times
(``tests/test_readme.py``)."""
START = """start with:
  hexaleg report      which springs to fit, and the gait's energy with them (about 5 s)
  hexaleg design      the full answer: every spring family, the springs to buy (about 20 s)
  hexaleg simulate    the report's answer checked in a MuJoCo simulation (about 3 s)
  hexaleg view        the gait in the browser, foot forces and joint colours

each command: hexaleg COMMAND --help (what it writes, how long it takes, examples);
the documentation is docs/ in the source repository"""
"""The top-level ``--help``'s closing lines: where a newcomer starts."""


TEXT_OPTIONS = ("out", "config", "robot", "design", "springs", "html", "identify", "host",
                "simulation", "motion", "scheduler", "spec", "urdf", "srdf", "cycle", "pattern")
"""The options that take a name or a path: each refuses an empty value (``--out ""`` once
wrote into the working directory, ``--html ""`` served instead of writing, ``--host ""``
listened on every interface)."""


def nonempty(text: str) -> str:
    """An option's value when it is not empty (:data:`TEXT_OPTIONS`)."""
    if not text.strip():
        raise argparse.ArgumentTypeError("an empty value; give a name or a path, or leave the "
                                         "option out for its default")
    return text


__all__ = ["GUIDE", "START", "TEXT_OPTIONS", "Parser", "nonempty"]
