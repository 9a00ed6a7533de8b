"""Route 1 (quadratic form) against route 2 (direct geometry), and balance."""

import numpy as np
import pytest

from springlab import Spring, random_directions, serial_chain
from springlab.energy import geometry, quadratic
from springlab.papers import juang2023 as paper


def test_two_link_gravity_energy_closed_form():
    chain = serial_chain([0.5], [0.2], [3.0], g=9.81)
    theta = np.linspace(0, np.pi, 7)
    X = chain.directions(np.stack([np.zeros_like(theta), theta, np.zeros_like(theta)], -1)[:, None, :])
    expected = 3.0 * 9.81 * 0.2 * np.cos(theta)
    np.testing.assert_allclose(geometry.gravity_energy(chain, X), expected, atol=1e-12)
    np.testing.assert_allclose(quadratic.quadratic_gravity_energy(chain, X), expected, atol=1e-12)


def test_spring_energy_closed_form():
    # S(1,2) between a point 0.1 m above the base and 0.3 m along a horizontal link
    chain = serial_chain([0.5], [0.2], [3.0])
    X = np.array([[[1, 0, 0], [0, 1, 0]]], dtype=float)
    spring = Spring(1, 2, a=0.1, b=0.3, k=100.0)
    expected = 0.5 * 100.0 * (0.1**2 + 0.3**2)
    np.testing.assert_allclose(geometry.spring_energy(chain, [spring], X), expected)
    np.testing.assert_allclose(quadratic.quadratic_energy(chain, [spring], X), expected)


@pytest.mark.parametrize("scale", [1.0, 0.9, 1.3])
def test_routes_agree_on_the_example_arm(arm, exact_springs, rng, scale):
    springs = [s.scaled(scale) for s in exact_springs]
    X = random_directions(arm.n, 500, rng)
    u1 = quadratic.quadratic_energy(arm, springs, X)
    u2 = geometry.total_energy(arm, springs, X)
    np.testing.assert_allclose(u1, u2, rtol=0, atol=1e-10)


def test_routes_agree_with_chunking(arm, exact_springs, rng):
    X = random_directions(arm.n, 1001, rng)
    springs = [s.scaled(0.8) for s in exact_springs]
    full = quadratic.quadratic_energy(arm, springs, X)
    np.testing.assert_allclose(quadratic.quadratic_energy(arm, springs, X, chunk=64), full, atol=1e-12)
    np.testing.assert_allclose(geometry.total_energy(arm, springs, X, chunk=100), full, atol=1e-10)


def test_exact_design_is_balanced_and_scaled_one_is_not(arm, exact_springs, rng):
    X = random_directions(arm.n, 1000, rng)
    gravity_range = np.ptp(geometry.gravity_energy(arm, X))
    assert np.ptp(geometry.total_energy(arm, exact_springs, X)) < 1e-10 * gravity_range
    assert np.abs(quadratic.balance_residual(arm, exact_springs)).max() < 1e-12
    unbalanced = [s.scaled(0.9) for s in exact_springs]
    assert np.ptp(geometry.total_energy(arm, unbalanced, X)) > 1e-2 * gravity_range


def test_printed_springs_leave_a_residual_within_the_bound(arm, rng):
    printed = paper.table3_springs()
    X = random_directions(arm.n, 2000, rng)
    spread = np.ptp(geometry.total_energy(arm, printed, X))
    bound = quadratic.energy_variation_bound(arm, printed)
    assert 1e-3 < spread <= bound
    # Eq. (48f) carries the largest residual: r_3 (k14 b14 + k24 b24) - k34 a34 b34 with b rounded up
    R = quadratic.balance_residual(arm, printed)
    assert np.argmax(np.abs(R)) == np.ravel_multi_index((2, 3), R.shape)


def test_free_length_spring_energy():
    chain = serial_chain([0.5], [0.2], [3.0])
    X = np.array([[[1, 0, 0], [0, 1, 0]]], dtype=float)
    spring = Spring(1, 2, a=0.3, b=0.4, k=100.0, free_length=0.1)
    np.testing.assert_allclose(geometry.spring_energy(chain, [spring], X), 0.5 * 100.0 * (0.5 - 0.1) ** 2)


