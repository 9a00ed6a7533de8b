"""Paper 001: rotational subsystems, pseudobases, RSSR modules (springlab.mechanisms.pseudobase)."""

import numpy as np
import pytest
import sympy as sp

from springlab.errors import SpringlabError, UnbalanceableError
from springlab.mechanisms.pseudobase import geometry as pbgeo
from springlab.mechanisms.pseudobase import model as pb
from springlab.mechanisms.pseudobase import simulation as ps
from springlab.mechanisms.pseudobase import subsystems as subs
from springlab.model.trajectories import PiecewiseCubic, rest_to_rest_cubic
from springlab.papers import lin2010 as paper

ARM = paper.arm()
SPRINGS = subs.design_equilibrators(ARM, paper.K, paper.L_CA)


def random_poses(N, seed=0):
    return np.random.default_rng(seed).uniform(-np.pi, np.pi, (N, ARM.n))


def random_arm(seed):
    """A random 5-link arm, joint 1 vertical, modules on links 2..5."""
    rng = np.random.default_rng(seed)
    n = 5
    dh = pb.DH(d=rng.uniform(-0.3, 0.3, n), a=rng.uniform(0, 0.5, n),
               alpha=rng.choice([0, np.pi / 2, -np.pi / 2], n) + rng.normal(0, 0.2, n) * (np.arange(n) > 0))
    dh = pb.DH(d=dh.d, a=dh.a, alpha=np.r_[np.pi / 2, dh.alpha[1:]])
    zero = np.zeros(3)
    return pb.PseudobaseArm(dh=dh, m=rng.uniform(1, 10, n), s=rng.uniform(-0.2, 0.2, (n, 3)), modules=range(2, n + 1),
                            m_hat=np.r_[0, rng.uniform(0.2, 2, n - 1)], s_hat=np.vstack([zero, rng.uniform(-0.2, 0.2, (n - 1, 3))]),
                            m_star=np.r_[0, rng.uniform(0.1, 1, n - 1)], c=np.vstack([zero, rng.uniform(-0.2, 0.2, (n - 1, 3))]),
                            aux_offset=[0, 0, 0.12], g=9.81)


def test_link_vectors_are_the_dh_origins():
    R, org = ARM.dh.frames(random_poses(20))
    r = ARM.link_vectors()
    for i in range(1, ARM.n + 1):
        world = np.einsum("nij,j->ni", R[:, i], r[i - 1])
        assert np.allclose(world, org[:, i - 1] - org[:, i], atol=1e-14)
    assert np.allclose(r[1:], paper.R, atol=1e-15)


def test_symbolic_eqs_4_to_8_agree():
    for n in range(1, 6):
        e = subs.symbolic_subsystems(n)
        assert sp.expand(e["eq4"] - e["eq5"]) == 0
        assert sp.simplify(e["eq5"] - e["eq6"]) == 0
    with pytest.raises(SpringlabError, match="n must be"):
        subs.symbolic_subsystems(0)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_subsystem_energy_equals_direct_geometry_up_to_a_constant(seed):
    arm = ARM if seed == 0 else random_arm(seed)
    q = np.random.default_rng(seed).uniform(-np.pi, np.pi, (200, arm.n))
    mu, sigma = subs.combined_subsystems(arm)
    diff = pbgeo.energies(arm, [], q)["gravity"] - subs.subsystem_energy(arm, q, mu, sigma)
    assert np.ptp(diff) < 1e-11
    # without modules' masses, Eqs. (7)-(8) alone
    mu0, sigma0 = subs.subsystems(arm.m, arm.s, arm.link_vectors())
    primary = pbgeo.energies(arm, [], q)["gravity_primary"] - subs.subsystem_energy(arm, q, mu0, sigma0)
    assert np.ptp(primary) < 1e-11


def test_only_the_product_mu_sigma_is_physical():
    q = random_poses(100)
    mu, sigma = subs.combined_subsystems(ARM)
    mu2, sigma2 = subs.combined_subsystems(ARM, mu=np.arange(1.0, ARM.n + 1))
    assert not np.allclose(mu, mu2)
    assert np.allclose(mu[:, None] * sigma, mu2[:, None] * sigma2)
    assert np.allclose(subs.subsystem_energy(ARM, q, mu, sigma), subs.subsystem_energy(ARM, q, mu2, sigma2), atol=1e-11)
    with pytest.raises(SpringlabError, match="mu must be"):
        subs.combined_subsystems(ARM, mu=np.zeros(ARM.n))


