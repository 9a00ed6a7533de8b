"""Paper 003: planar pseudo-stiffness, spring and system efficiency, the index (springlab.mechanisms.planar)."""

import numpy as np
import pytest
import sympy as sp

from springlab.energy import geometry, quadratic
from springlab.errors import SpringlabError, UnbalanceableError
from springlab.mechanisms.planar import efficiency as ef
from springlab.mechanisms.planar import geometry as plgeo
from springlab.mechanisms.planar import model as pl
from springlab.mechanisms.planar import quadratic as plq
from springlab.mechanisms.planar import synthesis as plsyn
from springlab.papers import juang2022 as paper

ARM, WS = paper.ARM, paper.WORKSPACE
TABLE4 = plsyn.design(ARM, "Λ3-1", paper.FREE_CHOICES)


def random_theta(N, seed=0, n=3):
    return np.radians(np.random.default_rng(seed).uniform(-180, 180, (N, n)))


def angled_springs(seed):
    rng = np.random.default_rng(seed)
    return [pl.PlanarSpring(i, j, rng.uniform(100, 5000), rng.uniform(0.05, 1) * ARM.r[i - 1],
                            rng.uniform(0.05, 1) * ARM.r[j - 1], rng.uniform(0, 360), rng.uniform(0, 360))
            for i, j in [(1, 2), (1, 3), (1, 4), (2, 3), (2, 4), (3, 4)]]


def test_G_and_com_distances():
    assert np.allclose(ARM.G, paper.G_PRINTED, atol=1e-9)
    assert np.allclose(plsyn.com_distances(paper.R, paper.M, paper.G_PRINTED, 9.8), np.array(paper.R[1:]) / 2)
    with pytest.raises(SpringlabError, match="need r_1"):
        plsyn.com_distances(paper.R, paper.M[:2], paper.G_PRINTED, 9.8)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_route1_equals_route2_with_angled_attachments(seed):
    springs = angled_springs(seed)
    theta = random_theta(2000, seed)
    r1 = plq.quadratic_energy(ARM, springs, theta)
    r2 = plgeo.energies(ARM, springs, theta)["total"]
    assert np.max(np.abs(r1 - r2)) < 1e-9 * np.ptp(r2)
    assert np.ptp(r2) > 100  # not balanced: the test compares real variation


def test_spring_term_count_and_formulas():
    for i, j in [(1, 2), (1, 4), (2, 4), (3, 4)]:
        assert len(plq.spring_terms(i, j, 1.0, 0.5, 0.5, 0.0, 0.0)) == (j - i) * (j - i + 1) // 2
    # Eq. (14): a spring over one joint has one term kAB cos(alpha - beta + 180 - Theta)
    (t,) = plq.spring_terms(2, 3, 10.0, 0.5, 0.4, 30.0, 10.0)
    assert (t.u, t.v, t.amplitude, t.phase) == (2, 3, 2.0, 200.0)


def test_planar_form_is_000s_spatial_form_in_a_plane():
    loose = [pl.PlanarSpring(s.i, s.j, 0.7 * s.k, s.a, s.b, s.alpha, s.beta) for s in TABLE4]
    C, S = plq.spatial_coefficients(ARM, loose)
    chain, springs = pl.to_spatial(ARM, loose)
    M = quadratic.energy_matrix(chain, springs)
    assert np.max(np.abs(C)) > 10 and np.allclose(C, np.triu(M, 1), atol=1e-9) and np.allclose(S, 0, atol=1e-9)
    theta = random_theta(500, 4)
    X = chain.directions(pl.spatial_angles(theta))
    assert np.allclose(geometry.total_energy(chain, springs, X), plgeo.energies(ARM, loose, theta)["total"], atol=1e-9)
    _, S_angled = plq.spatial_coefficients(ARM, angled_springs(5))
    assert np.max(np.abs(S_angled)) > 1
    with pytest.raises(SpringlabError, match="C1"):
        pl.to_spatial(ARM, angled_springs(5))


