"""Data of Lin, Shieh and Chen (2010), *Design of a Gravity-Balanced General Spatial
Serial-Type Manipulator*, J. Mechanisms Robotics 2, 031003 (paper 001): the 6-DOF
example of Section 6, as printed. SI units: m, kg, rad, s; stiffnesses in N/m.

Link numbering follows the paper: links 1..6, link 0 the ground. Table 2 gives no
data for link 1 (its joint axis is vertical, so its weight never changes the
energy); its mass is 0 here.

References
----------
Lin, P.-Y., Shieh, W.-B., Chen, D.-Z. (2010). Design of a gravity-balanced general spatial
serial-type manipulator. Journal of Mechanisms and Robotics 2(3), 031003. doi:10.1115/1.4001816
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from springlab.mechanisms.pseudobase.model import (
    DH,
    PseudobaseArm,
    attachment_a,
    aux_offset_from_dh,
)
from springlab.mechanisms.pseudobase.subsystems import combined_subsystems, subsystem_energy
from springlab.rounding import half_unit, propagated_rounding
from springlab.tables import Table

# Table 1: DH parameters (standard DH), primary / auxiliary chains
DH_PRIMARY = DH(d=[0.0, 0.0, 0.0, 0.5, 0.0, 0.27],
                a=[0.1, 0.4, 0.0, 0.0, 0.0, 0.0],
                alpha=np.radians([90.0, 0.0, 90.0, -90.0, 90.0, 0.0]))
DH_AUX = DH(d=[0.1, 0.0, 0.0, 0.5, 0.0, 0.27],  # d^_1 = 0.1: the auxiliary chain sits 0.1 m higher
            a=[0.1, 0.4, 0.0, 0.0, 0.0, 0.0],
            alpha=np.radians([90.0, 0.0, 90.0, -90.0, 90.0, 0.0]))

# Table 2: links 2..6 (index 0 is link 2)
LINKS = (2, 3, 4, 5, 6)
M = [23.21, 24.51, 15.13, 6.12, 2.20]  # m_i (kg)
M_STAR = [0.47, 0.47, 0.47, 0.47, 0.47]  # m*_i, pseudobases (kg)
M_HAT = [2.38, 0.81, 1.58, 1.32, 0.27]  # m^_i, auxiliary links (kg)
S = [(-0.20, 0.00, -0.1), (0, 0, 0), (0, 0.16, 0.00), (0, 0.02, 0.11), (0, 0.00, -0.02)]  # s_i, frame i
S_HAT = [(-0.17, 0.07, 0.06), (0, 0.02, 0.10), (0, 0.13, 0.00), (0, 0.01, 0.09), (0, -0.02, -0.08)]
R = [(-0.4, 0, 0), (0, 0, 0), (0, 0.5, 0), (0, 0, 0), (0, 0, -0.27)]  # r_i, frame i
R_HAT = [(-0.4, 0, 0), (0, 0, 0), (0, 0.5, 0), (0, 0, 0), (0, 0, -0.27)]
C = [(-0.3, 0.1, -0.1), (0, 0.06, 0.09), (0, 0.21, 0.06), (0, -0.1, 0.1), (0, -0.06, -0.06)]  # c_i
MU_TILDE = [105.92, 79.59, 45.21, 18.76, 5.88]  # printed with 2 decimals (kg)
SIGMA_TILDE = [(0.25, 0.00, -0.02), (0, 0.00, 0.00), (0, -0.25, 0.00), (0, 0.00, 0.05), (0, -0.01, 0.12)]  # 2 decimals (m)

# Table 3: springs 2..6
K = [20.0e3, 2.0e3, 15.0e3, 2.0e3, 1.0e3]  # N/m (printed in kN/m, 1 decimal)
L_CA = [0.1, 0.08, 0.08, 0.08, 0.08]  # m
L_CB = [0.13, 0.01, 0.09, 0.05, 0.09]  # m, 2 decimals
A = [(-0.2, 0.1, -0.1), (0.08, 0.06, 0.09), (0.08, 0.21, 0.06), (0.08, -0.1, 0.1), (0.08, -0.06, -0.06)]  # frame i
B = [(-0.17, 0.10, -0.11), (0, 0.06, 0.09), (0, 0.12, 0.06), (0, -0.09, 0.15), (0, -0.06, 0.03)]

# Table 4: joint i: t_I, t_F (s), theta_I, theta_F (rad), a_0..a_3 of 001 Eq. (26)
TABLE4 = np.array([
    [0, 5, 1.57, -0.42, 1.57, 0.0000, -0.2388, 0.0318],
    [0, 5, 1.57, 0.57, 1.57, 0.0000, -0.12, 0.016],
    [0, 5, 0, 1, 0, 0, 0.12, -0.016],
    [1, 3, 0, 1, 1, -2.25, 1.5, -0.25],
    [5, 9, 0, 1.2, 10.3125, -5.0625, 0.7875, -0.0375],
    [5, 9, 0, 2.5, 21.4844, -10.5429, 1.6406, -0.0781],
])
TABLE4_DECIMALS = np.array([  # printed decimals of a_0..a_3, per row
    [2, 4, 4, 4], [2, 4, 2, 3], [0, 0, 2, 3], [0, 2, 1, 2], [4, 4, 4, 4], [4, 4, 4, 4]])
DURATION = 10.0  # s, 001 Eq. (26)
INITIAL_POSE = TABLE4[:, 2]  # theta_I: the pose at which Table 3 prints a_i (x_2..x_6 vertical)

G = 9.81  # m/s^2; not stated. Table 3's two-digit l_CB cannot tell 9.8 from 9.81.


def _rows(values, first=(0.0, 0.0, 0.0)):
    return np.vstack([first, np.asarray(values, dtype=float)])


def arm(g: float = G) -> PseudobaseArm:
    """The 6-DOF arm of 001 Section 6 with its five modules (links 2..6)."""
    offset = aux_offset_from_dh(DH_PRIMARY, DH_AUX)  # 0.1 m along the vertical z_0
    return PseudobaseArm(
        dh=DH_PRIMARY, m=np.r_[0.0, M], s=_rows(S), modules=LINKS,
        m_hat=np.r_[0.0, M_HAT], s_hat=_rows(S_HAT), m_star=np.r_[0.0, M_STAR], c=_rows(C),
        aux_offset=offset, g=g)


# --- Tables 2 and 3 recomputed, with what their printed rounding allows ----------------------
INPUT_DECIMALS = 2  # Table 2 prints its masses (kg) and vectors (m) with 2 decimals


def table2_inputs() -> np.ndarray:
    """Table 2's printed inputs as one vector (60,): m, m^, m* (kg), then s, s^, c (m) of links 2..6."""
    return np.concatenate([M, M_HAT, M_STAR, np.ravel(S), np.ravel(S_HAT), np.ravel(C)])