def test_the_chapters_normalisations_share_one_energy_and_one_spring_product():
    """001 Eq. (16)'s K l_CA l_CB = mu~ g |sigma~| is the same under every normalisation, and so is the energy;
    a normalisation's mu~_2 and |sigma~_2| are not (the control: the table would not show three of them)."""
    q = random_poses(50)
    own = np.where(ARM.m + ARM.m_hat + ARM.m_star > 0, ARM.m + ARM.m_hat + ARM.m_star, 1.0)
    table, energy = paper.normalisations(ARM, q, {"Eq. (24)": None, "own": own, "1 kg": np.ones(ARM.n)})
    assert [r[0] for r in table.rows] == ["Eq. (24)", "own", "1 kg"]
    assert len({r[3] for r in table.rows}) == 1 and len({r[4] for r in table.rows}) == 1
    assert len({r[1] for r in table.rows}) == 3 and len({r[2] for r in table.rows}) == 3
    assert max(np.ptp(energy[k] - energy["Eq. (24)"]) for k in energy) < 1e-9
    assert float(table.rows[0][3]) == pytest.approx(263.4730, abs=5e-5)  # Table 3's S2 need, as the chapter prints it


@pytest.mark.parametrize("seed", [0, 3, 4])
def test_designed_springs_balance_and_rounded_ones_do_not(seed):
    arm = ARM if seed == 0 else random_arm(seed)
    k = len(arm.modules)
    springs = subs.design_equilibrators(arm, np.full(k, 2000.0), np.full(k, 0.08))
    mu, sigma = subs.combined_subsystems(arm)
    for s in springs:  # Eq. (16)
        assert np.isclose(s.K * s.l_CA * s.l_CB, mu[s.link - 1] * arm.g * np.linalg.norm(sigma[s.link - 1]))
    q = np.random.default_rng(seed).uniform(-np.pi, np.pi, (500, arm.n))
    E = pbgeo.energies(arm, springs, q)
    assert np.ptp(E["total"]) < 1e-10 * np.ptp(E["gravity"])
    off = pbgeo.energies(arm, [s.scaled(0.99) for s in springs], q)
    assert np.ptp(off["total"]) > 1e-3 * np.ptp(off["gravity"])


def test_table3_springs_as_printed_leave_an_unbalance():
    printed = subs.design_equilibrators(ARM, paper.K, paper.L_CA, l_CB=paper.L_CB)
    q = PiecewiseCubic(paper.TABLE4[:, :4]).angles(np.linspace(0, 10, 201))
    assert np.ptp(pbgeo.energies(ARM, printed, q)["total"]) > 1.0  # J
    assert np.ptp(pbgeo.energies(ARM, SPRINGS, q)["total"]) < 1e-9


def test_pseudobases_stay_vertical_and_attachment_points():
    q = random_poses(50)
    p = pbgeo.positions(ARM, SPRINGS, q)
    line = p["D"] - p["C"]
    assert np.allclose(line, ARM.h * ARM.up, atol=1e-14)
    for col, s in enumerate(SPRINGS):
        assert np.allclose(p["A"][:, col] - p["C"][:, col], s.l_CA * ARM.up, atol=1e-14)
        assert np.allclose(np.linalg.norm(p["B"][:, col] - p["C"][:, col], axis=1), s.l_CB)
    a = pb.attachment_a(ARM, SPRINGS, np.r_[0.3, np.pi / 2, 0, 0, 0, 0])[0]
    assert np.allclose(a - ARM.c[1:], np.array([[s.l_CA, 0, 0] for s in SPRINGS]), atol=1e-15)


def test_fold_margin_vanishes_where_the_crank_is_vertical():
    q = np.zeros((3, ARM.n))
    q[:, 1] = [np.pi / 4 - 0.1, np.pi / 4, np.pi / 4 + 0.1]  # module 2's crank c_2 - r_2 at 45 deg in link 2
    margin = pb.fold_margin(ARM, q)[:, 0]
    assert abs(margin[1]) < 1e-15 and margin[0] * margin[2] < 0
    t = np.linspace(0, 10, 2001)
    crossings = pb.fold_crossings(t, pb.fold_margin(ARM, PiecewiseCubic(paper.TABLE4[:, :4]).angles(t)), ARM.modules)
    assert [link for _, link in crossings] == [2, 6]
    assert abs(crossings[0][0] - 3.5024) < 1e-3