def test_equations_27_and_tables_4_5():
    sol = {k.name: v for k, v in plsyn.solve_configuration("Λ3-1", ["A_S14", "A_S24", "A_S12", "B_S12", "A_S34", "B_S34"]).items()}
    G13, G14, A14, A24 = sp.symbols("G_13 G_14 A_S14 A_S24", positive=True)
    assert sp.simplify(sol["B_S14"] - G14 / G13) == 0 and sp.simplify(sol["k_S24"] - G13 / (A14 * A24)) == 0
    ks = [s.k for s in TABLE4]
    assert np.allclose(ks, [4998, 3038, 6076, 6615])
    after = plsyn.design(ARM, "Λ3-1", paper.FREE_CHOICES | {"A_S14": 0.4})
    assert np.allclose([s.k for s in after], [4998, 759.5, 1519, 1653.75])


@pytest.mark.parametrize("config, choices", [
    ("Λ3-1", paper.FREE_CHOICES),
    ("Λ3-2", {"A_S14": 0.2, "B_S24": 0.6, "A_S12": 0.1, "B_S12": 0.5, "A_S23": 0.5, "B_S23": 0.8}),
])
def test_designs_balance_by_geometry(config, choices):
    springs = plsyn.design(ARM, config, choices)
    theta = random_theta(3000, 8)
    E = plgeo.energies(ARM, springs, theta)
    assert np.ptp(E["total"]) < 1e-10 * np.ptp(E["gravity"])
    off = [pl.PlanarSpring(s.i, s.j, s.k * (1.02 if s.i == 1 else 1.0), s.a, s.b, s.alpha, s.beta) for s in springs]
    assert np.ptp(plgeo.energies(ARM, off, theta)["total"]) > 1e-3 * np.ptp(E["gravity"])


def test_lambda32_forces_A24_and_table2_B24_differs():
    springs = plsyn.design(ARM, "Λ3-2", {"A_S14": 0.1, "B_S24": 0.5, "A_S12": 0.1, "B_S12": 0.5, "A_S23": 0.5, "B_S23": 0.8})
    s24 = next(s for s in springs if (s.i, s.j) == (2, 4))
    assert np.isclose(s24.A(ARM), 1.0)
    adjusted = plsyn.payload_adjustment(ARM, springs, "Λ3-2", 18.0)
    heavy = ARM.with_payload(18.0)
    b24 = next(s for s in adjusted if (s.i, s.j) == (2, 4)).B(ARM)
    assert not np.isclose(b24, heavy.G[2] / heavy.G[1])
    E = plgeo.energies(heavy, adjusted, random_theta(1000, 2))
    assert np.ptp(E["total"]) < 1e-10 * np.ptp(E["gravity"])


def test_efficiencies():
    theta = random_theta(1000, 3)
    mono = next(s for s in TABLE4 if s.j == s.i + 1)
    assert np.allclose(ef.spring_efficiency(ARM, mono, theta), 1.0)  # Eq. (22)
    ground = next(s for s in TABLE4 if (s.i, s.j) == (1, 4))
    e = ef.spring_efficiency(ARM, ground, theta)
    assert np.all((e > 0) & (e < 1))
    for reading in ef.READINGS:
        e_sys = ef.system_efficiency(ARM, TABLE4, theta, reading=reading)
        assert np.all((e_sys >= 0.5 - 1e-12) & (e_sys <= 1 + 1e-12))
    assert np.allclose(ef.system_efficiency(ARM, TABLE4, theta, reading="magnitudes"),
                       ef.system_efficiency(ARM, TABLE4, theta, reading="direct"))
    with pytest.raises(SpringlabError, match="reading"):
        ef.system_efficiency(ARM, TABLE4, theta, reading="average")


def test_index_reproduces_the_paper_on_a_5_degree_grid():
    assert round(ef.efficiency_index(ARM, TABLE4, WS, step=5), 4) == 0.5389
    after = plsyn.design(ARM, "Λ3-1", paper.FREE_CHOICES | {"A_S14": 0.4})
    assert round(ef.efficiency_index(ARM, after, WS, step=5), 4) == 0.6224
    assert round(ef.efficiency_index(ARM, TABLE4, WS, step=5, reading="literal"), 4) == 0.5351


