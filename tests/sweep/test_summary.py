"""The sweep summary: the best point per set compared per cycle within one gait and per metre
across gaits, with units, solver noise printed as 0 (tables built here; the runner's own tables
are test_runner's)."""

from __future__ import annotations

import math

import pandas as pd
import pytest

from hexaleg.errors import UnknownNameError
from hexaleg.sweep.summary import distance_per_cycle, normalisation, summary


def _table(periods: list[float], strides: list[float], energies: list[float],
           k_minus: list[float] | None = None, speed: list[float] | None = None) -> pd.DataFrame:
    n = len(periods)
    return pd.DataFrame({
        "point": range(n), "status": ["ok"] * n, "springs": ["femur"] * n,
        "gait.period": periods, "gait.stride_length": strides,
        "gait.speed": speed if speed is not None else [math.nan] * n,
        "femur.k_plus": [0.0132] * n,
        "femur.k_minus": k_minus if k_minus is not None else [0.0] * n,
        "electrical": energies, "baseline.electrical": [2 * e for e in energies],
        "saving.electrical": [0.5] * n,
        "peak_torque": [1.0 + i for i in range(n)], "baseline.peak_torque": [3.0] * n,
        "saving.peak_torque": [0.1] * n,
    })


def test_one_gait_compares_energy_per_cycle():
    table = _table([1.0, 1.0], [0.06, 0.06], [1.5, 1.4])
    assert normalisation(table, "electrical")[::2] == ("electrical", "J per cycle")
    text = summary(table)
    assert "femur: electrical = 1.4 J per cycle (no springs 2.8 J per cycle), saving +50.00 % " \
           "at point 1" in text


def test_different_periods_compare_per_metre_not_per_cycle():
    """The shorter period uses less energy per cycle but walks less per second for the same
    stride … here the half period walks half the stride: 0.6 J per 0.03 m = 20 J/m against
    1.0 J per 0.06 m = 16.7 J/m, so the longer period is the best (per cycle it would lose)."""
    table = _table([0.5, 1.0], [0.03, 0.06], [0.6, 1.0])
    label, divisor, unit = normalisation(table, "electrical")
    assert (label, unit) == ("electrical per metre", "J/m")
    assert list(divisor) == [0.03, 0.06]
    text = summary(table)
    assert "compared in J/m" in text
    assert "femur: electrical per metre = 16.6667 J/m (no springs 33.3333 J/m)" in text
    assert "at point 1:" in text and "gait.period = 1" in text


def test_a_set_speed_gives_the_distance_and_standing_gaits_compare_per_second():
    table = _table([0.5, 1.0], [0.06, 0.06], [0.6, 1.0], speed=[0.1, math.nan])
    assert list(distance_per_cycle(table)) == pytest.approx([0.05, 0.06])
    standing = _table([0.5, 1.0], [0.0, 0.0], [0.6, 1.0])
    label, _, unit = normalisation(standing, "electrical")
    assert (label, unit) == ("electrical per second", "W")
    assert "electrical per second = 1 W" in summary(standing)


def test_torques_compare_as_they_are():
    table = _table([0.5, 1.0], [0.03, 0.06], [0.6, 1.0])
    assert normalisation(table, "peak_torque") == ("peak_torque", None, "N·m")
    assert "peak_torque = 1 N·m (no springs 3 N·m)" in summary(table, "peak_torque")


def test_solver_noise_prints_as_zero_and_real_values_do_not():
    table = _table([1.0, 1.0], [0.06, 0.06], [1.5, 1.4], k_minus=[6.146e-13, 0.02])
    noisy = _table([1.0, 1.0], [0.06, 0.06], [1.4, 1.5], k_minus=[6.146e-13, 0.02])
    assert "femur.k_minus = 0.02" in summary(table)
    assert "femur.k_minus = 0," in summary(noisy) + "," and "e-13" not in summary(noisy)
    assert "femur.k_plus = 0.0132" in summary(noisy)


def test_unknown_metric_is_named():
    with pytest.raises(UnknownNameError, match="electrical"):
        summary(_table([1.0], [0.06], [1.0]), "nope")


def test_a_column_of_noise_prints_as_zero_beside_real_parameters():
    """One point (the optimum of a family): its k is the solver's 1.8e-13 beside a preload."""
    table = _table([1.0], [0.06], [1.0], k_minus=[1.838e-13])
    text = summary(table)
    assert "femur.k_minus = 0" in text and "e-13" not in text
    assert "femur.k_plus = 0.0132" in text