def test_mobility_eqs_19_20():
    assert pb.mobility(4, [1, 3, 3, 1]) == 2  # Eq. (19)
    assert pb.mobility(4, [1, 1, 1, 1], lam=3) == 1  # a planar four-bar
    for n in range(1, 8):
        assert pb.module_chain_mobility(n) == 2 * n  # Eq. (20)
    assert pb.mobility(17, [1] * 11 + [3] * 10) == 11  # the 6-DOF example: 6 active + 5 idle
    for bad in ((0, [1]), (4, [0, 1]), (4, [6]), (4, [1.5])):
        with pytest.raises(SpringlabError):
            pb.mobility(*bad)
    with pytest.raises(SpringlabError, match="lam"):
        pb.mobility(4, [1], lam=4)


def test_joint_space_inertia_one_link():
    arm = pb.PseudobaseArm(dh=pb.DH(d=[0.0], a=[0.5], alpha=[0.0]), m=[2.0], s=[[-0.1, 0, 0]], modules=[1],
                           m_hat=[0.5], s_hat=[[-0.2, 0, 0]], m_star=[0.3], c=[[-0.3, 0, 0]], aux_offset=[0, 0.1, 0],
                           up=[0, 1, 0])
    M = pb.joint_space_inertia(arm, [[0.7]], gyration=0.05)[0, 0, 0]
    expected = 2.0 * (0.4**2 + 0.05**2) + 0.5 * (0.3**2 + 0.05**2) + 0.3 * 0.2**2
    assert np.isclose(M, expected)
    q = random_poses(5)
    M6 = pb.joint_space_inertia(ARM, q)
    assert np.allclose(M6, np.swapaxes(M6, 1, 2))
    assert np.all(np.linalg.eigvalsh(M6) > -1e-12)
    assert np.all(np.diagonal(M6, axis1=1, axis2=2) >= np.diagonal(pb.joint_space_inertia(ARM, q, parts=("primary",)), axis1=1, axis2=2))


def test_eq26_cubics():
    c = rest_to_rest_cubic(5, 9, 0, 1.2)
    assert np.allclose(c, paper.TABLE4[4, 4:])  # row 5 exactly
    traj = PiecewiseCubic(paper.TABLE4[:, :4])
    assert np.allclose(traj.endpoint_errors(), 0, atol=1e-12)
    t = np.linspace(0, 10, 1001)
    h = 1e-6
    assert np.allclose(traj.rates(t[1:-1]), (traj.angles(t[1:-1] + h) - traj.angles(t[1:-1] - h)) / (2 * h), atol=1e-6)
    for j, (t_I, t_F) in enumerate(paper.TABLE4[:, :2]):  # at rest at both ends
        assert np.allclose(traj.rates(np.array([t_I, t_F - 1e-12]))[:, j], 0, atol=1e-9)
    printed = PiecewiseCubic(paper.TABLE4[:, :4], paper.TABLE4[:, 4:])
    errors = printed.endpoint_errors()
    assert abs(errors[5, 1] - 0.052) < 1e-3 and np.all(np.abs(errors[1:5]) < 1e-9)
    with pytest.raises(SpringlabError, match="after"):
        PiecewiseCubic([[3, 1, 0, 1]])
    with pytest.raises(SpringlabError, match="coefficients"):
        PiecewiseCubic([[0, 1, 0, 1]], [[0, 1, 2]])
    with pytest.raises(SpringlabError, match="t_F > t_I"):
        rest_to_rest_cubic(1, 1, 0, 1)


def _arm_kwargs(**changes):
    kw = dict(dh=paper.DH_PRIMARY, m=ARM.m, s=ARM.s, modules=ARM.modules, m_hat=ARM.m_hat, s_hat=ARM.s_hat,
              m_star=ARM.m_star, c=ARM.c, aux_offset=ARM.aux_offset)
    kw.update(changes)
    return kw


@pytest.mark.parametrize("changes, match", [
    (dict(m=np.r_[0, -1.0, ARM.m[2:]]), r"m\[1\] \(link 2\) = -1.0 kg"),
    (dict(m_star=np.r_[0, 0.47, -0.1, 0.47, 0.47, 0.47]), "m_star"),
    (dict(aux_offset=[0.05, 0, 0.1]), "not vertical|from vertical"),
    (dict(aux_offset=[0, 0, 0]), "aux_offset"),
    (dict(up=[1.0, 0, 0], aux_offset=[0.1, 0, 0]), "joint 1's axis"),
    (dict(modules=(3, 4, 5, 6)), "modules"),
    (dict(s=np.zeros((6, 2))), "s must be"),
    (dict(m=np.r_[0, np.nan, ARM.m[2:]]), "m must be"),
    (dict(m_hat=np.r_[1.0, ARM.m_hat[1:]]), "no module"),
])
def test_bad_arms_are_rejected(changes, match):
    with pytest.raises(SpringlabError, match=match):
        pb.PseudobaseArm(**_arm_kwargs(**changes))


