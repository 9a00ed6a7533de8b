"""An independent re-check of a design's peak holding torques (:class:`Audit`): random poses of the
workspace on their own seed, and from the worst of them a compass search
(:func:`springlab.design.search.compass_search`) that climbs to the nearby worst pose, per joint and
per case (gravity alone, ideal, realised springs); the cables whose end crosses its lead's line, and
the poses where a spring has no line of action, are named.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from springlab.design.realise import CROSSING, defined_torques, lead_angles, towards_leads
from springlab.design.search import compass_searches, sig
from springlab.design.structure import NEGLIGIBLE
from springlab.model.revolute import RevoluteChain

AUDIT_SAMPLES = 20_000
"""Random poses of the workspace, drawn from their own seed, on which every design's peaks are re-checked
(:class:`Audit`): ten times the design's own check, independent of it."""


AUDIT_STARTS = 3
"""From how many of the independent sample's worst poses, per joint and case, the audit's compass search
starts (the worst it reaches joins the check)."""


@dataclass(frozen=True)
class Audit:
    """An independent re-check of a design's peak holding torques: :data:`AUDIT_SAMPLES` random poses of
    the workspace (their own seed), and from the worst of them, per joint and per case (gravity alone,
    ideal, realised springs), a compass search (``_climbs``) that climbs to the nearby worst pose
    within the workspace. The worst poses found join the design's check poses, so every peak and
    share the design reports holds on them too.

    :ivar samples: how many random poses were drawn
    :ivar seed: their seed
    :ivar worst: the worst poses found, refined, (M, n) rad
    :ivar raised: per (case, joint name), the peak (N m) over the design's own check poses and over the
        audit's poses, where the audit found more (above the tables' 3 significant digits)
    :ivar undefined: per case whose springs have no line of action at some of the random poses (a cable's
        end within its pulley's radius of the pulley, a spring's ends coinciding), (case, how many, the
        first such pose (rad), the reason)
    :ivar crossings: per realised cable spring whose end B crosses its lead's line in the workspace
        (within :data:`~springlab.design.realise.CROSSING`), (its index, the angle (rad), the pose (rad))
    :ivar workspace: the drawn poses in collision were left out (an arm with collision geometry)
    """

    samples: int
    seed: int
    worst: np.ndarray
    raised: tuple
    undefined: tuple = ()
    crossings: tuple = ()
    workspace: bool = False

    @classmethod
    def of(cls, model: RevoluteChain, ranges, cases: dict, check, seed: int, samples: int = AUDIT_SAMPLES,
           sampler=None) -> Audit:
        """The audit of the springs ``cases`` (name -> springs; gravity alone is added) over the workspace
        ``ranges`` (n, 2) rad, beside the design's own ``check`` poses. With a ``sampler``
        (:class:`~springlab.design.collision.Sampler`) the drawn poses in collision are left out (each asked
        only when it matters: a start, an undefined pose, the nearest approach to a lead line, in order of
        how bad it is), and each climb moves through free poses only."""
        rng = np.random.default_rng([seed, samples])
        q = rng.uniform(ranges[:, 0], ranges[:, 1], (samples, model.n))
        known, free_at = np.zeros(samples, dtype=bool), np.ones(samples, dtype=bool)

        def first_free(order, count: int) -> np.ndarray:
            """The first ``count`` indices of ``order`` whose poses are in the workspace."""
            if sampler is None:
                return np.asarray(order[:count], dtype=int)
            out = []
            for at in range(0, len(order), 64):
                chunk = np.asarray(order[at:at + 64], dtype=int)
                todo = chunk[~known[chunk]]
                if len(todo):
                    free_at[todo], known[todo] = sampler.free(q[todo]), True
                out += chunk[free_at[chunk]].tolist()
                if len(out) >= count:
                    break
            return np.asarray(out[:count], dtype=int)

        lo, hi = ranges[:, 0], ranges[:, 1]
        worst, raised, undefined, largest = [], [], [], None
        for case, springs in ({"gravity alone": ()} | dict(cases)).items():
            tau, why = defined_torques(model, springs, q)
            bad = np.isnan(tau[:, 0])
            bad_free = first_free(np.flatnonzero(bad), samples) if np.any(bad) else np.zeros(0, dtype=int)
            if len(bad_free):
                undefined.append((case, len(bad_free), q[bad_free[0]].tolist(), why))
            tau = np.abs(np.where(bad[:, None], 0.0, tau))
            mine = np.abs(defined_torques(model, springs, check)[0])
            own = np.max(np.where(np.isnan(mine), 0.0, mine), axis=0)
            if largest is None:  # gravity's, the first case, over the workspace's poses
                largest = max(float(tau[first_free(np.argsort([-sig(v) for v in tau[:, j]], kind="stable"), 1),
                                        j].max(initial=0.0)) for j in range(model.n))
            loaded = [j for j in range(model.n) if np.max(tau[:, j]) > 0]
            jobs = [(j, start) for j in loaded
                    for start in q[first_free(np.argsort([-sig(v) for v in tau[:, j]], kind="stable"), AUDIT_STARTS)]]
            found = _climbs(model, springs, jobs, lo, hi, None if sampler is None else sampler.free)
            for j in loaded:
                climbed = []
                for (joint, _), (pose, value, broken) in zip(jobs, found, strict=True):
                    if joint != j:
                        continue
                    climbed.append((sig(value), -len(climbed), pose, value))
                    if broken is not None and not any(u[0] == case for u in undefined):
                        undefined.append((case, 0, broken[0].tolist(), broken[1]))
                _, _, pose, value = max(climbed, key=lambda c: c[:2])
                worst.append(pose)
                if sig(value, 3) > sig(own[j], 3) and value > NEGLIGIBLE * largest:
                    raised.append((case, model.joints[j], float(own[j]), float(value)))
        crossings = []
        led = [(m, s) for m, s in enumerate(dict(cases).get("realised", ())) if s.pulley_radius > 0]
        if led:  # each cable's end climbs towards its lead's line, the searches in lockstep
            starts = []
            for _, spring in led:
                angle = lead_angles(model, spring, q)
                if sampler is None:
                    starts.append(q[int(np.argmin(angle))])
                else:  # from the nearest free pose, through free poses
                    starts.append(q[first_free(np.argsort([sig(v) for v in angle], kind="stable"), 1)[0]])
            poses, values = compass_searches(towards_leads(model, [s for _, s in led]), np.array(starts), lo, hi,
                                             enough=0.0, allowed=None if sampler is None else sampler.free)
            for (m, _), pose, value in zip(led, poses, values, strict=True):
                if -value < CROSSING / 3:
                    crossings.append((m, float(-value), pose.tolist()))
        unique = np.unique(np.array(worst).reshape(-1, model.n), axis=0)
        keep = np.ones(len(unique), dtype=bool)  # a pose one case climbed to may leave another's spring undefined
        for case, springs in dict(cases).items():
            tau, why = defined_torques(model, springs, unique)
            bad = np.isnan(tau[:, 0]) if len(unique) else np.zeros(0, dtype=bool)
            if np.any(bad) and not any(u[0] == case for u in undefined):
                undefined.append((case, 0, unique[int(np.argmax(bad))].tolist(), why))
            keep &= ~bad
        return cls(samples, seed, unique[keep], tuple(raised), tuple(undefined), tuple(crossings), sampler is not None)

    def note(self, checked: int) -> str:
        """The sample, in words, for the design's output."""
        found = ("; it found more than the check at " + ", ".join(
            f"{joint} ({case}: {own:.3g} -> {value:.3g} N m)" for case, joint, own, value in self.raised)
                 if self.raised else "; it found no peak above the check's, to 3 digits")
        within = " (those in collision left out)" if self.workspace else ""
        return (f"checked by route 2 on {checked} random poses of the workspace, then re-checked on {self.samples:,} "
                f"independent ones{within} with a local search from the {AUDIT_STARTS} worst of them per joint and case (the {len(self.worst)} "
                f"worst poses found join the check, so every peak and share below holds on them){found}")

    def as_dict(self) -> dict:
        """For ``springlab design --json``."""
        return {"lead_crossings": [{"spring": m + 1, "angle_rad": angle, "pose_rad": pose}
                                   for m, angle, pose in self.crossings],
                "undefined": [{"case": case, "poses": count, "first_pose_rad": pose, "why": why}
                              for case, count, pose, why in self.undefined],
                "samples": self.samples, "workspace_only": self.workspace, "seed": list((self.seed, self.samples)),
                "worst_poses_rad": self.worst.tolist(),
                "raised": [{"case": case, "joint": joint, "check_peak_Nm": own, "audit_peak_Nm": value}
                           for case, joint, own, value in self.raised]}


