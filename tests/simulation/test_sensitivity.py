"""The sensitivity table: each variant reruns both simulations; a variant that cannot run is a
row with its error."""

from __future__ import annotations

import dataclasses

from hexaleg.commands.simulate.write import page, simulation_data
from hexaleg.simulation.sensitivity import VARIANTS, sensitivity


def test_sensitivity_rows_in_the_json_and_the_page(feedforward):
    """A variant reruns both simulations; a variant that cannot run is a row with its error."""
    variants = [next(v for v in VARIANTS if v[0] == "servo kp ×2"),
                ("too coarse", lambda s: dataclasses.replace(s, timestep=0.01))]
    rows = sensitivity(feedforward, variants)
    assert rows[0]["verdict"] == "walks" and abs(rows[0]["simulated"] - rows[0]["predicted"]) < 0.02
    assert rows[1]["simulated"] is None and "timestep" in rows[1]["verdict"]
    data = simulation_data(feedforward, sensitivity=rows)
    assert data["sensitivity"][0]["simulated_saving"]["unit"] == "%"
    assert "| servo kp ×2 | feedforward | walks |" in page(data)


def test_variants_change_what_they_say(feedforward):
    settings = feedforward.settings
    changed = {label: change(settings) for label, change in VARIANTS}
    assert changed["as set"] == settings
    assert changed["servo kp ×4"].kp_scale == 4 * settings.kp_scale
    assert changed["servo gains ×0.25"].kd_scale == 0.25 * settings.kd_scale
    assert changed["ground stiffness ×4"].stiffness == 4 * settings.stiffness
    assert changed["friction μ 0.3"].mu == 0.3 and changed["no-slip pass"].noslip
    assert changed["other controller"].controller == "position"


def test_the_controller_check_is_the_two_controllers_simulations(prepared, optimal, feedforward,
                                                                 position):
    """hexaleg design's proof: one row per controller, each the saving of that controller's own
    simulation (the unchanged variant reuses the base run instead of simulating it again)."""
    import numpy as np

    from hexaleg.simulation.sensitivity import controller_check

    rows = controller_check(prepared, optimal.springs, "joule", feedforward.settings)
    assert [r["controller"] for r in rows] == ["feedforward", "position"]
    for row, s in zip(rows, (feedforward, position), strict=True):
        assert row["verdict"] == "walks"
        np.testing.assert_allclose(row["simulated"], s.simulated()[2], rtol=1e-12)
        np.testing.assert_allclose([row["predicted_electrical"], row["predicted_baseline"],
                                    row["predicted"]], s.predicted(), rtol=1e-12)


def test_an_unchanged_variant_reuses_the_base_simulation(feedforward, monkeypatch):
    import hexaleg.simulation.sensitivity as module

    def refuse(*args, **kwargs):
        raise AssertionError("simulated again")

    monkeypatch.setattr(module, "simulate", refuse)
    (row,) = sensitivity(feedforward, [("as set", lambda s: s)])
    assert row["simulated"] == feedforward.simulated()[2]