def test_bad_springs_are_rejected():
    with pytest.raises(SpringlabError, match="K of spring 3 = 0.0 N/m"):
        subs.design_equilibrators(ARM, [2e4, 0.0, 1.5e4, 2e3, 1e3], paper.L_CA)
    with pytest.raises(SpringlabError, match="l_CA of spring 2"):
        subs.design_equilibrators(ARM, paper.K, [-0.1, 0.08, 0.08, 0.08, 0.08])
    with pytest.raises(SpringlabError, match="one per module"):
        subs.design_equilibrators(ARM, paper.K[:4], paper.L_CA)
    with pytest.raises(UnbalanceableError, match="spring 3 cannot be attached"):
        subs.design_equilibrators(ARM, [2e4, 10.0, 1.5e4, 2e3, 1e3], paper.L_CA, max_l_CB=0.3)
    flat = pb.PseudobaseArm(**_arm_kwargs(m_hat=np.zeros(6), m_star=np.r_[0, 0, 1e-9, 0, 0, 0],
                                          c=np.zeros((6, 3)), s=np.zeros((6, 3)),
                                          dh=pb.DH(d=np.zeros(6), a=np.r_[0.1, np.zeros(5)], alpha=paper.DH_PRIMARY.alpha)))
    with pytest.raises(UnbalanceableError, match="needs no spring"):
        subs.design_equilibrators(flat, paper.K, paper.L_CA)
    with pytest.raises(SpringlabError, match="joint angles"):
        pbgeo.energies(ARM, SPRINGS, np.zeros((3, 5)))


# --- route 3 ---------------------------------------------------------------------------
def test_rssr_model_keeps_pseudobases_vertical_and_energy_constant():
    traj = PiecewiseCubic(paper.TABLE4[:, :4])
    run = ps.follow(ARM, SPRINGS, traj.angles, 2.0, model="rssr", samples=11, step=1e-2)
    assert run.tilt.max() < 1e-9
    assert run.total_variation < 1e-8 * run.gravity_range
    assert np.allclose(run.gravity - run.route2["gravity"], 0, atol=1e-8)
    assert np.allclose(run.springs, run.route2["springs"], atol=1e-8)


def test_holding_torques_balanced_vs_springs_removed():
    q = PiecewiseCubic(paper.TABLE4[:, :4]).angles(np.array([1.0, 8.0]))
    for model in ("rssr", "ideal"):
        bal = ps.holding_torques(ARM, SPRINGS, q, model=model)
        bare = ps.holding_torques(ARM, SPRINGS, q, model=model, spring_scale=0.0)
        assert np.allclose(bare, pbgeo.holding_torques(ARM, SPRINGS, q, spring_scale=0.0), atol=1e-3)
        assert np.abs(bare).max() > 100 and np.abs(bal).max() < 1e-3 * np.abs(bare).max()
    with pytest.raises(SpringlabError, match="model"):
        ps.build_model(ARM, SPRINGS, q[0], model="parallel", joints="locked")
    with pytest.raises(SpringlabError, match="start at the reference pose"):
        ps.build_model(ARM, SPRINGS, q[0], joints="driven", trajectory=lambda t: q[1])


def test_aux_chain_from_its_own_dh_table():
    offset = pb.aux_offset_from_dh(paper.DH_PRIMARY, paper.DH_AUX)
    assert np.allclose(offset, [0, 0, 0.1])
    q = random_poses(100)
    (Rp, Op), (Ra, Oa) = paper.DH_PRIMARY.frames(q), paper.DH_AUX.frames(q)
    assert np.allclose(Ra, Rp) and np.allclose(Oa[:, 1:] - Op[:, 1:], offset, atol=1e-14)
    with pytest.raises(SpringlabError, match="first joint pair is not vertical"):
        pb.aux_offset_from_dh(paper.DH_PRIMARY, paper.DH_AUX, up=[0, np.sin(0.1), np.cos(0.1)])
    bent = pb.DH(d=paper.DH_AUX.d, a=paper.DH_AUX.a + [0, 0.01, 0, 0, 0, 0], alpha=paper.DH_AUX.alpha)
    with pytest.raises(SpringlabError, match="translated"):
        pb.aux_offset_from_dh(paper.DH_PRIMARY, bent)