def combined_from_inputs(x, base: PseudobaseArm | None = None):
    """(mu~, sigma~) (001 Eqs. 24-25) of the arm with Table 2's inputs replaced by ``x``
    (as :func:`table2_inputs` orders them); the DH chain, offset and g from ``base``."""
    base = base or arm()
    m, mh, ms = x[:5], x[5:10], x[10:15]
    s, sh, c = x[15:30].reshape(5, 3), x[30:45].reshape(5, 3), x[45:60].reshape(5, 3)
    a = PseudobaseArm(dh=base.dh, m=np.r_[0, m], s=_rows(s), modules=LINKS, m_hat=np.r_[0, mh], s_hat=_rows(sh),
                      m_star=np.r_[0, ms], c=_rows(c), aux_offset=base.aux_offset, g=base.g)
    return combined_subsystems(a)


def _band(f):
    x = table2_inputs()
    return propagated_rounding(f, x, np.full(x.size, half_unit(INPUT_DECIMALS))) + half_unit(INPUT_DECIMALS)


def table2_rows(base: PseudobaseArm) -> list[dict]:
    """Each printed mu~_i (kg) and sigma~_i component (m) of Table 2 beside ours (001 Eqs. 24-25),
    with the band Table 2's rounded inputs allow (propagated to first order, plus half a unit):
    dicts with quantity, kind ('mu' or 'sigma'), unit, paper, ours, band, in print order."""
    mu, sigma = combined_subsystems(base)
    rows = []
    for k, i in enumerate(LINKS):
        band = _band(lambda x, i=i: combined_from_inputs(x, base)[0][i - 1])
        rows.append({"quantity": f"mu~_{i}", "kind": "mu", "unit": "kg", "paper": MU_TILDE[k],
                     "ours": mu[i - 1], "band": band})
        for axis, name in enumerate("xyz"):
            band = _band(lambda x, i=i, axis=axis: combined_from_inputs(x, base)[1][i - 1, axis])
            rows.append({"quantity": f"sigma~_{i},{name}", "kind": "sigma", "unit": "m",
                         "paper": SIGMA_TILDE[k][axis], "ours": sigma[i - 1, axis], "band": band})
    return rows


