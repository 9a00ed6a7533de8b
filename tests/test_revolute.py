"""The general model of an arm (a revolute chain from a URDF's frames): the papers' chains are
special cases of it, route 2's torques are its energy's gradient, route 3 (exudyn) agrees with
route 2, and both agree with Pinocchio, the field's reference, on real robots' URDFs."""

import re

import numpy as np
import pytest

from springlab.energy import geometry, simulation
from springlab.errors import GeometryError, SpringlabError
from springlab.model.chain import point_springs, serial_chain
from springlab.model.revolute import RevoluteChain, body_frames, joint_axes
from springlab.model.robots import ROBOTS, load_robot, robot_urdf
from springlab.model.springs import PointSpring, Spring
from springlab.model.urdf import read_revolute_chain
from springlab.workbench.references import pinocchio_gravity

PLANAR = serial_chain([0.4, 0.3, 0.2], [0.2, 0.1, 0.1], [3.0, 2.0, 1.0], joints=[(0, 0, 1)] * 3)


def _chain_torques_along_axes(chain, springs, angles):
    """Route 2 on a Chain (world torque vectors per link) projected on the revolute model's axes."""
    model, q = chain.revolute_chain(), chain.joint_coordinates(angles)
    vectors = geometry.holding_torques(chain, springs, chain.directions(angles))
    per_joint = [3 if chain.joint(j) == "spherical" else 1 for j in range(2, chain.n + 1)]
    vectors = np.repeat(vectors, per_joint, axis=1)
    R, _ = body_frames(model, q)
    return np.einsum("pjc,pjc->pj", vectors, joint_axes(model, R))


@pytest.mark.parametrize("which", ["spherical (000)", "planar revolute"])
def test_the_papers_chains_are_special_cases(which, arm, exact_springs, rng):
    chain = arm if which.startswith("spherical") else PLANAR
    springs = [s.scaled(0.9) for s in exact_springs] if chain is arm else [Spring(1, 2, 0.1, 0.2, 300.0)]
    springs += [Spring(2, chain.n, -0.05, 0.08, 120.0, free_length=0.03, initial_tension=2.0)]
    angles = chain.random_angles(200, rng)
    model, q, ps = chain.revolute_chain(), chain.joint_coordinates(angles), point_springs(chain, springs)
    ours, theirs = geometry.potential(model, ps, q), geometry.energies(chain, springs, chain.directions(angles))
    for key in ("gravity", "springs", "total"):
        np.testing.assert_allclose(ours[key], theirs[key], rtol=0, atol=1e-12 * (1 + np.max(np.abs(theirs[key]))))
    torques = geometry.joint_torques(model, ps, q)
    np.testing.assert_allclose(torques, _chain_torques_along_axes(chain, springs, angles), rtol=0, atol=1e-11)
    assert np.max(np.abs(torques)) > 1.0  # the scaled springs leave a torque: the comparison is not of zeros


def test_the_exact_design_holds_every_joint_of_the_general_model(arm, exact_springs, rng):
    model = arm.revolute_chain()
    q = arm.joint_coordinates(arm.random_angles(100, rng))
    balanced = geometry.joint_torques(model, point_springs(arm, exact_springs), q)
    control = geometry.joint_torques(model, point_springs(arm, [s.scaled(0.9) for s in exact_springs]), q)
    assert np.max(np.abs(balanced)) < 1e-11
    assert np.max(np.abs(control)) > 0.5  # the negative control must fail


def _panda_springs():
    return [PointSpring("panda_link0", (0, 0, 0.5), "panda_link2", (0, -0.1, 0.05), k=800.0),
            PointSpring("panda_link1", (0.05, 0, 0), "panda_link4", (0.02, 0.03, 0.0), k=300.0, free_length=0.05,
                        initial_tension=4.0),
            PointSpring("panda_link3", (0, 0, 0.1), "panda_link8", (0, 0.02, 0.0), k=150.0)]


def test_torques_are_the_energy_gradient():
    model = load_robot("Panda")
    springs = _panda_springs()
    q = model.random_q(20, 7)
    h = 1e-6
    fd = np.empty(q.shape)
    for i in range(model.n):
        step = np.zeros(model.n)
        step[i] = h
        fd[:, i] = (geometry.potential(model, springs, q + step)["total"]
                    - geometry.potential(model, springs, q - step)["total"]) / (2 * h)
    torques = geometry.joint_torques(model, springs, q)
    np.testing.assert_allclose(torques, fd, rtol=0, atol=1e-6)  # central difference: O(h^2) and round-off / h


