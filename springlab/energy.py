"""Route 2: potential energies from direct geometry.

Every body and spring end is placed in space for each pose, then the energies
are summed as ``m g h`` (h = height of the COM above the base joint, along
x_1 = UP) and ``k (l - l0)**2 / 2`` (l = distance between the spring's ends).
Nothing here uses the quadratic form of :mod:`springlab.quadratic`; the two
routes agreeing is a check.

All energies in J; poses ``X`` of shape (N, n, 3) as in :mod:`springlab.chain`.
Large batches are processed in chunks, so memory stays bounded.
"""

from __future__ import annotations

import numpy as np

from springlab.chain import UP, Chain
from springlab.springs import Spring, check_springs

DEFAULT_CHUNK = 8192


def _chunks(n_pose: int, chunk: int):
    for start in range(0, n_pose, chunk):
        yield start, min(start + chunk, n_pose)


def _joints(chain: Chain, X: np.ndarray) -> np.ndarray:
    """Joint positions 1..n for a chunk (no validation): J_1 = 0, J_j = J_{j-1} + r_j x_j."""
    joints = np.zeros(X.shape)
    np.cumsum(np.asarray(chain.r)[None, :, None] * X[:, 1:], axis=1, out=joints[:, 1:])
    return joints


def attachment_points(chain: Chain, spring: Spring, X) -> tuple[np.ndarray, np.ndarray]:
    """World positions (m) of a spring's ends A (on link i) and B (on link j).

    A = J_i + a x_i and B = J_{j-1} + b x_j, with J_1 the base joint
    (see :mod:`springlab.springs`). Returns two arrays of shape (N, 3).
    """
    X = chain.check_directions(X)
    (spring,) = check_springs(chain, [spring])
    joints = _joints(chain, X)
    A = joints[:, spring.i - 1] + spring.a * X[:, spring.i - 1]
    B = joints[:, spring.j - 2] + spring.b * X[:, spring.j - 1]
    return A, B


def _gravity_chunk(chain: Chain, X: np.ndarray, joints: np.ndarray) -> np.ndarray:
    com = joints[:, :-1] + np.asarray(chain.d)[None, :, None] * X[:, 1:]
    heights = com @ UP
    return chain.g * (heights @ np.asarray(chain.m))


def _springs_chunk(springs, X: np.ndarray, joints: np.ndarray) -> np.ndarray:
    out = np.zeros(X.shape[0])
    for s in springs:
        A = joints[:, s.i - 1] + s.a * X[:, s.i - 1]
        B = joints[:, s.j - 2] + s.b * X[:, s.j - 1]
        diff = B - A
        length_sq = np.einsum("nc,nc->n", diff, diff)
        if s.free_length:
            out += 0.5 * s.k * (np.sqrt(length_sq) - s.free_length) ** 2
        else:
            out += 0.5 * s.k * length_sq
    return out


def _evaluate(chain, springs, X, chunk, gravity: bool, elastic: bool) -> np.ndarray:
    X = chain.check_directions(X)
    springs = check_springs(chain, springs)
    out = np.zeros(X.shape[0])
    for start, stop in _chunks(X.shape[0], chunk):
        x = X[start:stop]
        joints = _joints(chain, x)
        if gravity:
            out[start:stop] += _gravity_chunk(chain, x, joints)
        if elastic:
            out[start:stop] += _springs_chunk(springs, x, joints)
    return out


def gravity_energy(chain: Chain, X, *, chunk: int = DEFAULT_CHUNK) -> np.ndarray:
    """Gravity energy sum_j m_j g h_j (J) at each pose, ndarray(N,).

    The zero is the horizontal plane through the base joint (000 Section 2.2).
    """
    return _evaluate(chain, (), X, chunk, gravity=True, elastic=False)


def spring_energy(chain: Chain, springs, X, *, chunk: int = DEFAULT_CHUNK) -> np.ndarray:
    """Elastic energy sum_S k (l - l0)^2 / 2 (J) at each pose, ndarray(N,)."""
    return _evaluate(chain, springs, X, chunk, gravity=False, elastic=True)


def total_energy(chain: Chain, springs, X, *, chunk: int = DEFAULT_CHUNK) -> np.ndarray:
    """Gravity plus elastic energy (J) at each pose, ndarray(N,)."""
    return _evaluate(chain, springs, X, chunk, gravity=True, elastic=True)


def energy_breakdown(chain: Chain, springs, X, *, chunk: int = DEFAULT_CHUNK) -> dict[str, np.ndarray]:
    """Gravity, spring and total energy (J) at each pose: {'gravity', 'springs', 'total'}."""
    gravity = gravity_energy(chain, X, chunk=chunk)
    elastic = spring_energy(chain, springs, X, chunk=chunk)
    return {"gravity": gravity, "springs": elastic, "total": gravity + elastic}