def _climbs(model: RevoluteChain, springs, jobs, lo, hi, allowed=None) -> list[tuple[np.ndarray, float, tuple | None]]:
    """Per job (joint ``j``, pose ``start``): the largest |holding torque| (N m) of joint j near that pose within the
    bounds [lo, hi] (rad), by :func:`~springlab.design.search.compass_searches` on route 2's torques (every job's
    step in one call), moving only to poses ``allowed`` (a function of poses (M, n) -> (M,) bool; None: all); a
    job that climbed out of the workspace climbs again from its start, within it. Returns per job the pose, its
    |torque|, and the first trial pose where a spring had no line of action with the reason (None where every
    trial had one)."""
    if not jobs:
        return []
    joints = np.array([j for j, _ in jobs], dtype=int)
    broken: dict = {}

    def value(trials, which):
        A, M, n = trials.shape
        tau = defined_torques(model, springs, trials.reshape(A * M, n))[0].reshape(A, M, -1)
        picked = tau[np.arange(A), :, joints[which]]  # (A, M): each job's own joint
        for a in np.flatnonzero(np.isnan(tau[:, :, 0]).any(axis=1)):
            if which[a] not in broken:  # the job's first trials without a line of action, and why
                bad = np.isnan(picked[a])
                broken[which[a]] = (trials[a, int(np.argmax(bad))], defined_torques(model, springs, trials[a])[1])
        return np.abs(picked)  # nan where undefined: never chosen

    starts = np.array([start for _, start in jobs], dtype=float)
    X, best = compass_searches(value, starts, lo, hi)
    if allowed is not None:
        out = np.flatnonzero(~allowed(X))
        if len(out):  # those that climbed out of the workspace: again, within it
            again = lambda trials, which: value(trials, out[which])  # noqa: E731
            X[out], best[out] = compass_searches(again, starts[out], lo, hi, allowed=allowed)
    return [(X[s], float(best[s]), broken.get(s)) for s in range(len(jobs))]