def _forget_kept():
    from springlab.model import revolute

    revolute._forget_kept()


def test_kept_frames_are_given_again_only_for_the_same_model_and_angles():
    model, other = load_robot("Panda"), load_robot("Panda", payload=1.0)
    q = model.random_q(50, 3)
    R, o = body_frames(model, q)
    again = body_frames(model, q.copy())
    assert again[0] is R and again[1] is o  # the same angles: the kept arrays
    with pytest.raises(ValueError):
        R[0, 1, 0, 0] = 1.0  # kept arrays are read-only: no caller can change what the next one gets
    moved = q.copy()
    moved[7, 2] += 1e-9
    R_moved, _ = body_frames(model, moved)
    assert R_moved is not R and not np.array_equal(R_moved[7], R[7])  # other angles: computed afresh
    assert body_frames(other, q)[0] is not R  # another model with the same angles: its own frames
    _forget_kept()
    fresh, _ = body_frames(model, q)
    assert fresh is not R and np.array_equal(fresh, R)


def test_remembered_spring_loads_give_the_same_torques_and_follow_each_field():
    model = load_robot("Panda")
    springs = _panda_springs()
    q = model.random_q(40, 5)
    _forget_kept()
    first = geometry.joint_torques(model, springs, q)
    assert np.array_equal(geometry.joint_torques(model, springs, q), first)  # remembered: the same sums, bit for bit
    stiffer = springs[:2] + [PointSpring(springs[2].link_a, springs[2].point_a, springs[2].link_b, springs[2].point_b,
                                          k=springs[2].k * (1 + 1e-12))]
    moved = geometry.joint_torques(model, stiffer, q)
    assert not np.array_equal(moved, first)  # one field changed by 1e-12: recomputed, not the remembered load
    _forget_kept()
    np.testing.assert_array_equal(geometry.joint_torques(model, stiffer, q), moved)  # nothing kept: the same
    np.testing.assert_array_equal(geometry.joint_torques(model, springs, q), first)


def test_what_is_remembered_goes_with_its_frames():
    from springlab.model import revolute

    model = load_robot("Panda")
    _forget_kept()
    springs = _panda_springs()
    for seed in range(revolute.FRAMES_KEPT + 4):  # more pose sets than are kept, each with many springs
        q = model.random_q(30, seed)
        for k in range(revolute.RESULTS_KEPT + 5):
            geometry.joint_torques(model, [PointSpring(s.link_a, s.point_a, s.link_b, s.point_b, k=s.k + k)
                                           for s in springs], q)
    kept = list(revolute._FRAMES.values())
    assert len(kept) == revolute.FRAMES_KEPT
    assert sorted(revolute._BY_ROTATIONS) == sorted(id(entry.R) for entry in kept)  # the dropped frames' results went too
    assert all(len(entry.results) == revolute.RESULTS_KEPT for entry in kept)
    big = model.random_q(revolute.FRAMES_CACHED_POSES + 1, 1)
    R, _ = body_frames(model, big)
    assert body_frames(model, big)[0] is not R and id(R) not in revolute._BY_ROTATIONS  # too many poses: not kept


def test_exudyn_holds_what_route_2_computes():
    model = load_robot("Panda")
    springs = _panda_springs()
    q = model.random_q(3, 11)
    route3 = simulation.joint_torques(model, springs, q)
    route2 = geometry.joint_torques(model, springs, q)
    np.testing.assert_allclose(route3, route2, rtol=0, atol=1e-6)  # the target
    assert np.max(np.abs(route2)) > 1.0


def _pinocchio_gravity(label, model, q, *, scale_mass_of=None):
    """Pinocchio's computeGeneralizedGravity on the robot's own URDF (springlab.workbench.references),
    optionally with one body 1 % heavier (a negative control)."""
    pytest.importorskip("pinocchio")
    text = robot_urdf(label).read_text()
    if scale_mass_of is not None:  # the child link of that joint 1 % heavier, in the file itself
        child = re.search(rf'<joint name="{scale_mass_of}".*?<child link="([^"]+)"', text, re.S).group(1)
        link = re.search(rf'<link name="{child}">.*?</link>', text, re.S).group(0)
        mass = re.search(r'<mass value="([^"]+)"', link).group(1)
        text = text.replace(link, link.replace(f'<mass value="{mass}"', f'<mass value="{float(mass) * 1.01!r}"'))
    return pinocchio_gravity(text, model, q)