def test_attachment_points_follow_the_sign_convention(arm):
    X = np.tile([1.0, 0, 0], (1, arm.n, 1))  # all links straight up
    A, B = geometry.attachment_points(arm, Spring(3, 4, a=-0.2, b=-0.1, k=1.0), X)
    # joint 3 (distal of link 3) is at r2 + r3 = 0.54 m; A is 0.2 m back on link 3, B 0.1 m behind link 4's base
    np.testing.assert_allclose(A[0], [0.34, 0, 0])
    np.testing.assert_allclose(B[0], [0.44, 0, 0])


def _plain_holding_torques(chain, springs, X):
    """The holding torques as the docstring writes them, term by term in numpy (the compiled
    kernel of route 2 sums gravity from the end link inwards; this sums it link by link)."""
    joints = chain.joint_positions(X)
    com = chain.com_positions(X)
    weight = chain.g * np.asarray(chain.m)[None, :, None] * np.array([1.0, 0.0, 0.0])
    out = np.zeros((X.shape[0], chain.n - 1, 3))
    for j in range(2, chain.n + 1):
        out[:, j - 2] = np.cross(com[:, j - 2:] - joints[:, j - 2][:, None], weight[:, j - 2:]).sum(axis=1)
    for s in springs:
        A = joints[:, s.i - 1] + s.a * X[:, s.i - 1]
        B = joints[:, s.j - 2] + s.b * X[:, s.j - 1]
        pull = B - A
        if s.free_length:
            pull = pull * (1.0 - s.free_length / np.linalg.norm(pull, axis=1, keepdims=True))
        for j in range(s.i + 1, s.j + 1):
            out[:, j - 2] += s.k * np.cross(B - joints[:, j - 2], pull)
    return out


def test_the_holding_torque_kernel_equals_the_plain_sum(arm, exact_springs, rng):
    springs = list(exact_springs) + [Spring(1, 3, 0.05, 0.1, 200.0, free_length=0.03), Spring(2, 4, -0.1, 0.05, 80.0)]
    X = random_directions(arm.n, 3000, rng)
    ours, plain = geometry.holding_torques(arm, springs, X), _plain_holding_torques(arm, springs, X)
    assert np.abs(ours - plain).max() < 1e-12 * np.abs(plain).max()
    assert np.abs(geometry.holding_torques(arm, exact_springs, X)).max() < 1e-9  # balanced: no torque
    assert np.abs(geometry.holding_torques(arm, [s.scaled(0.9) for s in exact_springs], X)).max() > 0.1  # control


def test_route_1s_compiled_kernel_and_numpy_expression_agree_to_the_last_bit(arm, exact_springs, rng):
    X = random_directions(arm.n, quadratic.COMPILED_FROM + 7, rng)
    XT = np.ascontiguousarray(X.transpose(1, 2, 0))
    M = quadratic.energy_matrix(arm, [s.scaled(0.9) for s in exact_springs])  # unbalanced: the energy varies
    compiled = quadratic.quadratic_energy_component_major(M, XT)  # N above the threshold: the kernel
    small = np.concatenate([quadratic.quadratic_energy_component_major(M, XT[:, :, k:k + 1000])
                            for k in range(0, XT.shape[2], 1000)])  # below it: numpy
    assert np.array_equal(compiled, small) and np.ptp(compiled) > 1.0
    np.testing.assert_allclose(compiled, geometry.total_energy(arm, [s.scaled(0.9) for s in exact_springs], X),
                               atol=1e-9)


def test_holding_torques_write_into_a_given_array_or_refuse_it(arm, exact_springs, rng):
    from springlab.errors import SpringlabError

    X = random_directions(arm.n, 50, rng)
    out = np.full((50, arm.n - 1, 3), np.nan)
    got = geometry.holding_torques(arm, [s.scaled(0.9) for s in exact_springs], X, out=out)
    assert got is out and np.array_equal(out, geometry.holding_torques(arm, [s.scaled(0.9) for s in exact_springs], X))
    for bad in (np.empty((49, arm.n - 1, 3)), np.empty((50, arm.n - 1, 3), dtype=np.float32), [[0.0]]):
        with pytest.raises(SpringlabError, match="out must be"):
            geometry.holding_torques(arm, exact_springs, X, out=bad)
