"""The narrower workspace on which springs that run into a link clear it (springlab.design.narrowing): found on
the design's poses, re-measured on fresh ones, and checked here on poses of its own; each with a control."""

import json
from dataclasses import replace

import numpy as np
import pytest

pytest.importorskip("coal")

from springlab.design.arms import parse_workspace, workspace_ranges  # noqa: E402
from springlab.design.collision import Sampler  # noqa: E402
from springlab.design.narrowing import _box, _interval, colliding, narrowed  # noqa: E402
from springlab.model.robots import robot_urdf  # noqa: E402
from springlab.workbench.cli import _collision_line, _print_narrowed, main  # noqa: E402

MARGIN = 0.03
"""m: a margin the double pendulum's belt springs (21 and 24 mm from a link at worst) keep at about half its poses."""


def test_the_range_of_one_joint_that_holds_no_bad_pose_and_the_most_others():
    x = np.array([0.5, -1.0, 0.1, 0.9, -0.4, 0.3, 2.0, -2.0])
    bad = np.array([False, True, False, True, False, False, False, False])
    assert _interval(x, bad) == (4, -0.4, 0.5)  # between the bad -1.0 and 0.9: -0.4, 0.1, 0.3, 0.5
    assert _interval(x, np.ones(len(x), bool))[0] == 0  # the control: every value bad, no range
    rng = np.random.default_rng(3)
    q = rng.uniform(-np.pi, np.pi, (2000, 3))
    hit = q[:, 1] > 1.0  # bad wherever joint 1 passes 1 rad
    ranges = np.tile([-np.pi, np.pi], (3, 1))
    box = _box(q, hit, ranges, (1,))
    assert box[1, 1] <= 1.0 and box[1, 0] == pytest.approx(-np.pi, abs=np.radians(1.5))
    assert np.array_equal(box[[0, 2]], ranges[[0, 2]])  # the other joints keep their ranges
    assert _box(q, hit, ranges, (0,)) is None or np.degrees(np.diff(_box(q, hit, ranges, (0,))[0]))[0] < 5
    both = _box(q, hit | (q[:, 2] < -2.0), ranges, (1, 2))  # two joints together
    inside = np.all((q >= both[:, 0]) & (q <= both[:, 1]), axis=1)
    assert inside.sum() > 600 and not (hit | (q[:, 2] < -2.0))[inside].any()


@pytest.fixture(scope="module")
def tight(pendulum_belts):
    """The double pendulum's belt springs held to a 30 mm margin, and the narrower workspaces found for it."""
    d = pendulum_belts
    ranges = workspace_ranges(d.model)
    found = narrowed(d.model, d.realised, d.kinds, d.coils, d.realised_names, d.q, ranges, random=600,
                     margin=MARGIN, fresh=600, seed=1, massed=d.massed, loaded=d.structure.loaded, limits=ranges)
    return d, ranges, found


def _fresh(d, ranges, count, seed):
    rng = np.random.default_rng(seed)
    return Sampler(d.model, ranges, rng, limits=workspace_ranges(d.model)).draw(count, rng)


def test_springs_too_near_their_links_clear_them_on_the_narrower_workspace_found(tight):
    d, ranges, found = tight
    bad = colliding(d.model, d.realised, d.kinds, d.coils, d.realised_names, d.q, margin=MARGIN)
    assert 0.2 < bad.mean() < 0.8  # the springs come within 30 mm at some of the workspace's poses, not all
    assert found, "no narrower workspace was found"
    for n in found:
        assert 0 < n.kept < 1 and n.nearest >= MARGIN and n.fresh == 600
        assert np.all(n.ranges[:, 0] >= ranges[:, 0]) and np.all(n.ranges[:, 1] <= ranges[:, 1])
        assert set(n.removed) == {d.model.joints[i] for i in d.structure.loaded}
        assert np.allclose(np.degrees(n.ranges[list(n.joints)]), np.round(np.degrees(n.ranges[list(n.joints)])))
        own = _fresh(d, n.ranges, 400, seed=99)  # poses of its own, not those the narrowing drew
        near = colliding(d.model, d.realised, d.kinds, d.coils, d.realised_names, own, margin=MARGIN)
        assert near.mean() < 0.01
        whole = _fresh(d, ranges, 400, seed=99)  # the control: the whole workspace's poses come within it often
        assert colliding(d.model, d.realised, d.kinds, d.coils, d.realised_names, whole, margin=MARGIN).mean() > 0.2


