"""Route 3: the exudyn model against route 2, and its hold, torque and trajectory checks."""

import numpy as np
import pytest

from springlab import Spring, SpringlabError, UnbalanceableError, random_directions, serial_chain
from springlab.energy import simulation as sim
from springlab.energy.multibody import SimSettings
from springlab.model.trajectories import Sweep
from springlab.papers import juang2023 as paper


@pytest.fixture(scope="module")
def poses():
    return random_directions(4, 20, np.random.default_rng(2024))


def test_hold_test_balanced_stays_and_control_falls(arm, exact_springs, poses):
    result = sim.hold_test(arm, exact_springs, poses, duration=2.0)
    assert result.balanced.max_tip_drift < 1e-9
    assert result.balanced.max_angle_drift < 1e-8
    assert result.control.max_tip_drift > 1e-2
    assert result.control.springs_scale == 0.9


@pytest.mark.parametrize("scale", [1.0, 0.9])
def test_holding_torques_equal_route_2(arm, exact_springs, poses, scale):
    springs = [s.scaled(scale) for s in exact_springs]
    result = sim.holding_torques(arm, springs, poses)
    assert result.max_difference < 1e-9
    if scale == 1.0:
        assert np.abs(result.simulated).max() < 1e-9
    else:
        assert np.abs(result.simulated).max() > 0.1


def test_dense_and_sparse_linear_solvers_agree(arm, exact_springs, poses):
    """The dense LU (the default, faster on springlab's small models) and exudyn's sparse one
    give the same torques and the same drift, to the Newton tolerance; the control falls in both."""
    springs = [s.scaled(0.9) for s in exact_springs]
    dense = sim.holding_torques(arm, springs, poses[:5])
    sparse = sim.holding_torques(arm, springs, poses[:5], settings=SimSettings(dense=False))
    assert np.abs(dense.simulated - sparse.simulated).max() < 1e-9 < np.abs(dense.simulated).max()
    held = [sim.hold_test(arm, exact_springs, poses[:2], duration=0.5, settings=SimSettings(dense=d)) for d in (True, False)]
    assert all(h.balanced.max_tip_drift < 1e-9 and h.control.max_tip_drift > 1e-3 for h in held)
    assert abs(held[0].control.max_tip_drift - held[1].control.max_tip_drift) < 1e-8


def test_holding_torque_sign_against_a_known_load():
    # one horizontal link along +y, no springs: the joint must hold m g d about -z
    chain = serial_chain([0.5], [0.2], [3.0], g=9.81)
    X = np.array([[[1.0, 0, 0], [0, 1.0, 0]]])
    result = sim.holding_torques(chain, [], X)
    np.testing.assert_allclose(result.simulated[0, 0], [0, 0, -3.0 * 9.81 * 0.2], atol=1e-12)
    # a spring from 0.1 m above the base to 0.3 m along the link pulls it up: +z, k a b
    spring = Spring(1, 2, a=0.1, b=0.3, k=100.0)
    result = sim.holding_torques(chain, [spring], X)
    np.testing.assert_allclose(result.simulated[0, 0], [0, 0, -3.0 * 9.81 * 0.2 + 100.0 * 0.1 * 0.3], atol=1e-12)


def test_free_length_springs_and_payload_match_route_2(arm, exact_springs, poses):
    springs = [Spring(s.i, s.j, s.a, s.b, s.k, free_length=0.02) for s in exact_springs]
    heavy = arm.with_payload(1.5)
    result = sim.holding_torques(heavy, springs, poses[:5])
    assert result.max_difference < 1e-9
    assert np.abs(result.simulated).max() > 0.1


def test_follow_table_4_keeps_the_total_energy(arm, exact_springs):
    sweep = Sweep(paper.TABLE_4_INITIAL, paper.TABLE_4_ROTATION, paper.DURATION, law="quintic")
    result = sim.follow(arm, exact_springs, sweep, samples=151)
    gravity_range = np.ptp(result.gravity)
    assert gravity_range > 1.0
    assert np.ptp(result.total) < 1e-9 * gravity_range
    for key, ours in (("gravity", result.gravity), ("springs", result.springs), ("total", result.total)):
        assert np.abs(ours - result.route2[key]).max() < 1e-9 * gravity_range, key
    assert result.torques.shape == (151, 3, 3)
    np.testing.assert_allclose(result.t[[0, -1]], [0.0, paper.DURATION])