def test_indices_in_one_pass_equal_the_plain_means():
    """efficiency_indices shares terms across designs; each (design, reading) must still be
    the plain mean of e_sys over the grid, and a design must not leak into another's."""
    after = plsyn.design(ARM, "Λ3-1", paper.FREE_CHOICES | {"A_S14": 0.4})
    step = 15
    grid = np.stack(np.meshgrid(*WS.grid(step), indexing="ij"), -1).reshape(-1, 3)
    got = ef.efficiency_indices(ARM, {"table 4": TABLE4, "after": after}, WS, step=step, readings=ef.READINGS)
    for label, springs in (("table 4", TABLE4), ("after", after)):
        for reading in ef.READINGS:
            plain = ef.system_efficiency(ARM, springs, grid, reading=reading).mean()
            assert abs(got[(label, reading)] - plain) < 1e-14
    assert abs(got[("after", "magnitudes")] - got[("table 4", "magnitudes")]) > 0.05  # the designs differ
    with pytest.raises(SpringlabError, match="designs is empty"):
        ef.efficiency_indices(ARM, {}, WS, step=step)
    with pytest.raises(SpringlabError, match="reading"):
        ef.efficiency_indices(ARM, {"a": TABLE4}, WS, step=step, readings=("average",))


def test_one_more_reading_of_one_design_in_the_same_pass():
    """``also`` adds a (design, reading) pair to the pass: its index is the one efficiency_index
    gives alone, to the last bit, and the others' are unchanged; unknown labels are refused."""
    after = plsyn.design(ARM, "Λ3-1", paper.FREE_CHOICES | {"A_S14": 0.4})
    designs, step = {"table 4": TABLE4, "after": after}, 10
    plain = ef.efficiency_indices(ARM, designs, WS, step=step)
    got = ef.efficiency_indices(ARM, designs, WS, step=step, also=[("table 4", "literal")])
    assert set(got) == set(plain) | {("table 4", "literal")} and all(got[k] == plain[k] for k in plain)
    assert got[("table 4", "literal")] == ef.efficiency_index(ARM, TABLE4, WS, step=step, reading="literal")
    assert got[("table 4", "literal")] != got[("table 4", "magnitudes")]
    with pytest.raises(SpringlabError, match="also must hold"):
        ef.efficiency_indices(ARM, designs, WS, step=step, also=[("before", "literal")])
    with pytest.raises(SpringlabError, match="reading"):
        ef.efficiency_indices(ARM, designs, WS, step=step, also=[("after", "average")])


def test_grid_index_equals_the_plain_mean():
    step = 20
    axes = WS.grid(step)
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 3)
    for reading in ef.READINGS:
        plain = ef.system_efficiency(ARM, TABLE4, grid, reading=reading).mean()
        assert np.isclose(ef.efficiency_index(ARM, TABLE4, WS, step=step, reading=reading), plain, atol=1e-14)
    assert len(axes[0]) == 11 and np.isclose(np.degrees(axes[0][-1]), 180)  # ends included
    mc = ef.efficiency_index(ARM, TABLE4, WS, samples=50_000, seed=1, chunk=8192)
    assert abs(mc - ef.efficiency_index(ARM, TABLE4, WS, step=2)) < 5e-3
    assert mc == ef.efficiency_index(ARM, TABLE4, WS, samples=50_000, seed=1, chunk=8192)


def test_payload_rules():
    stiff = plsyn.payload_adjustment(ARM, TABLE4, "Λ3-1", 9.0)
    assert np.allclose([s.k for s in stiff], [s.k for s in TABLE4])
    kept = plsyn.payload_adjustment(ARM, TABLE4, "Λ3-1", 9.0, keep="attachments")
    assert np.allclose([s.A(ARM) for s in kept], [s.A(ARM) for s in TABLE4])
    heavy = ARM.with_payload(9.0)
    for springs in (stiff, kept):
        E = plgeo.energies(heavy, springs, random_theta(500, 6))
        assert np.ptp(E["total"]) < 1e-10 * np.ptp(E["gravity"])
    i0 = ef.efficiency_index(ARM, TABLE4, WS, step=10)
    assert ef.efficiency_index(heavy, stiff, WS, step=10) > i0 > ef.efficiency_index(heavy, kept, WS, step=10)


