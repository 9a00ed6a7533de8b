"""Route 2 for a spring realised as a cable over a pulley: its path, energy and holding torques.

A zero-free-length spring S(i,j) can be built from any extension spring by mounting the
spring along link i and leading a cable from its moving end over a pulley at end A to
end B: the spring then stretches by exactly the cable's path from the pulley to B, so with
the cable cut to absorb the spring's free length and initial tension the force is k times
that path (:mod:`springlab.design.buildable`). With a pulley of radius rho > 0 the path is
not |B - A|. The pulley is centred at A and swivels about link i's line so that its plane
holds B; the cable arrives along +x_i (the spring sits proximally of A, along the link, at
the offset rho) and wraps the pulley until it leaves along the tangent towards B::

    path = rho (alpha + asin(rho / L)) + sqrt(L^2 - rho^2)

with L = |B - A| and alpha the angle between x_i and B - A: the wrapped arc plus the
straight run. It tends to L as rho -> 0; to first order it is L + rho alpha, so the pulley
adds an energy k L rho alpha that depends on the pose, which the balance cannot absorb.

The cable pulls B towards the tangent point T with the tension k (path - l0) (l0 the
spring's effective free length, :attr:`springlab.model.springs.Spring.effective_free_length`,
0 when built as designed); every joint the spring crosses holds (B - J) x tension (B - T) / |B - T|.
Nothing here uses the quadratic form (route 1). Lengths in m, forces in N, torques in N m.
"""

from __future__ import annotations

import numpy as np

from springlab import _checks
from springlab.energy.geometry import attachment_points, cable_geometry, holding_torques
from springlab.errors import GeometryError
from springlab.model.chain import Chain, check_springs
from springlab.model.springs import Spring


def cable_path(chain: Chain, spring: Spring, X, radius: float) -> tuple[np.ndarray, np.ndarray]:
    """The cable's path from the pulley at A to B (m), (N,), and the point T (N, 3) where it
    leaves the pulley, at poses ``X`` (N, n, 3); ``radius`` (m) >= 0 (module docstring).

    :raises GeometryError: where B comes within the pulley's radius of A
    """
    (spring,) = check_springs(chain, [spring])
    radius = _checks.positive("radius", radius, allow_zero=True, unit="m")
    X = chain.check_directions(X)
    A, B = attachment_points(chain, spring, X)
    try:
        return cable_geometry(A, B, X[:, spring.i - 1], radius)  # the cable arrives along link i's direction
    except GeometryError as err:
        raise GeometryError(f"{spring.label}: {err}") from None


def cable_energy(chain: Chain, spring: Spring, X, radius: float) -> np.ndarray:
    """The spring's energy k (path - l0)^2 / 2 (J), (N,), its force acting along the cable's path."""
    path, _ = cable_path(chain, spring, X, radius)
    return 0.5 * spring.k * (path - spring.effective_free_length) ** 2


def holding_torques_with_pulleys(chain: Chain, springs, radii, X) -> np.ndarray:
    """Joint torques (N m) that hold each pose, (N, n-1, 3) as in
    :func:`springlab.energy.geometry.holding_torques`, with spring s led over a pulley of
    radius ``radii[s]`` (m) at its end A; None (or a missing entry) keeps a spring a
    straight line between A and B.
    """
    springs = check_springs(chain, springs)
    X = chain.check_directions(X)
    if isinstance(radii, str) or not hasattr(radii, "__len__") or len(radii) != len(springs):
        raise GeometryError(f"radii must give one pulley radius (m) or None per spring ({len(springs)}), got {radii!r}")
    straight = [s for s, rho in zip(springs, radii, strict=True) if rho is None]
    out = holding_torques(chain, straight, X)
    joints = chain.joint_positions(X)  # joints[:, t - 1] = J_t
    for s, rho in zip(springs, radii, strict=True):
        if rho is None:
            continue
        path, T = cable_path(chain, s, X, rho)
        _, B = attachment_points(chain, s, X)
        tension = s.k * (path - s.effective_free_length)
        line = B - T
        pull = (tension / np.linalg.norm(line, axis=1))[:, None] * line  # minus the force on B
        for j in range(s.i + 1, s.j + 1):  # joint j, at J_{j-1}, between links j-1 and j
            out[:, j - 2] += np.cross(B - joints[:, j - 2], pull)
    return out
