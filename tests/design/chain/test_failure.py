"""Tests of hexaleg.design.chain.failure: a stage after the candidates that fails ends the
stages after it, not the design (issue #55). The command's files of such a design are tested in
tests/commands/design/test_stages.py (slow)."""

from __future__ import annotations

import pytest

import hexaleg
from hexaleg.design.chain import chain as chain_module
from hexaleg.design.chain.chain import DesignChain
from hexaleg.design.chain.failure import STAGE_KEYS
from hexaleg.errors import InvalidParameterError

LINEAR = {"design": {"samples": 100, "families": ["linear"], "pareto_fractions": [0.5]}}
"""A design of one family (~1 s to its Pareto front)."""


def test_every_stage_after_the_candidates_names_its_keys():
    assert set(STAGE_KEYS) == set(chain_module.STAGES) - {"candidates"}


def test_a_later_stage_that_fails_keeps_the_stages_before_it(monkeypatch):
    """A stage after the candidates that fails ends the stages after it, not the design: the
    result holds the candidates and the Pareto front, and names the stage, its error and the
    keys that set it."""
    def fails(*_a, **_k):
        raise InvalidParameterError("design.life_cycles", 1e30, "an injected failure")

    monkeypatch.setattr(chain_module, "envelope_and_fatigue", fails)
    chain = DesignChain(hexaleg.Scenario.from_tables("hexaleg", LINEAR))
    r = chain.run(("candidates", "pareto", "envelope", "fold"))
    assert r.stages == ("candidates", "pareto") and r.pareto and not r.envelope
    assert r.failed is not None and r.failed.stage == "envelope"
    assert r.failed.left_out == ("fold",) and "life_cycles" in r.failed.keys
    assert "invalid design.life_cycles = 1e+30" in r.failed.error
    assert r.notes[0] == r.failed.line()
    assert r.to_dict()["failed"]["stage"] == "envelope"
    assert DesignChain(hexaleg.Scenario.from_tables("hexaleg", LINEAR)).run(
        ("candidates",)).failed is None


def test_the_first_stage_failing_ends_the_design(monkeypatch):
    """Nothing is kept when the candidates fail: the design is them."""
    def fails(*_a, **_k):
        raise InvalidParameterError("design.families", "x", "an injected failure")

    monkeypatch.setattr(chain_module, "family_candidates", fails)
    with pytest.raises(InvalidParameterError, match="injected"):
        DesignChain(hexaleg.Scenario.from_tables("hexaleg", LINEAR)).run(("candidates",))
