"""Benchmark: total potential energy of the 000 four-link example at random poses.

Prints poses per second on one core for route 1 (the numeric quadratic form; target
1.5e8 poses/s), route 2 (direct geometry) and, side by side in the same run, Pinocchio's
``computePotentialEnergy`` in a loop over the same poses (gravity only); then route 2's
holding torques beside Pinocchio's ``computeGeneralizedGravity`` (target: 20 times faster).

    make bench                      # 1,000,000 poses
    python benchmarks/bench_energy.py --poses 200000

Pose generation is not timed. BLAS is pinned to one thread (the Makefile sets
OMP_NUM_THREADS=1 and friends; threadpoolctl, where installed, confirms it).
"""

from __future__ import annotations

import argparse
import os
import platform
import time

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402

from springlab.design.solve import SpringSpec, solve_design  # noqa: E402
from springlab.energy import geometry, quadratic  # noqa: E402
from springlab.model.rotations import directions_from_relative  # noqa: E402
from springlab.papers import juang2023 as paper  # noqa: E402


def best_of(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def random_quaternions(rng, shape):
    q = rng.standard_normal(shape + (4,))
    return q / np.linalg.norm(q, axis=-1, keepdims=True)


def quaternion_matrices(q):
    """Rotation matrices of unit quaternions (x, y, z, w), Pinocchio's order."""
    x, y, z, w = np.moveaxis(q, -1, 0)
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1),
    ], -2)


def directions_from_quaternions(q):
    """Link directions x_1..x_n (N, n, 3) of a chain whose joint j rotates by q[:, j]."""
    return directions_from_relative(quaternion_matrices(q))


