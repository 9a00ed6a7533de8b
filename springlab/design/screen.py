"""Sets of springs of any sign pattern, and the screen that refutes most of them before any is solved:
the exact sign test and the linear relaxation of 000 Eqs. (39) (:func:`screen_verdicts`; a refusal is a
proof that the set cannot balance). Used by the default search (:mod:`springlab.design.rank`) and by the
searches for fewer springs (:mod:`springlab.design.ground`).

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
"""

from __future__ import annotations

import itertools
import math

import numpy as np

from springlab import _checks
from springlab.design.rules import PATTERNS, SpringSlot
from springlab.design.solve import relaxation_margin, sign_consistent
from springlab.errors import SpringlabError
from springlab.executors import check_executor, map_ordered
from springlab.model.chain import Chain

CANDIDATE_RATE = 1e3
"""Candidate configurations screened per second (one linear programme each), about."""


def all_pattern_slots(n: int) -> list[SpringSlot]:
    """Every spring S(i,j) of an n-link arm with every sign pattern, the paper's
    criteria (000 Eq. 41, Fig. 10) ignored."""
    n = _checks.links(n, "n")

    return [SpringSlot(i, j, p) for i in range(1, n) for j in range(i + 1, n + 1) for p in PATTERNS]


def any_sign_candidates(n: int, count: int) -> list[tuple[SpringSlot, ...]]:
    """Every set of ``count`` slots, any sign pattern, that includes a same-sign S(1,n) (the
    only spring with an entry (1, n), which gravity's G_1n > 0 needs: -k a b < 0)."""
    count = _checks.count("count", count, least=1)
    slots = all_pattern_slots(n)
    end = [s for s in slots if (s.i, s.j) == (1, n) and s.pattern in ("(+,+)", "(-,-)")]
    rest = [s for s in slots if s not in end]
    if count > len(rest) + 1:
        raise SpringlabError(f"count = {count} springs is more than the {len(rest) + 1} distinct slots of {n} links hold")
    total = len(end) * math.comb(len(rest), count - 1)
    _checks.poses(f"{count} springs on {n} links", total, rate=CANDIDATE_RATE, unit="candidate configurations",
                  hint="each is a linear programme: ask for fewer springs")
    _checks.memory(f"{total} candidate configurations of {count} springs", total * count, hint="ask for fewer springs")
    return [(e, *others) for e in end for others in itertools.combinations(rest, count - 1)]


SCREEN_CHUNK = 2000
"""Candidate sets per task of :func:`screen`."""


def _passing(chain: Chain, candidates) -> list[bool]:
    return [relaxation_margin(chain, cfg) > 1e-9 for cfg in candidates]


def screen_verdicts(chain: Chain, candidates, *, executor=None, progress: bool = False,
                    desc: str = "screen") -> list[str]:
    """Per candidate set of springs: 'signs' (refuted by the exact sign test,
    :func:`springlab.design.solve.sign_consistent`), 'relaxation' (refuted by the linear relaxation
    of 000 Eqs. (39), :func:`springlab.design.solve.relaxation_margin`) or 'pass'. Both refutations
    are proofs that the set cannot balance. The programmes run in tasks of :data:`SCREEN_CHUNK`
    on ``executor`` (None: here)."""
    from tqdm import tqdm

    _checks.instance("chain", chain, Chain)
    executor = check_executor(executor)
    candidates = list(candidates)
    allowed = sign_consistent(chain, candidates) if candidates else np.zeros(0, dtype=bool)
    rest = [cfg for cfg, ok in zip(candidates, allowed, strict=True) if ok]
    chunks = [rest[k:k + SCREEN_CHUNK] for k in range(0, len(rest), SCREEN_CHUNK)]
    out = []
    for passed in tqdm(map_ordered(executor, _passing, [(chain, c) for c in chunks]), disable=not progress,
                       desc=desc, mininterval=1.0):
        out += passed
    verdicts = iter(out)
    return ["signs" if not ok else "pass" if next(verdicts) else "relaxation" for ok in allowed]


def screen(chain: Chain, candidates, *, executor=None, progress: bool = False, desc: str = "screen") -> list[bool]:
    """Per candidate set of springs: True when the exact sign test and the linear relaxation of
    000 Eqs. (39) both admit it (:func:`screen_verdicts`; False is a proof that it cannot balance)."""
    return [v == "pass" for v in screen_verdicts(chain, candidates, executor=executor, progress=progress, desc=desc)]