def test_optimiser_respects_bounds():
    fixed = {k: v for k, v in paper.FREE_CHOICES.items() if k not in ("A_S14", "A_S24")}
    opt = plsyn.optimise_index(ARM, "Λ3-1", {"A_S14": (0.05, 0.6), "A_S24": (0.05, 0.7)}, fixed, WS, step=20,
                            start={"A_S14": 0.1, "A_S24": 0.5})
    assert opt.parameters["A_S14"] <= 0.6 + 1e-9 and opt.parameters["A_S24"] <= 0.7 + 1e-9
    assert opt.value > ef.efficiency_index(ARM, TABLE4, WS, step=20)
    assert max(s.k for s in opt.design) <= opt.settings["k_max"]


@pytest.mark.parametrize("spring, match", [
    (pl.PlanarSpring(1, 4, 3000, 0.1, 0.087, 45, 0), "breaks C1"),
    (pl.PlanarSpring(2, 4, 3000, 0.1, 0.087, 0, 180), "breaks C2"),
    (pl.PlanarSpring(3, 4, 3000, 0.2, 0.2, 90, 0), "breaks C2"),
    (pl.PlanarSpring(1, 4, 3000, 1.5, 0.087, 90, 0), r"A = 1.5 must lie in \(0, 1\]"),
    (pl.PlanarSpring(2, 4, 3000, 0.1, 0.0, 0, 0), r"B = 0 must lie in \(0, 1\]"),
    (pl.PlanarSpring(2, 5, 10.0, 0.1, 0.1, 0, 0), "1 <= i < j <= 4"),
])
def test_bad_springs(spring, match):
    with pytest.raises(SpringlabError, match=match):
        ef.system_efficiency(ARM, [spring], random_theta(3))


def test_a_negative_stiffness_is_refused_when_the_spring_is_made():
    with pytest.raises(SpringlabError, match=r"k of S\(2,4\) must be finite and > 0 N/m, got -1.0"):
        pl.PlanarSpring(2, 4, -1.0, 0.1, 0.1, 0, 0)


def test_bad_workspaces_and_arms():
    with pytest.raises(SpringlabError, match="reversed"):
        pl.Workspace(low=(-20, 140, -140), high=(180, -140, 140))
    with pytest.raises(SpringlabError, match="one entry per joint"):
        pl.Workspace(low=(), high=())
    with pytest.raises(SpringlabError, match="step must be"):
        WS.grid(0)
    with pytest.raises(SpringlabError, match="exactly one"):
        ef.efficiency_index(ARM, TABLE4, WS)
    with pytest.raises(SpringlabError, match="seed"):
        ef.efficiency_index(ARM, TABLE4, WS, samples=10)
    with pytest.raises(SpringlabError, match="unknown configuration 'Λ4'"):
        plsyn.design(ARM, "Λ4", paper.FREE_CHOICES)
    with pytest.raises(SpringlabError, match="empty sample"):
        ef.efficiency_index(ARM, TABLE4, WS, samples=0, seed=1)
    with pytest.raises(SpringlabError, match="workspace has 2 joints"):
        ef.efficiency_index(ARM, TABLE4, pl.Workspace((0, 0), (1, 1)), step=1)
    point = pl.Workspace(low=(10, 20, 30), high=(10, 20, 30))  # a single pose: fine
    assert ef.efficiency_index(ARM, TABLE4, point, step=5) == pytest.approx(
        ef.system_efficiency(ARM, TABLE4, np.radians([[10, 20, 30]]))[0])
    with pytest.raises(SpringlabError, match="m_3 = -26"):
        pl.PlanarArm(r=paper.R, s=ARM.s, m=(0, 25, -26, 18))
    with pytest.raises(SpringlabError, match="off link 2"):
        pl.PlanarArm(r=paper.R, s=(0, 0.5, 0.2, 0.1), m=ARM.m)
    with pytest.raises(UnbalanceableError, match="not determined"):
        plsyn.design(pl.PlanarArm(r=ARM.r[:2], s=ARM.s[:2], m=ARM.m[:2], g=9.8), "Λ1", {"A_S12": 0.1})  # k B left open
    choices = {k: v for k, v in paper.FREE_CHOICES.items() if k != "A_S34"} | {"k_S34": 100.0}
    with pytest.raises(SpringlabError, match=r"S\(3,4\): attachment ratio A = .* must lie in"):  # a too soft S(3,4)
        plsyn.design(ARM, "Λ3-1", choices)


