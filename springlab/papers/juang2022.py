"""Data of Juang, Jhuang and Chen (2022), *Spring efficiency assessment and efficient use
of spring methods of statically balanced planar serial manipulators with revolute
joints only*, Mechanical Sciences (paper 003): the 3-DOF example of Section 5, as
printed. SI units; angles in degrees as printed.

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2022). Spring efficiency assessment and efficient
use of spring methods of statically balanced planar serial manipulators with revolute
joints only. Mechanical Sciences (2022).
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from springlab.design.rank import configuration_of, rank_of
from springlab.errors import SpringlabError
from springlab.mechanisms.planar.efficiency import efficiency_index, spring_efficiency
from springlab.mechanisms.planar.model import PlanarArm, PlanarSpring, Workspace, to_spatial
from springlab.mechanisms.planar.synthesis import com_distances, design, solve_configuration
from springlab.model.armfile import arm_from_dict
from springlab.tables import Table

# Table 3: link 1 is the ground (reference length r_1 = 1 m)
R = (1.000, 0.360, 0.445, 0.300)  # m
M = (25.0, 26.0, 18.0)  # m_2..m_4 (kg)
WORKSPACE = Workspace(low=(-20.0, -140.0, -140.0), high=(180.0, 140.0, 140.0))  # theta_2..theta_4 (deg)
G_PRINTED = (553.7, 303.8, 88.2)  # |G_12|, |G_13|, |G_14| (N/m), Section 5, one decimal
EQ31 = 100.0  # %: 003 Eq. (31), a 1-DOF manipulator's system spring efficiency, Section 4.2

# Not printed: the COM distances and g that give G_PRINTED (found in the notebook):
S = (0.180, 0.2225, 0.150)  # s_2..s_4 = r_j / 2 (m)
G = 9.8  # m/s^2

ARM = PlanarArm(r=R, s=(0.0,) + S, m=(0.0,) + M, g=G)

# Table 4: configuration Λ3-1
TABLE4 = (  # (i, j, k (N/m), a (m), b (m), alpha, beta (deg))
    (1, 4, 3038.0, 0.100, 0.087, 90.0, 0.0),
    (1, 2, 4998.0, 0.100, 0.180, 90.0, 0.0),
    (2, 4, 6076.0, 0.180, 0.087, 0.0, 0.0),
    (3, 4, 6615.0, 0.223, 0.240, 180.0, 180.0),
)
SPRINGS_PRINTED = tuple(PlanarSpring(*row) for row in TABLE4)
FREE_CHOICES = {"A_S14": 0.1, "A_S24": 0.5, "A_S12": 0.1, "B_S12": 0.5, "A_S34": 0.5, "B_S34": 0.8}
"""Table 4's free choices: A_S14, A_S24 (the text's), and the one-joint springs' attachments."""

# Table 5: stiffnesses (N/m) and the index after each adjustment
TABLE5 = {
    "before": ({"A_S14": 0.1, "A_S24": 0.5}, {"k_S12": 4998, "k_S14": 3038, "k_S24": 6076, "k_S34": 6615}, 0.5389),
    "A_S14 0.1 -> 0.4": ({"A_S14": 0.4, "A_S24": 0.5}, {"k_S12": 4998, "k_S14": 760, "k_S24": 1519, "k_S34": 1654}, 0.6224),
    "A_S24 0.5 -> 0.8": ({"A_S14": 0.1, "A_S24": 0.8}, {"k_S12": 4998, "k_S14": 3038, "k_S24": 3798, "k_S34": 4961}, 0.5426),
}


def table4_entries(designed):
    """Each printed k (N/m, 0 decimals), a and b (m, 3 decimals) of Table 4 beside the designed
    spring of the same S(i,j) (``designed`` in Table 1's order S(1,2), S(1,4), S(2,4), S(3,4)):
    (designed spring, printed spring, name, decimals, unit) in print order."""
    order = SPRINGS_PRINTED[1:2] + SPRINGS_PRINTED[:1] + SPRINGS_PRINTED[2:]
    for mine, printed in zip(designed, order, strict=True):
        if (mine.i, mine.j) != (printed.i, printed.j):
            raise SpringlabError(f"designed {mine.label} where Table 4 prints {printed.label}: pass Table 1's order")
        for name, dec, unit in (("k", 0, "N/m"), ("a", 3, "m"), ("b", 3, "m")):
            yield mine, printed, name, dec, unit