def table3_rows(base: PseudobaseArm, springs) -> list[dict]:
    """Table 3 beside ours, per spring: l_CB (001 Eq. 16, with its band), the largest-differing
    component of a_i at theta_I (001 Eq. 13) and of b_i (001 Eq. 14, with its band); each a
    dict with quantity, kind ('l_CB', 'a' or 'b'), paper, ours (m), band (None: half a unit only), note, and the
    spring's 'printed' K l_CA l_CB and 'need' mu~ g |sigma~| (N m)."""
    mu, sigma = combined_subsystems(base)
    a_init = attachment_a(base, springs, INITIAL_POSE)[0]
    rows = []
    for k, sp_ in enumerate(springs):
        i = sp_.link
        need = mu[i - 1] * base.g * np.linalg.norm(sigma[i - 1])  # mu~ g |sigma~|, 001 Eq. (16)
        printed = K[k] * L_CA[k] * L_CB[k]

        def l_cb(x, i=i, k=k):
            m, s = combined_from_inputs(x)
            return m[i - 1] * base.g * np.linalg.norm(s[i - 1]) / (K[k] * L_CA[k])

        common = {"spring": i, "printed": printed, "need": need, "l_CB": sp_.l_CB, "b": sp_.b}
        rows.append({"quantity": f"l_CB,{i}", "kind": "l_CB", "paper": L_CB[k], "ours": sp_.l_CB,
                     "band": _band(l_cb), "note": f"K l_CA l_CB printed {printed:.2f} N m vs mu~ g |sigma~| = {need:.2f} N m",
                     **common})
        ja = int(np.argmax(np.abs(a_init[k] - np.asarray(A[k]))))
        rows.append({"quantity": f"a_{i}, {'xyz'[ja]} (largest difference)", "kind": "a",
                     "paper": A[k][ja], "ours": a_init[k, ja], "band": None, "note": "", **common})
        jb = int(np.argmax(np.abs(sp_.b - np.asarray(B[k]))))

        def b_comp(x, i=i, jb=jb, k=k):
            m, s = combined_from_inputs(x)
            return x[45 + 3 * (i - 2) + jb] + m[i - 1] * base.g * s[i - 1, jb] / (K[k] * L_CA[k])

        rows.append({"quantity": f"b_{i}, {'xyz'[jb]} (largest difference)", "kind": "b",
                     "paper": B[k][jb], "ours": sp_.b[jb], "band": _band(b_comp), "note": None, **common})
    return rows


def _g(x: float) -> str:
    return f"{x:g}"