def pinocchio_model(arm):
    import pinocchio as pin

    model = pin.Model()
    model.gravity.linear = np.array([-arm.g, 0.0, 0.0])  # gravity along -x_1
    parent, placement = 0, pin.SE3.Identity()
    for idx, (r, d, m) in enumerate(zip(arm.r, arm.d, arm.m, strict=True)):
        jid = model.addJoint(parent, pin.JointModelSpherical(), placement, f"joint{idx + 1}")
        model.appendBodyToJoint(jid, pin.Inertia(m, np.array([d, 0.0, 0.0]), np.diag([1e-3, 1e-2, 1e-2])),
                                pin.SE3.Identity())
        parent, placement = jid, pin.SE3(np.eye(3), np.array([r, 0.0, 0.0]))
    return pin, model, model.createData()


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--poses", type=int, default=1_000_000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)

    arm = paper.example_arm()
    specs = [SpringSpec(s.i, s.j, s.pattern, **paper.FREE_CHOICES[(s.i, s.j)])
             for s in paper.EXAMPLE_CONFIGURATION]
    springs = solve_design(arm, specs).springs
    rng = np.random.default_rng(args.seed)
    N = args.poses
    quats = random_quaternions(rng, (N, arm.n - 1))
    X = directions_from_quaternions(quats)                 # (N, n, 3), for route 2
    XT = np.ascontiguousarray(X.transpose(1, 2, 0))        # (n, 3, N), route 1's fast layout
    M = quadratic.energy_matrix(arm, springs)

    try:
        from threadpoolctl import threadpool_info
        blas = ", ".join(f"{i['internal_api']} {i['num_threads']} thread(s)" for i in threadpool_info())
    except ImportError:
        blas = f"OPENBLAS_NUM_THREADS={os.environ.get('OPENBLAS_NUM_THREADS')}"
    print(f"springlab energy benchmark: 000 four-link example, {N:,} random poses, best of {args.repeat}")
    print(f"python {platform.python_version()}, numpy {np.__version__}, {platform.machine()}, BLAS: {blas}\n")

    rows = []
    t = best_of(lambda: quadratic.quadratic_energy_component_major(M, XT), args.repeat)
    rows.append(("route 1, quadratic form, component-major poses (n, 3, N)", t))
    t = best_of(lambda: quadratic.quadratic_energy(arm, springs, X), args.repeat)
    rows.append(("route 1, quadratic form, poses (N, n, 3)", t))
    t = best_of(lambda: geometry.total_energy(arm, springs, X), args.repeat)
    rows.append(("route 2, direct geometry, gravity + springs", t))
    t = best_of(lambda: geometry.gravity_energy(arm, X), args.repeat)
    rows.append(("route 2, direct geometry, gravity only", t))

    # agreement, so that the speeds are of the same quantity
    u1 = quadratic.quadratic_energy_component_major(M, XT)
    u2 = geometry.total_energy(arm, springs, X)
    print(f"route 1 vs route 2: max |difference| {np.abs(u1 - u2).max():.2e} J, "
          f"total energy spread {np.ptp(u2):.2e} J over {N:,} poses")

    pin_rate = None
    try:
        pin, model, data = pinocchio_model(arm)
    except ImportError:
        print("Pinocchio (pip package 'pin', the 'bench' extra) is not installed: no reference timing")
    else:
        Q = np.ascontiguousarray(quats.reshape(N, -1))
        check = min(N, 2000)
        ours = geometry.gravity_energy(arm, X[:check])
        theirs = np.array([pin.computePotentialEnergy(model, data, Q[i]) for i in range(check)])
        print(f"Pinocchio vs route 2 gravity energy: max |difference| {np.abs(ours - theirs).max():.2e} J "
              f"over {check:,} poses")

        def pin_loop():
            f = pin.computePotentialEnergy
            for q in Q:
                f(model, data, q)

        t = best_of(pin_loop, 1)
        rows.append(("Pinocchio computePotentialEnergy (gravity only), Python loop", t))
        pin_rate = N / t
        torque_rows = torques_beside_pinocchio(arm, X, quats, pin, model, data, args.repeat)

    print()
    width = max(len(name) for name, _ in rows)
    for name, t in rows:
        rate = N / t
        ratio = f"   {rate / pin_rate:6.1f} x Pinocchio" if pin_rate else ""
        print(f"{name:<{width}}  {rate / 1e6:8.2f} M poses/s  ({t * 1e3:8.1f} ms){ratio}")
    if pin_rate:
        (ours_t, pin_t) = torque_rows
        print(f"\nholding torques, gravity only, {N:,} poses (target: 20 x Pinocchio):")
        print(f"  route 2, geometry.holding_torques (compiled, out= reused)  {N / ours_t / 1e6:8.2f} M poses/s   "
              f"{pin_t / ours_t:6.1f} x Pinocchio")
        print(f"  Pinocchio computeGeneralizedGravity, Python loop           {N / pin_t / 1e6:8.2f} M poses/s")


def torques_beside_pinocchio(arm, X, quats, pin, model, data, repeat: int) -> tuple[float, float]:
    """Route 2's holding torques against Pinocchio's generalised gravity (the torques that hold a
    pose, each spherical joint's in its own frame): agreement on 2,000 poses, then the times."""
    N = X.shape[0]
    Q = np.ascontiguousarray(quats.reshape(N, -1))
    check = min(N, 2000)
    ours = geometry.holding_torques(arm, (), X[:check])  # (poses, n - 1, 3), world frame
    worst = 0.0
    for p in range(check):
        theirs = pin.computeGeneralizedGravity(model, data, Q[p])
        pin.forwardKinematics(model, data, Q[p])
        local = np.concatenate([data.oMi[j].rotation.T @ ours[p, j - 1] for j in range(1, model.njoints)])
        worst = max(worst, float(np.abs(local - theirs).max()))
    print(f"Pinocchio vs route 2 holding torques (gravity): max |difference| {worst:.2e} N m over {check:,} poses")
    out = np.empty((N, arm.n - 1, 3))  # reused, as Pinocchio reuses its data.g
    ours_t = best_of(lambda: geometry.holding_torques(arm, (), X, out=out), repeat)

    def pin_loop():
        f = pin.computeGeneralizedGravity
        for q in Q:
            f(model, data, q)

    return ours_t, best_of(pin_loop, 1)


if __name__ == "__main__":
    main()
