"""Clearance on a real arm's own shapes (coal), the workspace free of self-collision, and the springs'
own mass: each with a negative control that must fail."""


import numpy as np
import pytest

pytest.importorskip("coal")


from springlab.design.arms import workspace_ranges  # noqa: E402
from springlab.design.collision import (  # noqa: E402
    MARGIN,
    Piece,
    Sampler,
    clearances,
    collision_masks,
    mounting_plane,
)
from springlab.model.revolute import body_frames, world_points  # noqa: E402
from springlab.model.robots import load_robot, robot_urdf  # noqa: E402
from springlab.workbench.cli import main  # noqa: E402


@pytest.fixture(scope="module")
def ur5():
    return load_robot("UR5")


def _through(model, q, link, offset):
    """A cable across the named link's middle (0.3 m long), moved ``offset`` m along the base's y axis."""
    R, o = body_frames(model, q)
    body = model.bodies.index(link)
    centre = np.mean([s.frame[:3, 3] for s in model.solids[body]], axis=0) + [0.0, 0.0, 0.2]
    middle = world_points(R, o, body, centre) + [0.0, offset, 0.0]
    return Piece("S9 cable", middle - [0.0, 0.0, 0.15], middle + [0.0, 0.0, 0.15], 0.0006)


def test_a_cable_moved_through_a_link_is_caught(ur5):
    q = np.zeros((3, ur5.n))  # the UR5 stretched out level: its upper arm along the base's y axis
    found = clearances(ur5, [_through(ur5, q, "upper_arm_link", 0.0), _through(ur5, q, "upper_arm_link", 0.5)], q)
    gaps = found.gaps[0][:, :-1]  # the links (the mounting plane is the last column)
    pose, body = np.unravel_index(int(np.argmin(gaps)), gaps.shape)
    gap = gaps[pose, body]
    assert ur5.bodies[body] == "upper_arm_link" and gap < -0.02  # through the link: a depth in m
    links = [f for f in found.failures() if f[1] != "the mounting plane"]
    assert links == [("S9 cable", "upper_arm_link", 0, gap)]
    lowest = min(found.pieces[0].a[0] @ ur5.up, found.pieces[0].b[0] @ ur5.up) - 0.0006  # the cable's lowest point
    assert found.gaps[0][0, -1] == pytest.approx(lowest - mounting_plane(ur5))  # its height above the table
    assert np.min(found.gaps[1][:, :-1]) > MARGIN  # the control: the same cable half a metre aside clears the links


def test_a_piece_wholly_inside_a_mesh_is_caught_although_it_touches_no_triangle(ur5):
    q = np.zeros((1, ur5.n))
    R, o = body_frames(ur5, q)
    body = ur5.bodies.index("upper_arm_link")
    mesh = next(s for s in ur5.solids[body] if s.kind == "mesh")
    inside = world_points(R, o, body, mesh.frame[:3, :3] @ mesh.vertices.mean(axis=0) + mesh.frame[:3, 3])
    tiny = Piece("S9 coil", inside, inside + [0.0, 0.0, 0.002], 0.001)
    assert clearances(ur5, [tiny], q).worst(0)[0] < 0


def _measured_everywhere(model, piece, q):
    """Each body's exact clearance from the piece at every pose (N, bodies): coal's full distance for every shape
    and pose, with no screen and no lower bound."""
    import coal

    from springlab.design import collision

    R, o = body_frames(model, q)
    out = np.full((q.shape[0], model.n + 1), np.inf)
    own = {body: (end, allowance) for body, end, allowance in piece.bodies}
    for item in collision._items(model):
        shapes = collision._piece_capsules(coal, piece.a, piece.b, piece.radius, own.get(item.body))
        for p in range(q.shape[0]):
            if shapes[p] is None:
                continue
            solid, Rs, c = shapes[p]
            Ri, ti = collision._placed(R, o, item, p)
            gap = collision._signed(coal, item, collision._transform(coal, Ri, ti), solid,
                                    collision._transform(coal, Rs, c), c, np.inf)
            out[p, item.body] = min(out[p, item.body], gap)
    return out


