"""Mechanism drawings and animations: the drawing shows route 2's points, every panel at one
scale with equal axes, the hold test's motion is the hold test, and a GIF is deterministic
and small enough to commit."""

from pathlib import Path

import matplotlib
import numpy as np
import pytest

from springlab.energy import simulation as sim
from springlab.energy.geometry import attachment_points
from springlab.errors import SpringlabError
from springlab.model.chain import random_directions
from springlab.workbench import drawing

matplotlib.use("Agg")
ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def poses():
    return random_directions(4, 3, np.random.default_rng(7))


def test_a_zigzag_runs_from_end_to_end_within_its_width():
    P, Q = np.array([0.0, 0.0]), np.array([1.0, 0.0])
    z = drawing.zigzag(P, Q, coils=5, width=0.05)
    assert np.allclose(z[0], P) and np.allclose(z[-1], Q)
    assert np.max(np.abs(z[:, 1])) == pytest.approx(0.05)
    assert np.all(np.diff(z[:, 0]) >= 0)  # it never turns back
    assert drawing.zigzag(P, P, width=0.05).shape == (1, 2)  # a spring seen end-on is a point
    assert np.max(np.abs(drawing.zigzag(P, [0.1, 0.0], width=0.05)[:, 1])) == pytest.approx(0.025)  # short: narrower


def test_the_scene_holds_route_2s_points(arm, exact_springs, poses):
    scene = drawing.chain_scene(arm, exact_springs, poses)
    assert np.allclose(scene.links[0], arm.joint_positions(poses))
    for s, (label, (A, B)) in zip(exact_springs, scene.springs.items(), strict=True):
        assert label.startswith(f"S({s.i},{s.j})")
        A2, B2 = attachment_points(arm, s, poses)
        assert np.array_equal(A, A2) and np.array_equal(B, B2)
    low, high = scene.column  # the ground column reaches every attachment on link 1
    assert all(low <= s.a <= high for s in exact_springs if s.i == 1)
    # the front view is (y, x up), the side view (z, x up), the top view (y, z)
    p = np.array([1.0, 2.0, 3.0])
    assert scene.project(p, "front").tolist() == [2.0, 1.0]
    assert scene.project(p, "side").tolist() == [3.0, 1.0]
    assert scene.project(p, "top").tolist() == [2.0, 3.0]
    with pytest.raises(SpringlabError, match="view must be one of"):
        scene.project(p, "oblique")


def test_every_panel_has_equal_axes_and_one_scale_per_view(arm, exact_springs, poses):
    import matplotlib.pyplot as plt

    fig = drawing.mechanism_figure(drawing.chain_scene(arm, exact_springs, poses), [0, 1, 2])
    axes = fig.axes
    assert len(axes) == 6 and all(ax.get_aspect() == 1.0 for ax in axes)
    for row in (axes[:3], axes[3:]):
        assert len({(ax.get_xlim(), ax.get_ylim()) for ax in row}) == 1
    labels = {t.get_text() for t in axes[0].texts}
    assert {f"S({s.i},{s.j})" for s in exact_springs} <= labels
    plt.close(fig)
    with pytest.raises(SpringlabError, match="poses must be 1 to 4"):
        drawing.mechanism_figure(drawing.chain_scene(arm, exact_springs, poses), [0, 1, 2, 0, 1])
    with pytest.raises(SpringlabError, match="coordinate axis"):
        drawing.Scene(np.array([0.6, 0.8, 0.0]), [np.zeros((1, 2, 3))], {}, (0, 0)).horizontal()


def test_the_hold_motion_is_the_hold_test(arm, exact_springs, poses):
    motion = sim.hold_motion(arm, exact_springs, poses[0], duration=1.0)
    test = sim.hold_test(arm, exact_springs, poses[:1], duration=1.0)
    tip = arm.tip_position(motion.balanced)
    falls = arm.tip_position(motion.control)
    assert np.max(np.linalg.norm(tip - tip[0], axis=1)) == pytest.approx(test.balanced.max_tip_drift, abs=1e-12)
    assert np.max(np.linalg.norm(falls - falls[0], axis=1)) == pytest.approx(test.control.max_tip_drift, rel=1e-9)
    assert test.balanced.max_tip_drift < 1e-9 and test.control.max_tip_drift > 1e-2  # still, and falling
    assert motion.tip_travel(arm) == pytest.approx((test.balanced.max_tip_drift, test.control.max_tip_drift), abs=1e-12)
    assert np.allclose(motion.balanced[0], poses[0])  # released where it was put
    short = motion.sampled(5)
    assert len(short.t) == 5 and short.t[0] == 0.0 and short.t[-1] == motion.t[-1]


