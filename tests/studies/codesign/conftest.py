"""One co-design of the default robot at 0.06 m/s, shared by the co-design tests (~9 s on a
quiet machine: 50 samples a cycle in the search, 100 in the rows, 30 evaluations a search, 2
restarts, the search's answer alone — still ≤ 0.65 of the default gait and below the
sequential design), and the same result with the full spring rules applied to its chosen gait
at a reduced cost (60 samples a cycle, the one-sided family alone: ~8 s). The full-size run —
the default search and the default rules, whose kept log asserts the issue's bars — is
``analysis/codesign_hexaleg.py`` (run by ``tests/test_examples.py``)."""

from __future__ import annotations

import dataclasses

import pytest

from hexaleg.studies.codesign.build import codesign, full_rules, rule_params

BUDGET = {"samples": 50, "final_samples": 100, "max_evaluations": 30, "restarts": 2,
          "rules": False}
"""The reduced search of the shared co-design (the default: 100, 200, 100, 3, with the rules)."""
RULES_SAMPLES = 60
"""Samples a cycle of the reduced full rules (the default: the rows' 200)."""


@pytest.fixture(scope="session")
def codesigned():
    return codesign("hexaleg", 0.06, **BUDGET)


@pytest.fixture(scope="session")
def ruled(codesigned):
    """``codesigned`` with the full spring rules (one-sided family) on its chosen gait."""
    chosen = dataclasses.replace(codesigned.chosen, samples=RULES_SAMPLES)
    rules = full_rules("hexaleg", chosen, codesigned.constraints, lambda _m: None,
                       rule_params(families=["one_sided"]))
    return dataclasses.replace(codesigned, rules=rules)
