"""Tests of hexaleg.design.families.family and the registry: every family's law is its basis
times its magnitudes, its mirror the reflected law, its geometry checked by name; the families
in containment waves."""

import numpy as np
import pytest

from hexaleg.design.families import FAMILIES, family
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.robot.springs import basis

GEOMETRY = {"linear": {}, "dead_zone": {"theta_minus": -0.1, "theta_plus": 0.2},
            "preloaded": {"theta_minus": -0.1, "theta_plus": 0.2},
            "one_sided": {"contact": 0.1, "side": "below"},
            "stiffening": {"above_1": 0.0, "above_2": 0.2, "below_1": -0.1, "below_2": -0.3}}


@pytest.mark.parametrize("name", FAMILIES)
def test_spring_of_magnitudes_is_the_basis_times_them(name):
    fam = family(name)
    geometry = fam.check(GEOMETRY[name], "g")
    terms = fam.terms(geometry, 0.5)
    assert [t.name for t in terms] == list(fam.magnitudes)
    x = np.linspace(0.3, 1.2, len(terms))
    q = np.linspace(-0.5, 1.5, 201)
    np.testing.assert_allclose(fam.spring(geometry, 0.5, x).torque(q), basis(terms, q) @ x,
                               atol=1e-15)
    assert fam.nonnegative().shape == (len(terms),)


@pytest.mark.parametrize("name", [n for n in FAMILIES if family(n).angles])
def test_idle_angles_are_exactly_those_that_do_not_change_the_law(name):
    """Family.idle names an angle when its stop's magnitudes are 0 (or the solver's round-off of
    0), and then moving that angle leaves the torque unchanged; an angle with a magnitude moves
    the torque. Catches a rule that marks an angle by the wrong magnitudes (k_above_1's angle
    for k_above_2), or that keeps printing an angle past which nothing acts."""
    fam = family(name)
    geometry = fam.check(GEOMETRY[name], "g")
    q = np.linspace(-0.6, 0.6, 241)

    def torque(g, m):
        return fam.spring(g, 0.0, [m[k] for k in fam.magnitudes]).torque(q)

    full = dict.fromkeys(fam.magnitudes, 0.7)
    assert fam.idle(full) == ()
    for angle in fam.angles:
        moved = {**geometry, angle: float(geometry[angle]) + 0.03}
        assert not np.allclose(torque(moved, full), torque(geometry, full))
        unused = {**full, **dict.fromkeys(fam.stops[angle], 0.0)}
        assert fam.idle(unused) == (angle,)
        np.testing.assert_array_equal(torque(moved, unused), torque(geometry, unused))
        assert fam.idle({**unused, fam.stops[angle][0]: 1e-13}) == (angle,)  # a solver's 0
        small = {**unused, fam.stops[angle][0]: 1e-7}
        assert fam.idle(small) == () and fam.idle(small, zero=1e-6) == (angle,)


def test_only_the_linear_constant_may_be_negative():
    assert list(family("linear").nonnegative()) == [True, False]
    assert family("preloaded").nonnegative().all()


def test_check_names_what_is_wrong():
    with pytest.raises(UnknownNameError, match="spring family"):
        family("coil")
    with pytest.raises(UnknownNameError, match="theta_k"):
        family("dead_zone").check({"theta_k": 0.1}, "g")
    with pytest.raises(InvalidParameterError, match=r"g\.theta_plus"):
        family("dead_zone").check({"theta_minus": 0.1}, "g")
    with pytest.raises(InvalidParameterError, match=r"g\.theta_minus"):
        family("dead_zone").check({"theta_minus": 0.1, "theta_plus": 0.1}, "g")
    family("preloaded").check({"theta_minus": 0.1, "theta_plus": 0.1}, "g")  # zero width is fine
    with pytest.raises(InvalidParameterError, match=r"g\.above_1"):
        family("stiffening").check({**GEOMETRY["stiffening"], "above_1": 0.3}, "g")
    with pytest.raises(UnknownNameError, match=r"g\.side"):
        family("one_sided").check({"contact": 0.0, "side": "up"}, "g")
    with pytest.raises(InvalidParameterError, match=r"g\.contact"):
        family("one_sided").check({"contact": "0"}, "g")