def table_1() -> Table:
    """Table 1 as the paper prints it: the standard DH parameters of frames i / i^ (primary / auxiliary
    chain): d (m), theta, a (m), alpha (deg).

    >>> print(table_1())  # doctest: +ELLIPSIS
    | frame i / i^ | d_i / d^_i (m) | theta_i | a_i / a^_i (m) | alpha_i / alpha^_i (deg) |
    |---|---|---|---|---|
    | 1 / 1^ | 0 / 0.1 | theta_1 | 0.1 / 0.1 | 90 / 90 |
    ...
    """
    p, q = DH_PRIMARY, DH_AUX
    return Table(["frame i / i^", "d_i / d^_i (m)", "theta_i", "a_i / a^_i (m)", "alpha_i / alpha^_i (deg)"],
                 [[f"{i + 1} / {i + 1}^", f"{_g(p.d[i])} / {_g(q.d[i])}", f"theta_{i + 1}",
                   f"{_g(p.a[i])} / {_g(q.a[i])}",
                   f"{_g(round(np.degrees(p.alpha[i])))} / {_g(round(np.degrees(q.alpha[i])))}"]
                  for i in range(len(p.d))])


def table_2() -> Table:
    """Table 2 as the paper prints it (kg and m, vectors in frame i), a column a link: the masses of the
    links, pseudobases and auxiliary links, the vectors s, s^, r, r^ and c, and the combined masses and
    vectors (001 Eqs. 24-25) the chapter recomputes. A vector's components print without trailing zeros
    (the paper prints some with two decimals, some with one)."""
    def vec(v):
        return "(" + ", ".join(_g(x) for x in v) + ")"
    rows = [("m_i", [f"{x:.2f}" for x in M]), ("m*_i", [f"{x:.2f}" for x in M_STAR]),
            ("m^_i", [f"{x:.2f}" for x in M_HAT]),
            ("s_i", [vec(v) for v in S]), ("s^_i", [vec(v) for v in S_HAT]), ("r_i", [vec(v) for v in R]),
            ("r^_i", [vec(v) for v in R_HAT]), ("c_i", [vec(v) for v in C]),
            ("mu~_i", [f"{x:.2f}" for x in MU_TILDE]), ("sigma~_i", [vec(v) for v in SIGMA_TILDE])]
    return Table(["link i", *map(str, LINKS)], [[name, *cells] for name, cells in rows])


def table2_table(results) -> Table:
    """Table 2's combined masses and vectors beside ours: ``results`` holds, per row of
    :func:`table2_rows`, (row, ours minus the paper's, status)."""
    return Table(["quantity", "paper", "ours", "difference", "rounding bound", "status"],
                 [(f"{r['quantity']} ({r['unit']})", f"{r['paper']:.2f}", f"{r['ours']:.4f}", f"{diff:+.4f}",
                   f"{r['band']:.4f}", status) for r, diff, status in results])


def table3_table(results) -> Table:
    """Each spring's l_CB (001 Eq. 16) beside Table 3's, with the printed K l_CA l_CB against the
    mu~ g |sigma~| it must equal (N m) and our b_i (m): ``results`` holds, per l_CB row of
    :func:`table3_rows`, (row, status)."""
    return Table(["spring", "K l_CA l_CB, printed (N m)", "mu~ g abs(sigma~) (N m)", "mismatch", "l_CB paper (m)",
                  "l_CB ours (m)", "b ours (m)", "status"],
                 [(r["spring"], f"{r['printed']:.2f}", f"{r['need']:.2f}", f"{100 * (r['printed'] / r['need'] - 1):+.1f} %",
                   f"{r['paper']:.2f}", f"{r['ours']:.4f}", np.round(r["b"], 4).tolist(), status)
                  for r, status in results])


def normalisations(arm, q, splits: dict) -> tuple[Table, dict]:
    """001 Eq. (5)'s subsystems under each normalisation of the masses (``splits``: label -> mu, as
    :func:`~springlab.mechanisms.pseudobase.subsystems.combined_subsystems` takes it; None for
    001 Eq. (24)'s): a table of subsystem 2's mu~ (kg), abs(sigma~) (m), its spring's K l_CA l_CB = mu~ g
    abs(sigma~) (N m, 001 Eq. 16) and the energy at the last pose of ``q`` (rad, (N, n)) (J), a row per label;
    and the subsystems' energy along ``q`` (J, (N,)) by label."""
    rows, energy = [], {}
    for label, mu in splits.items():
        mu_i, sigma_i = combined_subsystems(arm, mu=mu)
        energy[label] = subsystem_energy(arm, q, mu_i, sigma_i)
        size = float(np.linalg.norm(sigma_i[1]))
        rows.append((label, f"{mu_i[1]:.3f}", f"{size:.5f}", f"{mu_i[1] * arm.g * size:.4f}",  # 001 Eq. (16)
                     f"{energy[label][-1]:.6f}"))
    table = Table(["normalisation", "mu~_2 (kg)", "abs(sigma~_2) (m)", "K l_CA l_CB (N m)", "energy at the end (J)"],
                  rows)
    return table, energy