def test_unbalanced_follow_varies(arm, exact_springs):
    sweep = Sweep(paper.TABLE_5_INITIAL, paper.TABLE_5_ROTATION, 5.0, law="quintic")
    result = sim.follow(arm, [s.scaled(0.9) for s in exact_springs], sweep, samples=21)
    assert np.ptp(result.total) > 0.1
    assert np.abs(result.total - result.route2["total"]).max() < 1e-9 * np.ptp(result.gravity)


def test_model_writes_no_files(arm, exact_springs, poses, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    sim.hold_test(arm, exact_springs, poses[:1], duration=0.1)
    sim.holding_torques(arm, exact_springs, poses[:1])
    assert list(tmp_path.iterdir()) == []


def test_bad_inputs(arm, exact_springs, poses):
    off_link = [Spring(1, 2, a=0.1, b=0.5, k=100.0)]  # b beyond link 2's 0.30 m
    with pytest.raises(UnbalanceableError, match="off the link"):
        sim.hold_test(arm, off_link, poses[:1], duration=0.1)
    bad = poses[:2].copy()
    bad[1, 2, 0] = np.nan
    with pytest.raises(SpringlabError, match="NaN"):
        sim.holding_torques(arm, exact_springs, bad)
    moving = Sweep(paper.TABLE_4_INITIAL, paper.TABLE_4_ROTATION, paper.DURATION, law="linear")
    with pytest.raises(SpringlabError, match="does not start at rest"):
        sim.follow(arm, exact_springs, moving)
    with pytest.raises(SpringlabError, match="duration"):
        sim.hold_test(arm, exact_springs, poses[:1], duration=0.0)
    with pytest.raises(SpringlabError, match="payload"):
        arm.with_payload(-1.0)


@pytest.fixture(scope="module")
def planar_arm():
    """A 3-link arm in the vertical x-y plane: revolute joints about z, balanced by
    springs solved from the same Eqs. (39) (the planar case of the spatial form)."""
    from springlab.design.solve import design_for

    chain = serial_chain([0.4, 0.3, 0.25], [0.2, 0.15, 0.1], [3.0, 2.0, 1.0], joints=[(0, 0, 1)] * 3)
    _, springs = design_for(chain, seed=1)
    return chain, springs


def test_revolute_chain_holds_and_matches_route_2(planar_arm):
    chain, springs = planar_arm
    angles = chain.random_angles(6, np.random.default_rng(7))
    assert np.all(angles[..., 1:] == 0)
    X = chain.directions(angles)
    np.testing.assert_allclose(X[..., 2], 0, atol=1e-15)  # the arm stays in the x-y plane
    hold = sim.hold_test(chain, springs, angles, duration=1.0)
    assert hold.balanced.max_tip_drift < 1e-9 < 1e-2 < hold.control.max_tip_drift
    for scale in (1.0, 0.9):
        torques = sim.holding_torques(chain, [s.scaled(scale) for s in springs], angles)
        assert torques.max_difference < 1e-9
    sweep = Sweep(angles[0], angles[1] - angles[0], 4.0)
    run = sim.follow(chain, springs, sweep, samples=41)
    assert np.ptp(run.total) < 1e-9 * np.ptp(run.gravity)
    assert np.abs(run.total - run.route2["total"]).max() < 1e-9 * np.ptp(run.gravity)


def test_revolute_chain_needs_angles(planar_arm):
    chain, springs = planar_arm
    with pytest.raises(SpringlabError, match="joint angles"):
        sim.holding_torques(chain, springs, random_directions(4, 2, 0))
    with pytest.raises(SpringlabError, match="revolute"):
        chain.frames(np.ones((1, 3, 3)))
    with pytest.raises(SpringlabError, match="revolute axis"):
        serial_chain([0.4], [0.2], [3.0], joints=[(0, 0, 0)])


def test_mixed_joints_with_an_oblique_axis(exact_springs):
    chain = serial_chain([0.30, 0.24, 0.20], [0.15, 0.12, 0.10], [4.0, 3.2, 2.8], g=9.8,
                         joints=["spherical", (0.0, 1.0, 1.0), (0.0, 0.0, 1.0)])
    angles = chain.random_angles(4, np.random.default_rng(11))
    hold = sim.hold_test(chain, exact_springs, angles, duration=1.0)
    assert hold.balanced.max_tip_drift < 1e-9 < 1e-2 < hold.control.max_tip_drift
    torques = sim.holding_torques(chain, [s.scaled(0.9) for s in exact_springs], angles)
    assert torques.max_difference < 1e-9
    run = sim.follow(chain, exact_springs, Sweep(angles[2], angles[3] - angles[2], 3.0), samples=31)
    assert np.ptp(run.total) < 1e-9 * np.ptp(run.gravity)
    with pytest.raises(SpringlabError, match="revolute"):
        bad = np.zeros((3, 3))
        bad[1, 2] = 0.3  # a psi angle on the revolute joint 3
        sim.follow(chain, exact_springs, Sweep(np.zeros((3, 3)), bad, 3.0))


def test_light_damping_changes_nothing_at_rest(arm, exact_springs, poses):
    damped = sim.SimSettings(damping=2.0)
    hold = sim.hold_test(arm, exact_springs, poses[:3], duration=1.0, settings=damped)
    assert hold.balanced.max_tip_drift < 1e-9 < 1e-2 < hold.control.max_tip_drift
    assert sim.holding_torques(arm, exact_springs, poses[:3], settings=damped).max_difference < 1e-9


def test_holding_torque_sign_against_an_applied_torque(arm, poses):
    # a known torque applied to the end link must be held by every joint: tau_held = route 2 - T
    from exudyn.utilities import LoadTorqueVector, MarkerBodyRigid

    from springlab.energy.geometry import holding_torques as analytic
    from springlab.model.rotations import frames_from_directions

    applied = np.array([0.7, -1.3, 2.1])
    model = sim.build_model(arm, [], frames_from_directions(poses[:1])[0], joints="locked")
    marker = model.mbs.AddMarker(MarkerBodyRigid(bodyNumber=model.bodies[-1], localPosition=[0.0, 0.0, 0.0]))
    model.mbs.AddLoad(LoadTorqueVector(markerNumber=marker, loadVector=list(applied), bodyFixed=False))
    model.mbs.Assemble()
    held = sim.static_joint_torques(model)
    np.testing.assert_allclose(held, analytic(arm, [], poses[:1])[0] - applied, atol=1e-10)


def test_follow_torques_approach_the_holding_torques_in_a_slow_motion(arm, exact_springs):
    # unbalanced springs, a 60 s sweep: the driven joints' torques are the holding torques
    # (route 2, in the driven link's frame) plus a small inertial part
    from springlab.energy.geometry import holding_torques as analytic

    springs = [s.scaled(0.9) for s in exact_springs]
    sweep = Sweep(paper.TABLE_4_INITIAL, paper.TABLE_4_ROTATION, 60.0)
    run = sim.follow(arm, springs, sweep, samples=31)
    frames = arm.frames(sweep.angles(run.t))
    expected = np.einsum("tjba,tjb->tja", frames[:, 1:], analytic(arm, springs, frames[..., 0]))
    assert np.abs(expected).max() > 1.0
    assert np.abs(run.torques - expected).max() < 0.02


def test_the_control_runs_at_the_looser_tolerances_and_the_balanced_run_at_the_settings(arm, exact_springs, poses):
    """The control only has to show motion: it runs at sim.CONTROL_TOLERANCES whatever tighter ones
    the settings ask for, while the balanced run's drift follows the settings' tolerances."""
    rel, absolute = sim.CONTROL_TOLERANCES
    tight = sim.hold_test(arm, exact_springs, poses[:1], duration=0.3)
    loose = sim.hold_test(arm, exact_springs, poses[:1], duration=0.3,
                          settings=SimSettings(relative_tolerance=rel, absolute_tolerance=absolute))
    assert tight.control.max_tip_drift == loose.control.max_tip_drift > 1e-3  # the same run
    assert tight.balanced.max_tip_drift < 1e-10 < loose.balanced.max_tip_drift  # the settings' own