def table2_comparisons():
    """Table 2's printed payload-adjustment formulas (003 Eqs. 27-29 as the table prints them)
    beside the same parameters solved from 003 Eqs. (16) in sympy, with the stiffnesses and
    B of the one-joint springs kept: [(configuration, parameter, derived, printed or None)]."""
    import sympy as sp

    k = {n: sp.Symbol(f"k_S{n}", positive=True) for n in ("12", "13", "14", "23", "24", "34")}
    B = {n: sp.Symbol(f"B_S{n}", positive=True) for n in ("12", "23", "34")}
    G12, G13, G14 = sp.symbols("G_12 G_13 G_14", positive=True)

    def solved(config, given):
        return {key.name: v for key, v in solve_configuration(config, given).items()}

    s1 = solved("Λ1", ["k_S12", "B_S12"])
    s2 = solved("Λ2", ["k_S13", "k_S23", "B_S23"])
    s31 = solved("Λ3-1", ["k_S12", "k_S14", "k_S24", "k_S34", "B_S12", "B_S34"])
    s32 = solved("Λ3-2", ["k_S12", "k_S14", "k_S23", "k_S24", "B_S12", "B_S23"])
    return [
        ("Λ1", "(AB)'_S12", s1["A_S12"] * B["12"], G12 / k["12"]),
        ("Λ2", "A'_S13", s2["A_S13"], G12 / k["13"]),
        ("Λ2", "B'_S13", s2["B_S13"], G13 / G12),
        ("Λ2", "(AB)'_S23", s2["A_S23"] * B["23"], k["13"] * G13 / (k["23"] * G12)),
        ("Λ3-1", "A'_S14", s31["A_S14"], G13 / k["14"]),
        ("Λ3-1", "B'_S14", s31["B_S14"], G14 / G13),
        ("Λ3-1", "(AB)'_S34", s31["A_S34"] * B["34"], (k["14"] + k["24"]) / k["34"] * G14 / G13),
        ("Λ3-1", "B'_S24", s31["B_S24"], None),
        ("Λ3-1", "A'_S24 (unchanged)", s31["A_S24"], None),
        ("Λ3-2", "A'_S14", s32["A_S14"], G13 / k["14"]),
        ("Λ3-2", "B'_S14", s32["B_S14"], G14 / G13),
        ("Λ3-2", "B'_S24", s32["B_S24"], G14 / G13),
        ("Λ3-2", "(AB)'_S23", s32["A_S23"] * B["23"], (k["14"] + k["24"]) / k["23"]),
        ("Λ3-2", "A'_S24", s32["A_S24"], None),
    ]


def arm_spec():
    """The Section 5 arm as springlab's arm-file description (:class:`~springlab.model.armfile.ArmSpec`):
    revolute joints about z, links 2..4 of Table 3."""
    return arm_from_dict({"name": "paper 003's arm (Section 5)", "g": ARM.g,
                          "link": [{"length": float(r), "com": float(s), "mass": float(m), "joint": [0, 0, 1]}
                                   for r, s, m in zip(ARM.r[1:], ARM.s[1:], ARM.m[1:], strict=True)]}, source="003")


def table_3() -> Table:
    """Table 3 as the paper prints it: the links' lengths (m), masses (kg) and workspace (deg); link 1 is
    the ground's reference length, link 4 the added one.

    >>> print(table_3())
    | link | length r_i (m) | mass m_i (kg) | workspace |
    |---|---|---|---|
    | 1 | 1.000 | - | - |
    | 2 | 0.360 | 25 | theta_2: +180° to -20° |
    | 3 | 0.445 | 26 | theta_3: +140° to -140° |
    | 4 | 0.300 (an additional link) | 18 | theta_4: +140° to -140° |
    """
    rows = [[1, f"{R[0]:.3f}", "-", "-"]]
    for i in range(3):
        lo, hi = WORKSPACE.low[i], WORKSPACE.high[i]
        rows.append([i + 2, f"{R[i + 1]:.3f}" + (" (an additional link)" if i == 2 else ""), f"{M[i]:g}",
                     f"theta_{i + 2}: {hi:+g}° to {lo:+g}°"])
    return Table(["link", "length r_i (m)", "mass m_i (kg)", "workspace"], rows)