@pytest.mark.parametrize("name", FAMILIES)
def test_a_mirrored_spring_is_the_reflected_law(name):
    """mirror(): τ'(q) = −τ(2c − q) and U'(q) = U(2c − q) at random angles, for random valid
    geometries and magnitudes; mirroring twice gives the spring back."""
    rng = np.random.default_rng(7)
    fam = family(name)
    c = 0.4
    for _ in range(5):
        angles = np.sort(rng.uniform(-0.6, 0.6, len(fam.angles)))
        if name == "stiffening":
            angles = np.array([angles[0], angles[1], angles[3], angles[2]])
        geometry = dict(zip(fam.angles, (float(a) for a in angles), strict=True))
        if name == "one_sided":
            geometry["side"] = str(rng.choice(["above", "below"]))
        x = rng.uniform(0.01, 0.5, len(fam.magnitudes))
        if name == "linear":
            x[1] = rng.uniform(-0.3, 0.3)
        g2, x2 = fam.mirror(geometry, x)
        fam.check(g2, "mirrored")
        law, image = fam.spring(geometry, c, x), fam.spring(g2, c, x2)
        q = rng.uniform(c - 1.5, c + 1.5, 200)
        np.testing.assert_allclose(image.torque(q), -law.torque(2 * c - q), atol=1e-12)
        np.testing.assert_allclose(image.energy(q) - image.energy(np.array(c)),
                                   law.energy(2 * c - q) - law.energy(np.array(c)), atol=1e-12)
        g3, x3 = fam.mirror(g2, x2)
        assert g3 == {k: (float(v) if k != "side" else v) for k, v in geometry.items()}
        np.testing.assert_array_equal(x3, x)


def test_containment_waves_put_a_family_after_those_it_contains():
    from hexaleg.design.families import containment_waves

    assert containment_waves(["linear", "one_sided", "preloaded", "dead_zone"]) == [
        ["linear", "one_sided", "dead_zone"], ["preloaded"]]
    assert containment_waves(["stiffening", "dead_zone"]) == [["dead_zone"], ["stiffening"]]
    assert containment_waves(["preloaded", "one_sided"]) == [["one_sided"], ["preloaded"]]
    assert containment_waves(["stiffening", "linear"]) == [["stiffening", "linear"]]


def test_the_registry_is_one_entry_a_family():
    """FAMILIES, CONTAINS and design.json's classes all come from the registry."""
    from hexaleg.design import families
    from hexaleg.design.springs import law_json as spring_json

    assert families.FAMILIES == ("linear", "dead_zone", "preloaded", "one_sided", "stiffening")
    assert {n: f.law for n, f in families._FAMILIES.items()} == spring_json.CLASSES
    assert families.CONTAINS == {n: f.contains for n, f in families._FAMILIES.items()
                                 if f.contains}
    for f in families._FAMILIES.values():
        assert set(f.stops) == set(f.angles)
        assert {m for ms in f.stops.values() for m in ms} <= set(f.magnitudes)


def test_a_family_contains_only_what_it_says():
    from hexaleg.design.families import embed

    with pytest.raises(InvalidParameterError, match="one_sided in dead_zone"):
        embed("dead_zone", "one_sided", {"contact": 0.1, "side": "above"}, {}, (-1.0, 1.0))


def test_a_magnitude_at_the_design_zero_is_none_and_twice_it_is_one():
    """``Family.idle`` reads the one design zero (ZERO_MAGNITUDE), inclusive: a stop whose
    magnitudes are at most it has no angle, one with twice it keeps its angle. Fails on a strict
    ``<`` (the old ZERO_STIFFNESS rule) and on any other threshold a decade off."""
    from hexaleg.design.families import ZERO_MAGNITUDE

    fam = family("preloaded")
    at = {"k_plus": ZERO_MAGNITUDE, "preload_plus": -ZERO_MAGNITUDE, "k_minus": 0.02,
          "preload_minus": 0.0}
    assert fam.idle(at) == ("theta_plus",)
    assert fam.idle({**at, "preload_plus": 2 * ZERO_MAGNITUDE}) == ()
    assert fam.idle({**at, "k_plus": 10 * ZERO_MAGNITUDE}) == ()
    assert family("one_sided").idle({"k": ZERO_MAGNITUDE / 10, "preload": 0.0}) == ("contact",)
