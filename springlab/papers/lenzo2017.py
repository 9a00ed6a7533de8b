"""Data for Lenzo (2017), *Gravity balancing of a spatial serial 4-dof arm without
auxiliary links using minimum number of springs*, AIMETA 2017 (paper 004).

The paper gives no numerical example. The arm below is illustrative, of the size
of an adult human arm (upper arm 0.30 m, forearm and hand 0.35 m; masses and COM
positions of the order of the usual anthropometric tables); the free choices
are ours. SI units.
"""

from __future__ import annotations

from springlab.mechanisms.two_spring_arm import Arm

FOREARM_LENGTH = 0.35  # m, for drawing and simulation (the balance does not depend on it)

ARM = Arm(m1=2.0, m2=1.5, l1=0.30, h1=0.13, h2=0.18, g=9.81)
"""Illustrative human-sized arm: COM of the forearm and hand beyond the elbow (h2 > 0)."""

ARM_COUNTERMASS = Arm(m1=2.0, m2=1.5, l1=0.30, h1=0.13, h2=-0.05, g=9.81)
"""The same arm with a counter-mass on the forearm bringing its COM behind the elbow
(h2 < 0), as layouts c and d need."""

A2 = 0.15  # m, the frame attachment of k2 above the shoulder (free choice, all layouts)
FREE_CHOICES = {  # (a12, b12) in m per layout (our choices, of Fig. 5's sign patterns)
    "a": (-0.05, 0.20),
    "b": (0.06, 0.40),
    "c": (0.06, 0.20),
    "d": (-0.05, 0.40),
}