SECOND_CHOICES = {"A_S14": 0.1, "B_S24": 0.5, "A_S12": 0.1, "B_S12": 0.5, "A_S23": 0.5, "B_S23": 0.8}
"""Free choices (A = a / r_i, B = b / r_j) for configuration Λ3-2, ours: the paper gives it none."""


def ranks_in(report) -> Table:
    """Where the paper's configurations Λ3-1 (with its free choices) and Λ3-2 (with
    :data:`SECOND_CHOICES`) stand among a ranked list of designs for this arm (a
    :class:`springlab.design.rank.DesignReport`), as paper 000's springs: rank (None when
    missing) and the largest force (N) of the ranked design."""
    rows = []
    for name, free in {"Λ3-1": FREE_CHOICES, "Λ3-2": SECOND_CHOICES}.items():
        configuration = configuration_of(to_spatial(ARM, design(ARM, name, free))[1])
        found = rank_of(report, configuration)
        force = f"{report.designs[found - 1].max_force:.0f}" if found else "-"
        rows.append((name, " ".join(map(str, configuration)), found, len(report.designs), force))
    return Table(["003", "as 000's springs", "rank", "of", "largest force (N)"], rows)


def com_table(gs) -> Table:
    """The COM distances s_2..s_4 (m) that give the printed |G_1j| (003 Eq. 7) at each g (m/s^2) of
    ``gs``, and their ratios to the links' lengths."""
    rows = []
    for g in gs:
        s = com_distances(R, M, G_PRINTED, g)
        rows.append((g, *np.round(s, 5), *np.round(s / np.array(R[1:]), 5)))
    return Table(["g (m/s^2)", "s_2 (m)", "s_3 (m)", "s_4 (m)", "s_2/r_2", "s_3/r_3", "s_4/r_4"], rows)


def printed_eq27() -> dict:
    """003 Eqs. (27a-e) as printed, typed in (sympy): B_S14, k_S14, B_S24, k_S24 and k_S34 in the
    |G_1j| and the free choices; (27e) as printed gives (k A B)_S34, here divided by A_S34 B_S34."""
    G13, G14, A14, A24, A34, B34 = sp.symbols("G_13 G_14 A_S14 A_S24 A_S34 B_S34", positive=True)
    return {"B_S14": G14 / G13,  # 003 Eq. (27a)
            "k_S14": G13 / A14,  # 003 Eq. (27b)
            "B_S24": G14 / G13,  # 003 Eq. (27c)
            "k_S24": G13 / (A14 * A24),  # 003 Eq. (27d)
            "k_S34": (G13 / A14 + G13 / (A14 * A24)) * G14 / G13 / (A34 * B34)}  # 003 Eq. (27e)


def table4_table(results) -> Table:
    """Table 4 beside ours: ``results`` holds, per entry of :func:`table4_entries`, (spring label, name,
    (the paper's value, its printed decimals), ours, ours minus the paper's, status)."""
    return Table(["spring", "quantity", "paper", "ours", "difference", "status"],
                 [(label, name, f"{paper:.{decimals}f}", f"{ours:.5g}", f"{diff:+.2g}", status)
                  for label, name, (paper, decimals), ours, diff, status in results])


def table2_check() -> tuple[Table, dict, dict]:
    """Table 2's printed payload-adjustment formulas beside the ones derived from 003 Eqs. (16)
    (:func:`table2_comparisons`): the table (LaTeX in its cells), and per (configuration, parameter)
    whether they agree (None: not printed) and the derived expression."""
    rows, same, derived = [], {}, {}
    for config, label, expr, printed in table2_comparisons():
        derived[config, label] = expr
        same[config, label] = None if printed is None else sp.simplify(expr - printed) == 0
        shown = f"${sp.latex(printed)}$" if printed is not None else "(not printed)"
        verdict = {True: "equal", False: "**differs**", None: "**missing**"}[same[config, label]]
        rows.append((config, label, shown, f"${sp.latex(sp.simplify(expr))}$", verdict))
    return Table(["configuration", "parameter", "Table 2", "derived (balance equations)", ""], rows), same, derived


