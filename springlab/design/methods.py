"""The balancing methods compared on one arm: paper 000's springs without auxiliary links
(the best ranked design), the n - 1 ground springs, paper 001's pseudobases (idealised), and
for a two-link arm paper 004's two springs.

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
Lin, P.-Y., Shieh, W.-B., Chen, D.-Z. (2010). Design of a gravity-balanced general spatial
serial-type manipulator. Journal of Mechanisms and Robotics 2(3), 031003. doi:10.1115/1.4001816
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from springlab import _checks
from springlab.design.ground import ground_spring_design
from springlab.design.rank import VERIFY_TOLERANCE, DesignReport, design_arm, workspace_poses
from springlab.errors import SpringlabError, UnbalanceableError
from springlab.model.armfile import ArmSpec
from springlab.model.chain import UP
from springlab.tables import Table


# --- other methods, for comparison ------------------------------------------------------------
@dataclass(frozen=True)
class MethodSummary:
    """One method's best design for an arm, in the comparison's terms (N, N/m, kg)."""

    method: str
    springs: int
    stiffness_sum: float
    max_force: float
    added_mass: float
    efficiency: float
    energy_variation: float
    note: str = ""


def pseudobase_summary(spec: ArmSpec, *, aux_mass_ratio: float = 0.09, pseudobase_mass: float = 0.47,
                       post: float = 0.1) -> MethodSummary:
    """Paper 001's method on this arm, idealised: one spring per moving link i, from a point
    l_CA above its proximal joint on a pseudobase kept vertical (by RSSR parallelograms and an
    auxiliary link beside link i) to a point l_CB along link i, K_i l_CA l_CB = g mu~_i sigma~_i
    (001 Eq. 16). Both lengths are the arm's ``max_attachment`` (B within the link), the
    stiffness the least that balances.

    The auxiliary links (``aux_mass_ratio`` of each link's mass, 001's Table 2 has 9 %, each with
    its centre of mass beside link i's: a translated copy) and
    pseudobases (``pseudobase_mass`` kg each, at the joint, ``post`` m tall) add mass; their
    energy is folded into the combined subsystems (001 Eqs. 24-25). Verified by route 2: every
    body and spring end placed for each workspace pose.
    """
    _checks.instance("spec", spec, ArmSpec, "ArmSpec (load_arm(path))")

    chain = spec.chain()
    if not (0 <= aux_mass_ratio and pseudobase_mass >= 0 and post > 0):
        raise SpringlabError("aux_mass_ratio and pseudobase_mass must be >= 0 and post > 0")
    m = np.asarray(chain.m)
    m_hat = aux_mass_ratio * m
    total = m + m_hat + pseudobase_mass
    beyond = np.r_[np.cumsum(total[::-1])[::-1][1:], 0.0]
    moment = (m + m_hat) * np.asarray(chain.d) + beyond * np.asarray(chain.r)  # mu~ sigma~ along x_i (kg m)
    reach = spec.max_attachment if spec.max_attachment is not None else max(chain.r)
    l_CA = np.full(len(m), reach)
    l_CB = np.minimum(reach, np.asarray(chain.r))
    K = chain.g * moment / (l_CA * l_CB)  # 001 Eq. (16)
    X = workspace_poses(spec, chain)
    joints = chain.joint_positions(X)
    com = chain.com_positions(X)
    heights = com @ UP
    gravity = chain.g * (heights @ (m + m_hat)) + chain.g * ((joints[:, :-1] @ UP) @ np.full(len(m), pseudobase_mass))
    elastic = np.zeros(len(X))
    force = 0.0
    for idx in range(len(m)):
        A = joints[:, idx] + l_CA[idx] * UP  # on the pseudobase, above the proximal joint
        B = joints[:, idx] + l_CB[idx] * X[:, idx + 1]  # along link idx + 2
        stretch = np.linalg.norm(B - A, axis=1)
        elastic += 0.5 * K[idx] * stretch**2
        force = max(force, float(K[idx] * stretch.max()))
    rel = float(np.ptp(gravity + elastic) / np.ptp(gravity))
    if not rel < VERIFY_TOLERANCE:
        raise UnbalanceableError(f"pseudobase design: route 2 variation {rel:.2e} of the gravity range")
    note = "" if K.max() <= spec.max_stiffness else f"exceeds max_stiffness ({K.max():.0f} N/m)"
    added = float(m_hat.sum() + pseudobase_mass * len(m))
    return MethodSummary("pseudobases (001), idealised", len(m), float(K.sum()), force, added, 1.0, rel, note)


def compare_methods(spec: ArmSpec, report: DesignReport | None = None, **pseudobase_options) -> list[MethodSummary]:
    """The best design of each method that applies to the arm: 000's (no auxiliary links, the
    best of that family in ``report``), the n - 1 ground springs (:func:`springlab.design.ground.ground_spring_design`), 001's
    pseudobases (idealised), and 004's two springs where the arm has
    two moving links (n = 3), which are 000's configurations S(1,3) + S(2,3) (Lenzo's layouts
    a and b; c and d need a COM off the link)."""
    report = report or design_arm(spec, method="no auxiliary links", max_designs=5)
    out = []
    ours = [d for d in report.designs if d.method == "no auxiliary links"]  # 000's family of a default report
    if ours:
        d = ours[0]
        out.append(MethodSummary("no auxiliary links (000)", d.spring_count, d.stiffness_sum, d.max_force, 0.0,
                                 d.efficiency, d.energy_variation))
    try:
        d = ground_spring_design(spec, samples=spec.samples, seed=spec.seed)
        out.append(MethodSummary("ground springs, n - 1 (any signs)", d.spring_count, d.stiffness_sum, d.max_force, 0.0,
                                 d.efficiency, d.energy_variation, "000 Eq. (41) forbids the (+,-) ground springs"))
    except (UnbalanceableError, SpringlabError) as err:
        out.append(MethodSummary("ground springs, n - 1 (any signs)", spec.n - 1, float("nan"), float("nan"), 0.0,
                                 float("nan"), float("nan"), f"none within the limits: {err}"[:120]))
    out.append(pseudobase_summary(spec, **pseudobase_options))
    if spec.n == 3:  # Lenzo's two springs are 000's S(1,3) + S(2,3): layouts b (+,+) and a (-,-)
        two = [d for d in ours if [(s.i, s.j) for s in d.springs] == [(1, 3), (2, 3)]]
        if two:
            d = two[0]
            layout = "b" if d.springs[1].pattern == "(+,+)" else "a"
            out.append(MethodSummary("two springs (004)", 2, d.stiffness_sum, d.max_force, 0.0, d.efficiency,
                                     d.energy_variation, f"Lenzo's layout {layout}: 000's {d.label()}"))
    return out


def comparison_table(rows) -> Table:
    """:class:`MethodSummary` rows as a table (shown as Markdown in a notebook)."""
    return Table(["method", "springs", "sum of k (N/m)", "largest spring force (N)", "added mass (kg)",
                  "efficiency", "energy variation", "note"],
                 [(r.method, r.springs, f"{r.stiffness_sum:.0f}", f"{r.max_force:.1f}", f"{r.added_mass:.2f}",
                   f"{r.efficiency:.3f}", f"{r.energy_variation:.1e}", r.note) for r in rows])