def test_holding_torques_vanish_for_a_balanced_design_and_not_for_the_control():
    theta = WS.sample(200, 3)
    balanced = plgeo.holding_torques(ARM, TABLE4, theta)
    bare = plgeo.holding_torques(ARM, [], theta)
    assert balanced.shape == (200, 3)
    assert np.abs(balanced).max() < 1e-6 * np.abs(bare).max()
    spoiled = [pl.PlanarSpring(s.i, s.j, 0.9 * s.k, s.a, s.b, s.alpha, s.beta) for s in TABLE4]
    assert np.abs(plgeo.holding_torques(ARM, spoiled, theta)).max() > 1e-2 * np.abs(bare).max()


def test_the_same_spring_over_more_joints_is_less_efficient_on_average_not_at_every_pose():
    # 003 Eq. (23): over one joint the efficiency is 1 (Eq. 22); the workspace mean falls with each joint spanned
    grid = np.stack(np.meshgrid(*WS.grid(10), indexing="ij"), -1).reshape(-1, ARM.n - 1)
    eff = ef.spans(ARM, 1, grid, k=500.0, A=0.3, B=0.5, alpha=90.0, beta=0.0)
    assert sorted(eff) == [2, 3, 4] and np.allclose(eff[2], 1.0)
    assert eff[2].mean() > eff[3].mean() > eff[4].mean()
    assert 0 < np.mean(eff[4] > eff[3]) < 0.2  # pose by pose S(1,4) is the more efficient somewhere
    rows, changes = ef.span_rows(ARM, {"ground": (1, dict(k=500.0, A=0.3, B=0.5, alpha=90.0, beta=0.0))}, grid)
    assert [r[1] for r in rows] == ["S(1,2)", "S(1,3)", "S(1,4)"] and set(changes) == {("ground", 1, 3), ("ground", 1, 4)}
    assert all(change < 0 for change, _ in changes.values())
    assert changes["ground", 1, 4][1] == pytest.approx(np.mean(eff[4] > eff[3] + 1e-12))
    with pytest.raises(SpringlabError, match="C1"):  # the control: a ground spring over one joint needs alpha - beta = 90
        ef.spans(ARM, 1, grid, k=500.0, A=0.3, B=0.5, alpha=0.0, beta=0.0)


def test_the_chapters_tables_of_paper_003():
    import sympy as sp

    from springlab.mechanisms.planar import synthesis as plsyn

    table = paper.com_table((9.8, 9.81))
    assert [float(x) for x in table.rows[0][4:]] == [0.5, 0.5, 0.5]  # g = 9.8: every COM at mid-link
    assert [float(x) for x in table.rows[1][4:]] != [0.5, 0.5, 0.5]  # the control: 9.81 does not fit
    sol = {k.name: v for k, v in plsyn.solve_configuration(
        "Λ3-1", ["A_S14", "A_S24", "A_S12", "B_S12", "A_S34", "B_S34"]).items()}
    assert all(sp.simplify(sol[n] - e) == 0 for n, e in paper.printed_eq27().items())
    _, same, derived = paper.table2_check()
    assert same[("Λ3-2", "B'_S24")] is False and same[("Λ3-1", "B'_S14")] is True
    setups = paper.configurations()
    table, designed = paper.configurations_table(setups)
    assert [row[0] for row in table.rows] == ["Λ1", "Λ2", "Λ3-1", "Λ3-2"] and table.rows[0][5] == "1.0000"
    assert set(designed) == set(setups)


def test_a_workspaces_grid_poses_are_every_combination_of_its_joints_grids():
    poses = paper.WORKSPACE.grid_poses(20)
    assert poses.shape == (paper.WORKSPACE.grid_size(20), 3)
    axes = paper.WORKSPACE.grid(20)
    assert np.array_equal(poses[1], [axes[0][0], axes[1][0], axes[2][1]])  # the last joint varies fastest
    assert len({tuple(p) for p in poses}) == len(poses)  # every combination once