def test_springs_that_clear_need_no_narrowing_and_a_margin_none_keeps_finds_none(tight):
    d, ranges, _ = tight
    assert d.narrowed == () and not d.clearance.failing()  # the design clears its 5 mm: nothing to narrow
    args = (d.model, d.realised, d.kinds, d.coils, d.realised_names, d.q, ranges)
    assert narrowed(*args, random=600, fresh=200) == ()
    assert narrowed(*args, random=600, margin=0.2, fresh=200) == ()  # 200 mm: every pose is within it


def test_the_cli_says_the_springs_collide_in_its_first_line_and_writes_that_no_narrowing_clears(tmp_path, capsys):
    out = tmp_path / "d.json"
    code = main(["design", str(robot_urdf("double pendulum")), "--layout", "belts", "--samples", "300",
                 "--audit-samples", "500", "--margin", "30 mm", "--json", str(out), "--quiet"])
    text = capsys.readouterr().out
    first = text.splitlines()[0]
    assert code == 3 and "SPRINGS COLLIDE: S1, S2 come within the 30 mm margin" in first
    assert "no narrower workspace found where they clear" in first and "no narrowing of one joint's range" in text
    record = json.loads(out.read_text())["clearance"]
    assert record["clears"] is False and record["narrowed_workspaces"] == []


def test_a_narrower_workspace_found_is_printed_and_written_as_workspace_takes_it(tight, capsys):
    d, _, found = tight
    held = replace(d, narrowed=found, clearance=replace(d.clearance, margin=MARGIN))
    best = max(found, key=lambda n: n.kept)
    first = _collision_line(held)
    assert f"on a narrower workspace they clear ({best.workspace(d.model)}, {100 * best.kept:.0f} % of it kept)" in first
    _print_narrowed(held)
    text = capsys.readouterr().out
    assert all(n.workspace(d.model) in text for n in found) and "fresh poses, all clear" in text
    assert parse_workspace(best.workspace(d.model))  # the --workspace argument parses
    record = held.as_dict()["clearance"]
    assert record["clears"] is False and len(record["narrowed_workspaces"]) == len(found)
    assert record["narrowed_workspaces"][-1]["workspace_argument"] == found[-1].workspace(d.model)
    assert _collision_line(d) == ""  # the control: springs that clear say nothing of it


def test_each_spring_that_does_not_clear_says_at_what_share_of_the_poses(pendulum_belts):
    """The share of the first check poses at which a spring comes within the margin, as the clearance reports it,
    is the share found by measuring each of those poses alone (its nearest approach, exact, at that pose); the
    flag and the JSON carry it. The control: at the default 5 mm margin the same springs clear, with no share."""
    from springlab.design.collision import clearances
    from springlab.design.hardware import WITHIN_POSES, _poses, spring_clearance, spring_pieces

    d = pendulum_belts
    found = spring_clearance(d.model, d.realised, d.kinds, d.coils, d.realised_names, d.q, margin=MARGIN)
    assert found.within and set(found.within) == {r[0] for r in found.failing()}
    q = d.q[:WITHIN_POSES]
    pieces = spring_pieces(d.model, d.realised, d.kinds, d.coils, d.realised_names, q)
    for spring, share in found.within.items():
        own = [p for p in pieces if p.name.partition(" ")[0] == spring]
        near = [any(clearances(d.model, [_poses(p, slice(i, i + 1))], q[[i]], margin=MARGIN).worst(0)[0] < MARGIN
                    for p in own) for i in range(len(q))]
        assert share == pytest.approx(np.mean(near), abs=1e-12) and 0 < share < 1
    design = replace(d, clearance=found)
    flags = [f for f in design.flags() if "cannot be mounted" in f]
    assert flags and all(f"of {len(q)} check poses" in f for f in flags)
    shares = [r.get("share_of_poses_within_margin") for r in design.as_dict()["realised"]]
    assert sorted(s for s in shares if s) == sorted(found.within.values())
    assert spring_clearance(d.model, d.realised, d.kinds, d.coils, d.realised_names, d.q).within == {}
