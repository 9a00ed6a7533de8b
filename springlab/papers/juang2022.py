"""Data of Juang, Jhuang and Chen (2022), *Spring efficiency assessment and efficient use
of spring methods of statically balanced planar serial manipulators with revolute
joints only*, Mechanical Sciences (paper 003): the 3-DOF example of Section 5, as
printed. SI units; angles in degrees as printed.
"""

from __future__ import annotations

from springlab.mechanisms.planar.model import PlanarArm, PlanarSpring, Workspace

# Table 3: link 1 is the ground (reference length r_1 = 1 m)
R = (1.000, 0.360, 0.445, 0.300)  # m
M = (25.0, 26.0, 18.0)  # m_2..m_4 (kg)
WORKSPACE = Workspace(low=(-20.0, -140.0, -140.0), high=(180.0, 140.0, 140.0))  # theta_2..theta_4 (deg)
G_PRINTED = (553.7, 303.8, 88.2)  # |G_12|, |G_13|, |G_14| (N/m), Section 5, one decimal

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