def test_an_animation_is_deterministic_and_refuses_mismatched_scenes(arm, exact_springs, poses, tmp_path):
    from PIL import Image

    scene = drawing.chain_scene(arm, exact_springs, poses)
    one = drawing.animate({"a": (scene, "front"), "b": (scene, "side")}, tmp_path / "one.gif", times=[0, 1, 2])
    two = drawing.animate({"a": (scene, "front"), "b": (scene, "side")}, tmp_path / "two.gif", times=[0, 1, 2])
    assert Path(one).read_bytes() == Path(two).read_bytes()
    assert Image.open(one).n_frames == 3
    with pytest.raises(SpringlabError, match="common number of poses"):
        drawing.animate({"a": (scene, "front"), "b": (drawing.chain_scene(arm, exact_springs, poses[:2]), "front")},
                        tmp_path / "bad.gif")


@pytest.mark.parametrize("gif", sorted((ROOT / "figures").glob("*/*.gif")), ids=lambda p: p.parent.name)
def test_committed_animations_are_small(gif):
    from PIL import Image

    assert gif.stat().st_size < 2_000_000
    assert Image.open(gif).n_frames >= 10


def test_there_are_committed_animations():
    assert {p.parent.name for p in (ROOT / "figures").glob("*/*.gif")} >= {"juang2023_spatial_balance",
                                                                         "lin2010_pseudobases"}


def _distance_to_segment(p, a, b) -> float:
    ab = b - a
    t = np.clip(np.dot(p - a, ab) / max(np.dot(ab, ab), 1e-300), 0.0, 1.0)
    return float(np.linalg.norm(p - (a + t * ab)))


def floating(scene: drawing.Scene, pose: int = 0) -> list[str]:
    """The spring ends and centres of mass that lie on no link, bracket or the ground column."""
    joints = scene.links[0][pose]
    segments = [(joints[k], joints[k + 1]) for k in range(len(joints) - 1)]
    segments += [tuple(b) for b in (scene.brackets[pose] if scene.brackets is not None else [])]
    segments.append((scene.column[0] * scene.up, scene.column[1] * scene.up))
    points = {f"{label} {end}": P[pose] for label, (A, B) in scene.springs.items() for end, P in (("A", A), ("B", B))}
    points |= {f"centre of mass {k + 2}": c for k, c in enumerate(scene.masses[pose])}
    return [name for name, p in points.items() if min(_distance_to_segment(p, a, b) for a, b in segments) > 1e-12]


def test_no_spring_end_or_mass_floats(arm, exact_springs, poses):
    from springlab.mechanisms import two_spring_arm as an
    from springlab.papers import lenzo2017 as lenzo

    assert floating(drawing.chain_scene(arm, exact_springs, poses)) == []
    for layout, (a12, b12) in lenzo.FREE_CHOICES.items():  # c and d carry a countermass behind the elbow
        two = lenzo.ARM if layout in ("a", "b") else lenzo.ARM_COUNTERMASS
        d = an.solve(two, a2=lenzo.A2, a12=a12, b12=b12, layout=layout)
        chain = two.chain(lenzo.FOREARM_LENGTH)
        X = chain.directions(chain.random_angles(2, np.random.default_rng(1)))
        assert floating(drawing.chain_scene(chain, an.to_chain_springs(two, d), X)) == [], layout


def test_the_floating_check_can_fail(arm, exact_springs, poses):
    scene = drawing.chain_scene(arm, exact_springs, poses)
    bare = drawing.Scene(scene.up, scene.links, scene.springs, scene.column, masses=scene.masses)  # no brackets
    assert floating(bare) != []


def test_nothing_floats_on_paper_001s_arm():
    from springlab.mechanisms.pseudobase import subsystems as subs
    from springlab.papers import lin2010

    arm = lin2010.arm()
    springs = subs.design_equilibrators(arm, lin2010.K, lin2010.L_CA)
    q = np.random.default_rng(3).uniform(-np.pi, np.pi, (3, arm.n))
    scene = drawing.pseudobase_scene(arm, springs, q)
    assert len(scene.springs) == len(springs) and len(scene.extras) == len(arm.modules)
    for pose in range(3):
        assert floating(scene, pose) == []
