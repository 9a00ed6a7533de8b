import numpy as np

from springlab import UP, random_directions, serial_chain
from springlab.model.rotations import directions_from_relative, rot_xyz


def test_straight_up_pose_places_joints_and_coms_on_the_vertical(arm):
    X = np.tile(UP, (1, arm.n, 1))
    joints = arm.joint_positions(X)
    np.testing.assert_allclose(joints[0, :, 0], np.concatenate([[0], np.cumsum(arm.r)]))
    np.testing.assert_allclose(joints[0, :, 1:], 0)
    com = arm.com_positions(X)
    np.testing.assert_allclose(com[0, :, 0], np.concatenate([[0], np.cumsum(arm.r)[:-1]]) + arm.d)


def test_zero_angles_point_every_link_up(arm):
    X = arm.directions(np.zeros((2, arm.n - 1, 3)))
    np.testing.assert_allclose(X, np.tile(UP, (2, arm.n, 1)))


def test_relative_angles_compose_along_the_chain():
    # phi = -90 deg about y turns x = up into +z; a second -90 deg turns it to -x (down).
    ang = np.radians([[[0, -90, 0], [0, -90, 0]]])
    X = serial_chain([1.0, 1.0], [0.5, 0.5], [1.0, 1.0]).directions(ang)
    np.testing.assert_allclose(directions_from_relative(rot_xyz(*np.moveaxis(ang, -1, 0))), X)
    np.testing.assert_allclose(X[0, 1], [0, 0, 1], atol=1e-15)
    np.testing.assert_allclose(X[0, 2], [-1, 0, 0], atol=1e-15)


def test_rotations_are_orthonormal(rng):
    R = rot_xyz(*rng.uniform(-np.pi, np.pi, (3, 50)))
    np.testing.assert_allclose(R @ np.swapaxes(R, -1, -2), np.broadcast_to(np.eye(3), R.shape), atol=1e-14)
    np.testing.assert_allclose(np.linalg.det(R), 1.0)


def test_random_directions_are_unit_and_seeded():
    a = random_directions(5, 100, 7)
    b = random_directions(5, 100, 7)
    np.testing.assert_array_equal(a, b)
    np.testing.assert_allclose(np.linalg.norm(a, axis=2), 1.0)
    np.testing.assert_array_equal(a[:, 0], np.tile(UP, (100, 1)))


def test_com_off_link_is_allowed_only_on_request():
    chain = serial_chain([0.3], [-0.05], [1.0], com_off_link=True)
    assert chain.d == (-0.05,)
