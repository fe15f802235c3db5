"""The full spring rules run beside the co-design: their ``[design]`` settings, and the forked
process that computes them (its result or error comes back whole; it ends with a killed
co-design)."""

from __future__ import annotations

import pytest

from hexaleg.design.codesign.full_rules import RULE_FAMILIES, Background, rule_params
from hexaleg.errors import InvalidParameterError, UnknownNameError


def test_rule_params_defaults_and_bad_keys():
    p = rule_params()
    assert p.families == RULE_FAMILIES and "dead_zone" not in p.families and not p.robustness
    assert rule_params(stop_tolerance=0.0, robustness=True).robustness
    with pytest.raises(UnknownNameError, match="familes"):
        rule_params(familes=["linear"])


def _fails():
    raise InvalidParameterError("x", 1, "2")


def test_the_rules_run_beside_the_search_and_come_back_whole():
    """Background: the child's result (pickled back) or its error, raised here; close() stops a
    child whose result was never asked for."""
    import time

    assert Background(lambda: {"a": [1.5, "b"]}).result() == {"a": [1.5, "b"]}
    with pytest.raises(InvalidParameterError, match="x"):
        Background(_fails).result()
    slow = Background(lambda: time.sleep(60))
    start = time.perf_counter()
    slow.close()
    assert time.perf_counter() - start < 30 and slow._process is None


def test_the_rules_child_ends_with_a_killed_co_design():
    """The rules' child is a worker of the co-design: SIGKILL of the co-design ends it (it had
    computed on as an orphan, holding the output folder's lock)."""
    import signal
    import subprocess
    import sys

    from processes import HAS_PROC, children, wait_gone

    if not HAS_PROC:
        pytest.skip("finds the child in /proc")
    code = ("import time\nfrom hexaleg.design.codesign.full_rules import Background\n"
            "b = Background(lambda: time.sleep(120))\nprint('started', flush=True)\n"
            "time.sleep(120)\n")
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    assert proc.stdout is not None and proc.stdout.readline().strip() == "started"
    child = children(proc.pid)
    assert len(child) == 1
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    assert wait_gone(child) == set()