def endpoint_table(jumps) -> Table:
    """How far each printed cubic of Table 4 misses its own end points (rad): ``jumps`` (joints, 2),
    at t_I and t_F."""
    return Table(["joint", "printed cubic(t_I) - theta_I (rad)", "printed cubic(t_F) - theta_F (rad)"],
                 [(j + 1, f"{a:+.4f}", f"{b:+.4f}") for j, (a, b) in enumerate(jumps)])


def equilibrator_forms() -> dict:
    """001 Eqs. (9a), (9b), (12) and (15) in sympy, for one equilibrator: a spring K from A to B, a
    subsystem of mass mu at sigma, gravity g (3-vectors of symbols). 001 Eq. (12)'s two sides come with
    001 Eqs. (13)-(14) substituted: a - c along -g at l_CA, b - c along sigma at l_CB."""
    def vec(name):
        return sp.Matrix(sp.symbols(f"{name}_x {name}_y {name}_z", real=True))

    a, b, g, s = (vec(v) for v in ("a", "b", "g", "sigma"))
    K, mu, l_CA, l_CB = sp.symbols("K mu l_CA l_CB", positive=True)
    ac, bc = -l_CA / g.norm() * g, l_CB / s.norm() * s  # 001 Eqs. (13), (14): a_i - c_i, b_i - c_i
    return {"9a": K / 2 * (b - a).dot(b - a) - mu * g.dot(s),  # 001 Eq. (9a)
            "9b": -K * b.dot(a) + K / 2 * (a.dot(a) + b.dot(b)) - mu * g.dot(s),  # 001 Eq. (9b)
            "12": (K / 2 * (bc - ac).dot(bc - ac), -K * ac.dot(bc) + K / 2 * (l_CA**2 + l_CB**2)),  # 001 Eq. (12)
            "15": K * l_CA * l_CB / (g.norm() * s.norm()) * g.dot(s) + K / 2 * (l_CA**2 + l_CB**2)}  # 001 Eq. (15)


def single_link_spreads(*, turns: int = 2000, seed: int = 3) -> dict[str, float]:
    """One link on a spherical joint at O with one spring: the total energy's range over gravity's,
    over ``turns`` random orientations, with OB' along sigma as 001 Eq. (10) asks ('met') and
    off it ('control'). Illustrative numbers: mu 2 kg, sigma (0.3, 0.1, 0.2) m, K 400 N/m, l_CA 0.1 m,
    l_CB from 001 Eq. (16)."""
    from scipy.spatial.transform import Rotation

    rotations = Rotation.random(turns, random_state=seed).as_matrix()
    mu, sigma, g, k, a_len = 2.0, np.array([0.3, 0.1, 0.2]), np.array([0.0, 0.0, -9.81]), 400.0, 0.1
    b_len = mu * 9.81 * np.linalg.norm(sigma) / (k * a_len)  # 001 Eq. (16): K l_CA l_CB = mu g sigma
    a = -a_len * g / 9.81  # 001 Eq. (13): OA' along -g, up
    ends = {"met": b_len * sigma / np.linalg.norm(sigma), "control": b_len * np.array([1.0, 0.0, 0.0])}
    spread = {}
    for label, b0 in ends.items():  # OB' along sigma (001 Eq. 14), and off it
        b, s = rotations @ b0, rotations @ sigma
        total = 0.5 * k * np.sum((b - a) ** 2, axis=1) - mu * s @ g  # 001 Eq. (9a), J
        spread[label] = float(np.ptp(total) / np.ptp(-mu * s @ g))
    return spread