def test_turning_a_crank_moves_the_fold_and_keeps_the_balance():
    t = np.linspace(0, 10, 1001)
    q = PiecewiseCubic(paper.TABLE4[:, :4]).angles(t)
    turn, best = pb.clearest_crank(ARM, 2, q, samples=72)
    moved = pb.rotate_crank(ARM, 2, turn)
    r2 = ARM.link_vectors()[1]
    axis = np.array([0, 0, 1.0])  # joint 2's axis in frame 2 (alpha_2 = 0)
    before, after = ARM.c[1] - r2, moved.c[1] - r2
    assert np.isclose(np.linalg.norm(np.cross(axis, before)), np.linalg.norm(np.cross(axis, after)))
    assert np.isclose(before @ axis, after @ axis)
    assert best > 0.5 and [k for _, k in pb.fold_crossings(t, pb.fold_margin(moved, q), moved.modules)] == [6]
    springs = subs.design_equilibrators(moved, paper.K, paper.L_CA)
    E = pbgeo.energies(moved, springs, q)
    assert np.ptp(E["total"]) < 1e-10 * np.ptp(E["gravity"])
    with pytest.raises(SpringlabError, match="no module"):
        pb.rotate_crank(ARM, 1, 0.1)


def test_crank_margins_are_the_turned_arms_fold_margins_to_the_last_bit():
    q = PiecewiseCubic(paper.TABLE4[:, :4]).angles(np.linspace(0.0, paper.DURATION, 201))
    turns = np.linspace(-np.pi, np.pi, 24, endpoint=False)
    for link in (2, 6):
        together = pb.crank_margins(ARM, link, q, turns)
        one_by_one = np.stack([pb.fold_margin(pb.rotate_crank(ARM, link, a), q)[:, ARM.modules.index(link)]
                               for a in turns], axis=1)
        assert np.array_equal(together, one_by_one)
        assert np.ptp(together[0]) > 0.1  # the turn moves the margin
    with pytest.raises(SpringlabError, match="no module"):
        pb.crank_margins(ARM, 1, q, turns)


def test_the_equilibrator_forms_agree_and_a_spring_off_sigma_is_caught():
    forms = paper.equilibrator_forms()
    assert sp.expand(forms["9a"] - forms["9b"]) == 0
    left, right = forms["12"]
    assert sp.simplify(left - right) == 0 and sp.simplify(right - forms["15"]) == 0
    assert sp.simplify(forms["15"] - forms["9a"]) != 0  # the control: (15) is (9a) only once (13)-(14) hold
    spreads = paper.single_link_spreads(turns=500)
    assert spreads["met"] < 1e-12 < 0.1 < spreads["control"]  # the control: B' off sigma


def test_the_chapters_tables_show_each_row_given():
    arm = paper.arm()
    rows = paper.table2_rows(arm)
    table = paper.table2_table([(r, r["ours"] - r["paper"], "reproduced") for r in rows])
    assert len(table.rows) == len(rows) and table.rows[0][0] == "mu~_2 (kg)"
    springs = subs.design_equilibrators(arm, paper.K, paper.L_CA)
    l_cb = [r for r in paper.table3_rows(arm, springs) if r["kind"] == "l_CB"]
    assert [row[0] for row in paper.table3_table([(r, "reproduced") for r in l_cb]).rows] == list(paper.LINKS)
    printed = PiecewiseCubic(paper.TABLE4[:, :4], paper.TABLE4[:, 4:])
    jumps = printed.endpoint_errors()
    assert len(paper.endpoint_table(jumps).rows) == 6 and abs(jumps[5]).max() > 0.02  # row 6: its misprint


def test_the_runs_table_reports_each_run_against_the_gravity_range():
    traj = PiecewiseCubic(paper.TABLE4[:, :4])
    run = ps.follow(ARM, SPRINGS, traj.angles, 1.0, model="ideal", step=1e-2, samples=11)
    table = ps.runs_table([(run, "ideal, 0-1 s")], run.gravity_range)
    assert table.rows[0][0] == "ideal, 0-1 s" and float(table.rows[0][2]) < 1e-6