@pytest.mark.parametrize("label", [*ROBOTS, "Tiago arm", "PR2 left", "ASR TwoDofs"])  # all 42: make bench
def test_gravity_torques_agree_with_pinocchio(label):
    model = load_robot(label)
    q = model.random_q(50, 3)
    if label.startswith("double pendulum"):  # its URDF's limits read 0, 0 (taken as unlimited); its gravity at zero is zero
        assert np.all(np.isinf(model.limits))
    ours, reference = geometry.gravity_torques(model, q), _pinocchio_gravity(label, model, q)
    scale = np.max(np.abs(reference))
    assert scale > 0.1 or label == "ASR TwoDofs"  # TwoDofs moves in a horizontal plane: gravity loads none of its joints
    np.testing.assert_allclose(ours, reference, rtol=0, atol=1e-9 * max(scale, 1.0))  # 1e-9 relative (1e-9 N m at least)


def test_a_wrong_mass_disagrees_with_pinocchio():
    model = load_robot("UR5")
    q = model.random_q(20, 4)
    wrong = _pinocchio_gravity("UR5", model, q, scale_mass_of="elbow_joint")  # the forearm 1 % heavier
    assert np.max(np.abs(geometry.gravity_torques(model, q) - wrong)) > 1e-3 * np.max(np.abs(wrong))


def test_bodies_merge_as_pinocchio_merges_them():
    pin = pytest.importorskip("pinocchio")
    model = load_robot("Panda")  # the hand and its two locked fingers ride on panda_link7
    full = pin.buildModelFromUrdf(str(robot_urdf("Panda")))
    lock = [full.getJointId(name) for name in full.names[1:] if name not in model.joints]
    reduced = pin.buildReducedModel(full, lock, pin.neutral(full))
    for b, name in enumerate(model.joints, start=1):
        theirs = reduced.inertias[reduced.getJointId(name)]
        assert model.mass[b] == pytest.approx(theirs.mass, rel=1e-12)
        np.testing.assert_allclose(model.com[b], theirs.lever, atol=1e-12)
        np.testing.assert_allclose(model.inertia[b], theirs.inertia, atol=1e-12)


def test_a_payload_is_a_point_mass_at_the_tip():
    model, loaded = load_robot("UR5"), load_robot("UR5", payload=2.0)
    q = model.random_q(10, 5)
    R, o = body_frames(model, q)
    tip = o[:, -1]
    lever = geometry.gravity_torques(loaded, q) - geometry.gravity_torques(model, q)
    extra = np.empty_like(lever)  # the torque of 2 kg at the tip frame's origin, by hand
    axes = joint_axes(model, R)
    for i in range(model.n):
        moment = np.cross(tip - o[:, i + 1], 2.0 * model.gravity)
        extra[:, i] = -np.einsum("pc,pc->p", moment, axes[:, i])
    np.testing.assert_allclose(lever, extra, atol=1e-12)


URDF = """<robot name="r">
  <link name="base"/>
  <link name="a"><inertial><origin xyz="0.1 0.02 0"/><mass value="2"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/></inertial></link>
  <link name="b"><inertial><origin xyz="0.1 0 0.03" rpy="0 0.3 0"/><mass value="1"/>
    <inertia ixx="0.003" ixy="0.001" ixz="0" iyy="0.004" iyz="0" izz="0.005"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 1 0"/>
    <origin xyz="0 0 0.2"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j2" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 1 0"/>
    <origin xyz="0.3 0.05 0" rpy="0.1 0 0"/></joint>
</robot>"""


def test_a_urdf_reads_into_the_general_model():
    model = read_revolute_chain(URDF, source="r.urdf")
    assert model.bodies == ("base", "a", "b") and model.joints == ("j1", "j2")
    np.testing.assert_allclose(model.gravity, [0, 0, -9.81])
    np.testing.assert_allclose(model.limits, [[-1, 1], [-np.inf, np.inf]])
    np.testing.assert_allclose(model.com[1], [0.1, 0.02, 0])
    np.testing.assert_allclose(model.placements[1][:3, 3], [0.3, 0.05, 0])
    # the inertia given in a rotated frame is turned into the link's frame
    c, s = np.cos(0.3), np.sin(0.3)
    Ry = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    J = np.array([[0.003, 0.001, 0], [0.001, 0.004, 0], [0, 0, 0.005]])
    np.testing.assert_allclose(model.inertia[2], Ry @ J @ Ry.T, atol=1e-15)
    # at q = 0 the second link's centre is 0.3 + 0.1 m out (the roll of joint 2 and the rpy of its
    # inertia leave its x alone): joint 1 holds -m g x about +y
    tau = geometry.gravity_torques(model, np.zeros(2))[0]
    assert tau[0] == pytest.approx(-(2 * 0.1 + 1 * (0.3 + 0.1)) * 9.81, rel=1e-12)