@pytest.mark.parametrize("every", [False, True])
def test_the_nearest_approach_and_the_poses_within_the_margin_are_those_of_measuring_everything(ur5, every):
    """The check measures a mesh exactly only below the margin, or below the smallest clearance it knows, and
    settles the rest by lower bounds: its worst (value, link, pose) and, measuring ``every`` pose, which poses
    come within the margin, must be those of measuring every shape at every pose."""
    q = np.random.default_rng(7).uniform(-np.pi, np.pi, (40, ur5.n))
    body = ur5.bodies.index("upper_arm_link")
    mesh = next(s for s in ur5.solids[body] if s.kind == "mesh")
    v = mesh.vertices @ mesh.frame[:3, :3].T + mesh.frame[:3, 3]  # the link's frame
    along = np.linalg.svd(v - v.mean(axis=0), full_matrices=False)[2]  # its long axis, then two across it
    reach = np.max(np.abs((v - v.mean(axis=0)) @ along[1]))
    R, o = body_frames(ur5, q)

    def cable(d):  # a cable along the link, d m beside its side: through it at d < 0
        ends = [v.mean(axis=0) + (reach + d) * along[1] + s * 0.05 * along[0] for s in (-1, 1)]
        return Piece("S9 cable", *(world_points(R, o, body, e) for e in ends), 0.0006)

    pieces = [cable(d) for d in (-0.03, 0.003, 0.02, 0.06, 0.3)]
    found = clearances(ur5, pieces, q, every=every)
    truth = [_measured_everywhere(ur5, piece, q) for piece in pieces]
    worst = []
    for k, exact in enumerate(truth):
        pose, body = np.unravel_index(int(np.argmin(exact)), exact.shape)
        links = found.gaps[k][:, :-1]  # the mounting plane, last, is a height: not measured by coal
        pose_found, body_found = np.unravel_index(int(np.argmin(links)), links.shape)
        gap = links[pose_found, body_found]
        assert gap == exact[pose, body] and (body_found, pose_found) == (body, pose)
        assert np.all(links <= exact + 1e-6)  # never larger than the truth, to coal's GJK tolerance (1e-6 m)
        worst.append(gap)
    assert min(worst) < 0 < MARGIN < max(worst)  # a piece through the link, and one clear of it
    if every:  # the pieces beside the link (the first runs into it at every pose)
        found = clearances(ur5, pieces[1:], q, every=True)
        plane = found.gaps[:, :, -1].min(axis=0)
        near = (np.min([np.min(t, axis=1) for t in truth[1:]], axis=0) < MARGIN) | (plane < MARGIN)
        assert np.array_equal(found.within(), near)
        assert near.any() and not near.all()


def test_the_workspace_leaves_out_poses_in_collision_and_below_the_mount(ur5):
    ranges = workspace_ranges(ur5)
    rng = np.random.default_rng(3)
    sampler = Sampler(ur5, ranges, rng)
    q = sampler.draw(300, rng)
    assert np.all(sampler.free(q)) and 0.2 < sampler.share < 0.6  # the UR5: about a third of its limits' box
    folded = np.zeros((1, ur5.n))
    folded[0, 1], folded[0, 2] = -np.pi / 2, np.pi  # the forearm folded back down onto the upper arm's side
    down = np.zeros((1, ur5.n))
    down[0, 1] = np.pi / 2  # the upper arm pointing down, through the mounting plane
    hit, low = collision_masks(ur5, np.vstack([folded, down]), pairs=sampler.pairs, below=sampler.below)
    assert hit[0].any() and not low[0].any() and not sampler.free(folded)[0]  # links in collision
    assert low[1].any() and not sampler.free(down)[0]  # below the mount
    raised = np.zeros((1, ur5.n))
    raised[0, 1] = -np.pi / 4  # the control: the arm raised, clear of itself and of the mount
    assert sampler.free(raised)[0]
    assert not sampler.free(np.zeros((1, ur5.n)))[0]  # stretched out level, its wrist hangs just below the base


def test_the_springs_own_mass_is_carried_and_costs_balance(ur5_two_point):
    design = ur5_two_point
    data = design.as_dict()
    shoulder = data["torques"][1]
    assert data["spring_mass_kg"] == pytest.approx(sum(s["mass_kg"] for s in data["realised"]))
    assert data["spring_mass_kg"] > 1.0
    # carrying the steel leaves more on the shoulder than the springs alone: a design that left it out would
    # overstate its balance
    assert shoulder["realised_with_spring_mass_peak_Nm"] > 2 * shoulder["realised_peak_Nm"]


@pytest.mark.parametrize("margin", ["-1 mm", "nan", "3 kg"])
def test_a_bad_margin_is_refused_and_nothing_written(tmp_path, capsys, margin):
    out = tmp_path / "d.json"
    assert main(["design", str(robot_urdf("UR5")), "--margin", margin, "--json", str(out), "--quiet"]) == 2
    assert "--margin" in capsys.readouterr().err and not out.exists()


def test_a_workspace_where_every_pose_collides_is_refused(tmp_path, capsys):
    # the UR5 hanging straight down from its shoulder: every pose passes below the mounting plane. Within
    # that narrowed workspace the links are always below it, which must not make them "below by construction"
    from springlab.model.robots import robot_urdf
    from springlab.workbench.cli import main

    out = tmp_path / "x.json"
    down = "shoulder_lift_joint=85:95,elbow_joint=-5:5"
    assert main(["design", str(robot_urdf("UR5")), "--workspace", down, "--json", str(out), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "no pose of the workspace is free" in err and err.count("\n") == 1 and not out.exists()


def test_a_hull_corner_with_hundreds_of_neighbours_falls_back_to_the_triangles():
    # a cone of 300 rim points: its apex has 300 neighbours on the hull, more than coal's hull takes (255);
    # the mesh is still measured (by its triangles), and the control, a cone of 30, gets its convex hull
    from springlab.design.collision import _mesh_geometry

    for rim, convex in ((300, False), (30, True)):
        a = np.linspace(0.0, 2 * np.pi, rim, endpoint=False)
        v = np.vstack([np.c_[np.cos(a), np.sin(a), np.zeros(rim)], [[0.0, 0.0, 1.0], [0.0, 0.0, -0.01]]])
        f = np.array([(k, (k + 1) % rim, rim) for k in range(rim)] + [((k + 1) % rim, k, rim + 1) for k in range(rim)])
        hull, bvh, points = _mesh_geometry(np.ascontiguousarray(v).tobytes(), np.ascontiguousarray(f, dtype=np.int64).tobytes())
        assert (hull is not bvh) == convex and len(points) == rim + 2
