"""Route 1: the quadratic form of gravity and spring energy (Juang, Jhuang, Chen 2023).

With the link unit vectors stacked as X = [x_1, ..., x_n] (000 Eq. 15), the gravity
energy is U_g = X^T G X (000 Eq. 14) with G nonzero in its first row only (000 Eq. 18)::

    G_{1,j} = g (m_j d_j + r_j sum_{t>j} m_t)                         # 000 Eq. (18)

and a zero-free-length spring S(i,j) attached on the joint lines (P1) has
U_S = X^T K_S X (000 Eq. 24), nonzero in the block bounded by row i, column j and
the diagonal (000 Eq. 26)::

    K_{i,j} = -k a b                       (000 Eq. 23a)
    K_{i,v} = -r_v k a        i < v < j    (000 Eq. 23b)
    K_{u,v} =  r_u r_v k      i < u < v < j (000 Eq. 23c)
    K_{u,j} =  r_u k b        i < u < j    (000 Eq. 23d)

The constant C^S of 000 Eq. (22) is spread over the diagonal (k a^2/2 at (i,i),
k r_t^2/2 at (t,t), k b^2/2 at (j,j)); since x_u . x_u = 1 this makes X^T K_S X
the spring's whole energy, not just its pose-dependent part.

The arm is balanced when the strictly upper triangle of M = G + sum K_S is zero
(000 Eqs. 39a-b): then U = sum_u M_uu, the same at every pose.

One set of entry formulas serves both the numeric (numpy, floats) and the
symbolic (sympy) forms; :func:`expand_gravity_energy` and
:func:`expand_spring_energy` derive the same energies from the geometry, with
no entry formula, so that the formulas can be checked against them.

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from springlab import _checks
from springlab.errors import SpringlabError
from springlab.model.chain import Chain, check_springs
from springlab.model.springs import Spring

DEFAULT_CHUNK = 16384


# --- entry formulas (shared by numeric and symbolic) ---------------------------
def gravity_entries(r, d, m, g) -> dict[tuple[int, int], object]:
    """Nonzero entries of G (000 Eq. 18), keyed (1, j); r, d, m list links 2..n."""
    n = len(r) + 1
    out = {}
    for j in range(2, n + 1):
        distal_mass = sum(m[t - 2] for t in range(j + 1, n + 1))
        out[(1, j)] = g * (m[j - 2] * d[j - 2] + r[j - 2] * distal_mass)  # 000 Eq. (18)
    return out


def spring_entries(i, j, a, b, k, r) -> dict[tuple[int, int], object]:
    """Entries of K_S(i,j) (000 Eqs. 22, 23a-d), keyed (u, v) with u <= v.

    ``r`` lists r_2..r_n; the diagonal carries 000 Eq. (22)'s constant.
    """
    rr = {t: r[t - 2] for t in range(2, len(r) + 2)}
    out = {(i, i): k * a**2 / 2, (j, j): k * b**2 / 2, (i, j): -k * a * b}  # 000 Eq. (22), (23a)
    for t in range(i + 1, j):
        out[(t, t)] = k * rr[t] ** 2 / 2  # 000 Eq. (22)
        out[(i, t)] = -rr[t] * k * a  # 000 Eq. (23b)
        out[(t, j)] = rr[t] * k * b  # 000 Eq. (23d)
        for v in range(t + 1, j):
            out[(t, v)] = rr[t] * rr[v] * k  # 000 Eq. (23c)
    return out


# --- numeric -------------------------------------------------------------------
def gravity_matrix(chain: Chain) -> np.ndarray:
    """G (000 Eqs. 16, 18) as an (n, n) array in J."""
    check_springs(chain, ())
    G = np.zeros((chain.n, chain.n))
    for (u, v), val in gravity_entries(chain.r, chain.d, chain.m, chain.g).items():
        G[u - 1, v - 1] = val
    return G


def spring_matrix(chain: Chain, spring: Spring) -> np.ndarray:
    """K_S(i,j) (000 Eqs. 22-26) as an (n, n) upper-triangular array in J."""
    (spring,) = check_springs(chain, [spring])
    if not spring.ideal:
        raise SpringlabError(
            f"{spring.label} has free_length = {spring.free_length} m and initial_tension = "
            f"{spring.initial_tension} N; the quadratic form holds only for zero-free-length springs "
            "(use springlab.energy.geometry for others)"
        )
    K = np.zeros((chain.n, chain.n))
    for (u, v), val in spring_entries(spring.i, spring.j, spring.a, spring.b, spring.k, chain.r).items():
        K[u - 1, v - 1] += val
    return K


def energy_matrix(chain: Chain, springs=()) -> np.ndarray:
    """M = G + sum K_S (000 Eq. 37), upper triangular, in J: U(X) = sum_{u<=v} M_uv x_u . x_v."""
    M = gravity_matrix(chain)
    for s in check_springs(chain, springs):
        M += spring_matrix(chain, s)
    return M


def balance_residual(chain: Chain, springs) -> np.ndarray:
    """The strictly upper triangle of M = G + sum K_S (J): the left-hand sides of
    000 Eqs. (39a-b). All zero means balanced."""
    return np.triu(energy_matrix(chain, springs), 1)


def energy_variation_bound(chain: Chain, springs) -> float:
    """An upper bound (J) on max U - min U over all poses: 2 sum |residual entries|.

    Each x_u . x_v ranges over [-1, 1], so no pose pair can differ by more.
    """
    return float(2.0 * np.abs(balance_residual(chain, springs)).sum())


def quadratic_energy_component_major(M: np.ndarray, XT: np.ndarray, *, out=None,
                                     chunk: int = DEFAULT_CHUNK) -> np.ndarray:
    """Evaluate U = sum_{u<=v} M_uv x_u . x_v on poses stored component-major.

    The fast kernel of route 1: ``XT`` has shape (n, 3, N) (link, coordinate,
    pose), so every slice it multiplies is contiguous. The ground link's x_1 = UP
    makes its row of M linear in x_j[0]; the diagonal is a constant.

    :param M: (n, n) upper-triangular energy matrix (J), e.g. :func:`energy_matrix`
    :param XT: (n, 3, N) link unit vectors; XT[0] must be UP
    :returns: ndarray(N,) energies in J
    """
    n, _, n_pose = XT.shape
    if out is None:
        out = np.empty(n_pose)
    lin = [(v, M[0, v]) for v in range(1, n) if M[0, v] != 0.0]  # M_1v x_1 . x_v, with x_1 = UP = e_0
    pairs = [(u, v, M[u, v]) for u in range(1, n) for v in range(u + 1, n) if M[u, v] != 0.0]  # M_uv x_u . x_v
    const = float(np.trace(M))
    if n_pose < COMPILED_FROM:
        return _component_major_numpy(const, lin, pairs, XT, out, chunk)
    from springlab.energy.quadratic_kernel import component_major_energy

    XT = XT if XT.dtype == np.float64 and XT.flags.c_contiguous else np.ascontiguousarray(XT, dtype=float)
    component_major_energy(const, np.array([v for v, _ in lin], dtype=np.int64),
                           np.array([c for _, c in lin], dtype=float),
                           np.array([u for u, _, _ in pairs], dtype=np.int64), np.array([v for _, v, _ in pairs], dtype=np.int64),
                           np.array([c for _, _, c in pairs], dtype=float), XT, out)
    return out


COMPILED_FROM = 1 << 16
"""Poses from which route 1 runs its compiled kernel (:mod:`springlab.energy.quadratic_kernel`,
twice the speed of numpy); below, the numpy expression, which needs no compilation (about 3 s
the first time in a process without numba's cache). Both do the same arithmetic in the same
order: the energies are equal to the last bit (tested)."""


def _component_major_numpy(const, lin, pairs, XT, out, chunk):
    n_pose = XT.shape[2]
    acc = np.empty(chunk)
    tmp = np.empty(chunk)
    dot = np.empty(chunk)
    for start in range(0, n_pose, chunk):
        stop = min(start + chunk, n_pose)
        m = stop - start
        a, t, d = acc[:m], tmp[:m], dot[:m]
        a.fill(const)
        x = XT[:, :, start:stop]
        for v, c in lin:  # M_1v x_1 . x_v, with x_1 = UP = e_0
            np.multiply(x[v, 0], c, out=t)
            a += t
        for u, v, c in pairs:  # M_uv x_u . x_v
            np.multiply(x[u, 0], x[v, 0], out=d)
            np.multiply(x[u, 1], x[v, 1], out=t)
            d += t
            np.multiply(x[u, 2], x[v, 2], out=t)
            d += t
            d *= c
            a += d
        out[start:stop] = a
    return out


def quadratic_energy(chain: Chain, springs, X, *, chunk: int = DEFAULT_CHUNK) -> np.ndarray:
    """Total potential energy (J) by the quadratic form, ndarray(N,).

    U = X^T (G + sum K_S) X at each pose of ``X`` (N, n, 3). Exact for any
    springs on the joint lines, balanced or not.
    """
    M = energy_matrix(chain, springs)
    X = chain.as_poses(X)
    out = np.empty(X.shape[0])
    for start, stop, xt in chain.component_major_chunks(X, chunk):
        quadratic_energy_component_major(M, xt, out=out[start:stop], chunk=chunk)
    return out


def energies(chain: Chain, springs, X, *, chunk: int = DEFAULT_CHUNK) -> dict[str, np.ndarray]:
    """Gravity, spring and total energy (J) at each pose by the quadratic form (route 1):
    {'gravity': X^T G X (000 Eq. 14), 'springs': sum_S X^T K_S X (000 Eq. 24), 'total':
    X^T (G + sum K_S) X}, each ndarray(N,). The same name and shape as route 2's
    :func:`springlab.energy.geometry.energies`."""
    gravity = quadratic_energy(chain, (), X, chunk=chunk)
    total = quadratic_energy(chain, springs, X, chunk=chunk)
    return {"gravity": gravity, "springs": total - gravity, "total": total}


def quadratic_gravity_energy(chain: Chain, X) -> np.ndarray:
    """U_g = X^T G X (000 Eq. 14) in J, ndarray(N,)."""
    return quadratic_energy(chain, (), X)


# --- symbolic ------------------------------------------------------------------
def chain_symbols(n: int):
    """sympy symbols (r, d, m, g) for an n-link chain; r, d, m list links 2..n."""
    n = _checks.links(n, "n")
    r = sp.symbols(f"r_2:{n + 1}", positive=True)
    d = sp.symbols(f"d_2:{n + 1}", nonnegative=True)
    m = sp.symbols(f"m_2:{n + 1}", positive=True)
    g = sp.Symbol("g", positive=True)
    return r, d, m, g


def spring_symbols(i: int, j: int):
    """sympy symbols (a, b, k) of a spring S(i,j), named as in the paper."""
    a = sp.Symbol(f"a_S({i},{j})", real=True)
    b = sp.Symbol(f"b_S({i},{j})", real=True)
    k = sp.Symbol(f"k_S({i},{j})", positive=True)
    return a, b, k


def symbolic_matrix(n: int, entries: dict) -> sp.Matrix:
    """An (n, n) sympy Matrix from {(u, v): expr} with 1-based keys."""
    M = sp.zeros(n, n)
    for (u, v), val in entries.items():
        M[u - 1, v - 1] += val
    return M


def dot_symbol(u, v) -> sp.Symbol:
    """The symbol for the dot product of two unit vectors, e.g. x_1 . x_3.

    ``u`` and ``v`` are link numbers or the strings 'a', 'b' (the paper's
    \\hat a_S and \\hat b_S before P1 identifies them with link vectors).
    """
    for w in (u, v):
        if not (isinstance(w, str) and w) and (isinstance(w, bool) or not isinstance(w, int) or w < 0):
            raise SpringlabError(f"u and v must be link numbers (integers >= 0) or names such as 'a', got {w!r}")
    def name(w):
        return {"a": r"\hat{a}", "b": r"\hat{b}"}.get(w, rf"\hat{{x}}_{{{w}}}")

    key = sorted([u, v], key=lambda w: (isinstance(w, str), str(w) if isinstance(w, str) else w))
    return sp.Symbol(rf"{name(key[0])} \cdot {name(key[1])}")


def expand_vectors_dot(vec1: dict, vec2: dict):
    """Bilinear dot product of two vectors written as {unit vector: coefficient},
    with x_u . x_u = 1 and the other products as :func:`dot_symbol` symbols."""
    total = 0
    for u, cu in vec1.items():
        for v, cv in vec2.items():
            total += cu * cv * (1 if u == v else dot_symbol(u, v))
    return sp.expand(total)


def quadratic_form(M: sp.Matrix, names=None):
    """sum_{u<=v} M_uv (y_u . y_v) with unit vectors y named by ``names`` (default 1..n)."""
    n = M.shape[0]
    names = names or list(range(1, n + 1))
    total = 0
    for u in range(n):
        for v in range(u, n):
            if M[u, v] != 0:
                total += M[u, v] * (1 if u == v else dot_symbol(names[u], names[v]))
    return sp.expand(total)


def expand_gravity_energy(n: int):
    """U_g of an n-link chain derived from the geometry (000 Eqs. 8-9), expanded.

    h_j = (d_j x_j + sum_{w=2}^{j-1} r_w x_w) . x_1, U_g = sum_j m_j g h_j.
    Uses no entry of G; compare with ``quadratic_form(symbolic_matrix(n, gravity_entries(...)))``.
    """
    n = _checks.links(n, "n")
    r, d, m, g = chain_symbols(n)
    total = 0
    for j in range(2, n + 1):
        com = {j: d[j - 2]}
        for w in range(2, j):
            com[w] = com.get(w, 0) + r[w - 2]
        total += m[j - 2] * g * expand_vectors_dot(com, {1: 1})  # 000 Eq. (8)-(9)
    return sp.expand(total)


def planar_symbols(n: int):
    """sympy symbols (theta, r_1) of 000 Section 2.1's planar arm: theta = (theta_2, ..., theta_n), each link's
    angle from the one before (rad; link 2's from the horizontal), and the ground link's length r_1, which
    the planar form of 000 Eqs. (4)-(7) multiplies in and divides out."""
    n = _checks.links(n, "n")
    return sp.symbols(f"theta_2:{n + 1}", real=True), sp.Symbol("r_1", positive=True)


def planar_gravity_energy(n: int):
    """U_g of an n-link planar arm from its links' heights (000 Eqs. 1-2), expanded: the centre of mass of
    link j stands h_j = sum_{w=2}^{j-1} r_w sin(phi_w) + d_j sin(phi_j) high, phi_w = theta_2 + ... + theta_w.
    Uses no entry of G^p; compare with :func:`planar_gravity_matrix`'s form."""
    r, d, m, g = chain_symbols(n)
    theta, _ = planar_symbols(n)
    phi = [sum(theta[: w - 1]) for w in range(2, n + 1)]  # phi[w - 2]: link w's angle from the horizontal
    total = 0
    for j in range(2, n + 1):
        h = sum(r[w - 2] * sp.sin(phi[w - 2]) for w in range(2, j)) + d[j - 2] * sp.sin(phi[j - 2])  # 000 Eq. (2a)
        total += m[j - 2] * g * h  # 000 Eq. (1)
    return sp.expand(total)


def planar_gravity_matrix(n: int) -> sp.Matrix:
    """G^p of an n-link planar arm (000 Eq. 6), nonzero in its first row only:
    G^p_{1,j} = (m_j g d_j / (r_1 r_j) + g sum_{t>j} m_t / r_1) sin(theta_2 + ... + theta_j) (000 Eqs. 7a-7c),
    so that U_g = [r_1 .. r_n] G^p [r_1 .. r_n]^T (000 Eq. 5)."""
    r, d, m, g = chain_symbols(n)
    theta, r1 = planar_symbols(n)
    G = sp.zeros(n, n)
    for j in range(2, n + 1):
        beyond = sum(m[t - 2] for t in range(j + 1, n + 1))
        G[0, j - 1] = (m[j - 2] * g * d[j - 2] / (r1 * r[j - 2]) + beyond * g / r1) * sp.sin(sum(theta[: j - 1]))  # 000 Eq. (7a)
    return G


def planar_form(n: int):
    """[r_1 .. r_n] G^p [r_1 .. r_n]^T (000 Eq. 5) with :func:`planar_gravity_matrix`, expanded."""
    r, _, _, _ = chain_symbols(n)
    _, r1 = planar_symbols(n)
    lengths = sp.Matrix([r1, *r])
    return sp.expand((lengths.T * planar_gravity_matrix(n) * lengths)[0, 0])


def expand_spring_energy(i: int, j: int, n: int, *, on_joint_lines: bool = True):
    """U_S(i,j) = k l^2 / 2 derived from the spring vector of 000 Eq. (19), expanded.

    l = -a a_hat + b b_hat + sum_{t=i+1}^{j-1} r_t x_t. With ``on_joint_lines``
    (principle P1) a_hat = x_i and b_hat = x_j; without it a_hat, b_hat stay
    separate unit vectors, which is 000 Eq. (21) as printed.
    """
    r, _, _, _ = chain_symbols(n)
    a, b, k = spring_symbols(i, j)
    a_hat, b_hat = (i, j) if on_joint_lines else ("a", "b")
    vec = {a_hat: -a}
    vec[b_hat] = vec.get(b_hat, 0) + b
    for t in range(i + 1, j):
        vec[t] = vec.get(t, 0) + r[t - 2]
    return sp.expand(k * expand_vectors_dot(vec, vec) / 2)  # 000 Eq. (20)


def symbolic_gravity_matrix(n: int) -> sp.Matrix:
    """G (000 Eq. 16-18) with symbols r_j, d_j, m_j, g."""
    n = _checks.links(n, "n")
    r, d, m, g = chain_symbols(n)
    return symbolic_matrix(n, gravity_entries(r, d, m, g))


def symbolic_spring_matrix(i: int, j: int, n: int) -> sp.Matrix:
    """K_S(i,j) (000 Eqs. 22-26) with symbols a_S(i,j), b_S(i,j), k_S(i,j), r_t."""
    r, _, _, _ = chain_symbols(n)
    a, b, k = spring_symbols(i, j)
    return symbolic_matrix(n, spring_entries(i, j, a, b, k, r))


def balancing_equations(n: int, spring_pairs) -> dict[tuple[int, int], object]:
    """000 Eqs. (39a-b) for springs on the pairs ``spring_pairs`` [(i, j), ...]:
    {(u, v): left-hand side} for every u < v the gravity or a spring touches."""
    M = symbolic_gravity_matrix(n)
    for i, j in spring_pairs:
        M += symbolic_spring_matrix(i, j, n)
    return {(u + 1, v + 1): M[u, v] for u in range(n) for v in range(u + 1, n) if M[u, v] != 0}