def test_bad_inputs_are_refused_with_the_parameter_named():
    model = read_revolute_chain(URDF, source="r.urdf")
    with pytest.raises(SpringlabError, match="shape \\(N, 2\\)"):
        geometry.gravity_torques(model, np.zeros(3))
    with pytest.raises(SpringlabError, match="NaN"):
        geometry.gravity_torques(model, [np.nan, 0.0])
    with pytest.raises(SpringlabError, match="'c' is not a link"):
        geometry.potential(model, [PointSpring("base", (0, 0, 0), "c", (0, 0, 0), k=1.0)], np.zeros(2))
    with pytest.raises(SpringlabError, match="both ends are on 'a'"):
        PointSpring("a", (0, 0, 0), "a", (1, 0, 0), k=1.0)
    with pytest.raises(SpringlabError, match="point_b of base-a must be 3 finite"):
        PointSpring("base", (0, 0, 0), "a", (np.nan, 0, 0), k=1.0)
    with pytest.raises(SpringlabError, match="k of base-a must be a finite stiffness"):
        PointSpring("base", (0, 0, 0), "a", (0, 0, 0), k=-5.0)
    with pytest.raises(SpringlabError, match="expected PointSpring"):
        geometry.joint_torques(model, [Spring(1, 2, 0.1, 0.1, 10.0)], np.zeros(2))
    with pytest.raises(GeometryError, match="ends coincide"):
        geometry.joint_torques(model, [PointSpring("base", (0, 0, 0.2), "a", (0, 0, 0), k=10.0, free_length=0.1)],
                               np.zeros(2))
    with pytest.raises(SpringlabError, match="axis of joint 'j' must be a unit vector"):
        RevoluteChain("x", ("b0", "b1"), ("j",), np.eye(4)[None], [[0, 0, 2.0]], [0, 1], np.zeros((2, 3)),
                      np.zeros((2, 3, 3)), [0, 0, -9.81])
    with pytest.raises(SpringlabError, match="mass of body 'b1' = -1 kg"):
        RevoluteChain("x", ("b0", "b1"), ("j",), np.eye(4)[None], [[0, 0, 1.0]], [0, -1], np.zeros((2, 3)),
                      np.zeros((2, 3, 3)), [0, 0, -9.81])
    with pytest.raises(SpringlabError, match="gravity must be a nonzero vector"):
        RevoluteChain("x", ("b0", "b1"), ("j",), np.eye(4)[None], [[0, 0, 1.0]], [0, 1], np.zeros((2, 3)),
                      np.zeros((2, 3, 3)), [0, 0, 0])
    with pytest.raises(SpringlabError, match="not one of springlab's example robots"):
        load_robot("R2-D2")


def test_the_frames_unchecked_rotations_are_rot_axis_bit_for_bit():
    # body_frames turns each body by its model's (checked) axis without rot_axis's checks: the same
    # arithmetic, so the same bits; a rotation about another axis must differ (the negative control)
    from springlab.model import revolute
    from springlab.model.rotations import rot_axis

    rng = np.random.default_rng(0)
    for _ in range(50):
        u = rng.normal(size=3)
        u /= np.linalg.norm(u)
        angles = rng.uniform(-7.0, 7.0, 40)
        assert np.array_equal(revolute._turns(u, angles), rot_axis(u, angles))
    assert not np.array_equal(revolute._turns(u, angles), rot_axis(np.roll(u, 1), angles))


def test_route_2s_cross_product_is_numpys_bit_for_bit():
    # route 2 takes a x b by its components (numpy.cross's arithmetic without its axis handling): the
    # same bits on batches and broadcasts; the negative control, b x a, differs
    from springlab.energy.geometry import _cross

    rng = np.random.default_rng(1)
    for a_shape, b_shape in (((3,), (3,)), ((50, 3), (50, 3)), ((7, 5, 3), (5, 3)), ((40, 3), (3,))):
        a, b = rng.normal(size=a_shape), rng.normal(size=b_shape)
        assert np.array_equal(_cross(a, b), np.cross(a, b))
    assert not np.array_equal(_cross(b, a), np.cross(a, b))