def index_table(indices: dict, printed: dict, readings) -> Table:
    """Each design's efficiency index (003 Eq. 24) by each reading of X and Y beside the printed one:
    ``indices`` {case: {reading: index}}, ``printed`` {case: Table 5's index}."""
    heads = {"magnitudes": "magnitudes (Section 4.1)", "literal": "literal (X, Y as printed)",
             "direct": "direct (the definition)"}
    return Table(["case", "paper", *(heads.get(r, r) for r in readings)],
                 [(case, value, *(f"{indices[case][r]:.4f}" for r in readings)) for case, value in printed.items()])


def resolution_table(steps, sizes, curves: dict, literal) -> Table:
    """The index on each grid: ``steps`` (deg), ``sizes`` (poses), ``curves`` {case: [index per step]},
    ``literal`` [Table 4's index read literally, per step]."""
    return Table(["grid step (deg)", "poses", *curves, "before, literal"],
                 [(f"{step:g}", size, *(f"{curve[k]:.4f}" for curve in curves.values()), f"{literal[k]:.4f}")
                  for k, (step, size) in enumerate(zip(steps, sizes, strict=True))])


def payload_table(ratios, indices: dict) -> Table:
    """The index against the payload (a fraction of m_4) under each rebalancing rule: ``indices``
    {rule: [index per ratio]}."""
    return Table(["payload / m_4", *indices],
                 [(f"{r:g}", *(f"{v[k]:.4f}" for v in indices.values())) for k, r in enumerate(ratios)])


def configurations(arm: PlanarArm = ARM, workspace: Workspace = WORKSPACE) -> dict:
    """Table 1's configurations on Table 3's arm, {name: (arm, workspace, free choices)}: Λ1 on link 2
    alone, Λ2 on links 2-3, Λ3-1 and Λ3-2 on the whole arm (Λ1's and Λ2's choices, and Λ3-2's, ours)."""
    def first(n):
        return PlanarArm(r=arm.r[:n], s=arm.s[:n], m=arm.m[:n], g=arm.g)

    low, high = workspace.low, workspace.high
    return {"Λ1": (first(2), Workspace(low[:1], high[:1]), {"A_S12": 0.1, "B_S12": 0.5}),
            "Λ2": (first(3), Workspace(low[:2], high[:2]), {"A_S13": 0.1, "A_S23": 0.5, "B_S23": 0.8}),
            "Λ3-1": (arm, workspace, FREE_CHOICES),
            "Λ3-2": (arm, workspace, SECOND_CHOICES)}


def configurations_table(setups: dict, step: float = 5.0) -> tuple[Table, dict]:
    """Each configuration of :func:`configurations` designed: its DOF, springs, joints spanned, sum of
    k (N/m), index and each spring's mean efficiency on a ``step`` (deg) grid; with the designs,
    {name: (arm, workspace, springs)}."""
    rows, designed = [], {}
    for name, (a, w, choice) in setups.items():
        springs = design(a, name, choice)
        designed[name] = (a, w, springs)
        grid = w.grid_poses(step)
        means = ", ".join(f"{s.label} {spring_efficiency(a, s, grid).mean():.3f}" for s in springs)
        rows.append((name, a.n - 1, len(springs), sum(s.j - s.i for s in springs), f"{sum(s.k for s in springs):.0f}",
                     f"{efficiency_index(a, springs, w, step=step):.4f}", means))
    return Table(["configuration", "DOF", "springs", "joints spanned", "sum of k (N/m)", f"index ({step:g} deg)",
                  "spring efficiencies (means)"], rows), designed


def optimum_table(best: dict, reference: float) -> Table:
    """Each configuration's best design by the index (:func:`springlab.mechanisms.planar.synthesis.optimise_index`
    results, {name: result}) against ``reference``, the best index the paper prints."""
    return Table(["configuration", "best free parameters", "stiffnesses (N/m)", "index", f"/ {reference:g}",
                  "evaluations"],
                 [(name, ", ".join(f"{k} = {v:.3f}" for k, v in o.parameters.items()),
                   ", ".join(f"{s.label} {s.k:.0f}" for s in o.design), f"{o.value:.4f}", f"{o.value / reference:.3f}",
                   o.evaluations) for name, o in best.items()])
