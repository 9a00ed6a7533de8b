"""Spring configurations: attachment criteria, rules R1-R6, and their enumeration
(Juang, Jhuang, Chen 2023, Sections 3.2-3.3, Table 1).

A configuration is a set of springs S(i,j), each with a sign pattern
(sign a, sign b) (see :mod:`springlab.model.springs` for the sketch). Two springs may
join the same pair of links with different patterns (the paper's S and S').

Each spring contributes to the entries (u, v), u < v, of the balance matrix
M = G + sum K_S with known signs (000 Eqs. 23a-d)::

    (i, j): -k a b -> sign -(sa sb)     (i, t): -r_t k a -> sign -sa
    (t, j):  r_t k b -> sign  sb        (t, v):  r_t r_v k -> always +

Gravity fills row 1 with positive G_{1,j}. The paper's rules say which springs
must be present so that every positive entry has a negative partner; they are
implemented here word for word (:func:`rule_violations`). Whether 000 Eqs. (39)
really have a solution with k > 0 and the stated signs is a separate, plain
check (:func:`springlab.design.feasibility`), and the two are compared in the
paper-000 notebook.

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
"""

from __future__ import annotations

import functools
import itertools
import numbers
import re
import time
from dataclasses import dataclass

from springlab import _checks
from springlab.errors import SearchExhaustedError, SpringlabError
from springlab.tables import Table

PATTERNS = ("(+,+)", "(-,-)", "(+,-)", "(-,+)")
_SIGN = {"+": 1, "-": -1}


@dataclass(frozen=True, order=True)
class SpringSlot:
    """A spring S(i,j) with a sign pattern, before any numbers are chosen."""

    i: int
    j: int
    pattern: str = "(+,+)"

    def __post_init__(self):
        for name in ("i", "j"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, numbers.Integral | float) or int(value) != value:
                raise SpringlabError(f"spring link index {name} of S(i,j) must be an integer, got {value!r}")
            object.__setattr__(self, name, int(value))
        if not (1 <= self.i < self.j):
            raise SpringlabError(f"a spring S(i,j) needs 1 <= i < j, got i={self.i}, j={self.j}")
        if self.pattern not in PATTERNS:
            raise SpringlabError(f"pattern of S({self.i},{self.j}) must be one of {PATTERNS}, got {self.pattern!r}")

    @property
    def sa(self) -> int:
        return _SIGN[self.pattern[1]]

    @property
    def sb(self) -> int:
        return _SIGN[self.pattern[3]]

    @property
    def ground(self) -> bool:
        return self.i == 1

    def __str__(self) -> str:
        return f"S({self.i},{self.j}){self.pattern}"


def slot(text: str) -> SpringSlot:
    """Parse 'S(2,4)(+,-)' (the pattern may be omitted for (+,+))."""
    if not isinstance(text, str):
        raise SpringlabError(f"a spring label must be a string like 'S(2,4)(+,-)', got {text!r}")
    body = text.replace(" ", "")
    match = re.fullmatch(r"S\((\d+),(\d+)\)(\([+-],[+-]\))?", body)
    if not match:
        raise SpringlabError(f"cannot read a spring from {text!r}; write S(i,j) with integers i < j and "
                             "optionally a pattern, e.g. 'S(2,4)(+,-)'")
    return SpringSlot(int(match.group(1)), int(match.group(2)), match.group(3) or "(+,+)")


def as_slots(slots) -> list[SpringSlot]:
    """A configuration as a list of :class:`SpringSlot`; strings are parsed by :func:`slot`."""
    if isinstance(slots, str | SpringSlot) or not hasattr(slots, "__iter__"):
        raise SpringlabError(f"a configuration must be a list of springs such as ['S(1,3)(+,+)'], got {slots!r}")
    out = []
    for s in slots:
        if not isinstance(s, str | SpringSlot):
            raise SpringlabError(f"each spring of a configuration must be a SpringSlot or a label like "
                                 f"'S(1,3)(+,+)', got {s!r}")
        out.append(slot(s) if isinstance(s, str) else s)
    return out


def contributions(s: SpringSlot) -> dict[tuple[int, int], int]:
    """Signs of the off-diagonal entries a spring contributes to M (000 Eqs. 23a-d)."""
    out = {(s.i, s.j): -s.sa * s.sb}
    for t in range(s.i + 1, s.j):
        out[(s.i, t)] = -s.sa
        out[(t, s.j)] = s.sb
        for v in range(t + 1, s.j):
            out[(t, v)] = 1
    return out


def entry_signs(slots) -> dict[tuple[int, int], set[int]]:
    """For each entry (u, v) of rows >= 2, the set of signs the springs put there."""
    return _entry_signs(as_slots(slots))


def _entry_signs(slots) -> dict[tuple[int, int], set[int]]:
    out: dict[tuple[int, int], set[int]] = {}
    for s in slots:
        for key, sign in contributions(s).items():
            if key[0] >= 2:
                out.setdefault(key, set()).add(sign)
    return out


@dataclass(frozen=True)
class Violation:
    rule: str
    message: str

    def __str__(self) -> str:
        return f"{self.rule}: {self.message}"


def _has(slots, i, j, patterns) -> bool:
    return any(s.i == i and s.j == j and s.pattern in patterns for s in slots)


def rule_candidates(u: int, v: int, n: int) -> tuple[str, list[SpringSlot]]:
    """The rule that governs entry (u, v), u >= 2, and the springs it allows there.

    R3 (2, n); R4 (2, j), 2 < j < n; R5 (i, n), i > 2; R6 (i, j), i > 2, j < n,
    each as the paper words it.
    """
    n = _count_links(n)
    u, v = _checks.count("u", u, least=2), _checks.count("v", v, least=2)
    if not u < v <= n:
        raise SpringlabError(f"need 2 <= u < v <= n = {n}, got u = {u}, v = {v}")
    rule, candidates = _rule_candidates(u, v, n)
    return rule, list(candidates)


@functools.lru_cache(maxsize=4096)
def _rule_candidates(u: int, v: int, n: int) -> tuple[str, tuple[SpringSlot, ...]]:
    """:func:`rule_candidates` for checked integers, cached (the enumeration asks again and again)."""
    same = [SpringSlot(u, v, "(+,+)"), SpringSlot(u, v, "(-,-)")]
    longer = [SpringSlot(u, v + 1, "(+,+)"), SpringSlot(u, v + 1, "(+,-)")] if v < n else []
    lower = [SpringSlot(t, v, p) for t in range(2, u) for p in ("(-,-)", "(+,-)")]
    if u == 2 and v == n:
        return "R3", tuple(same)
    if u == 2:
        return "R4", tuple(same + longer)
    if v == n:
        return "R5", tuple(same + lower)
    return "R6", tuple(same + longer + lower)


def rule_violations(n: int, slots) -> list[Violation]:
    """Every attachment criterion and rule R1-R6 the configuration breaks (empty: admissible).

    :param n: number of links, the ground included
    :param slots: iterable of :class:`SpringSlot` (or strings for :func:`slot`)
    """
    return _violations(_count_links(n), as_slots(slots))


def _violations(n: int, slots) -> list[Violation]:
    """:func:`rule_violations` for a checked n and a list of :class:`SpringSlot`."""
    out: list[Violation] = []
    seen = set()
    for s in slots:
        if s.j > n:
            out.append(Violation("range", f"{s} attaches to link {s.j} but the arm has {n} links"))
        if s in seen:
            out.append(Violation("duplicate", f"{s} is listed twice"))
        seen.add(s)
        if s.ground:
            allowed = ("(+,+)", "(-,-)") if s.j == 2 else ("(+,+)",)
            if s.pattern not in allowed:
                out.append(Violation(
                    "000 Eq. (41)",
                    f"ground-connected {s} must be (+,+)" + (" or (-,-)" if s.j == 2 else "")
                    + ", or its first-row components add to gravity instead of cancelling it"))
        elif s.pattern == "(-,+)":
            out.append(Violation(
                "Fig. 10", f"{s}: a (-,+) spring contributes only positive components"))
    if out:
        return out
    if not _has(slots, 1, n, ("(+,+)", "(-,-)") if n == 2 else ("(+,+)",)):
        out.append(Violation("R1", f"no ground-connected spring S(1,{n}) to the end link"))
    for j in range(2, n):
        if not (_has(slots, 1, j, PATTERNS) or _has(slots, 1, j + 1, PATTERNS)):
            out.append(Violation(
                "R2", f"neither S(1,{j}) nor S(1,{j + 1}): G_1,{j} cannot be offset"))
    for (u, v), signs in sorted(_entry_signs(slots).items()):
        if 1 in signs:
            rule, candidates = _rule_candidates(u, v, n)
            if not any(c in slots for c in candidates):
                names = ", ".join(str(c) for c in candidates) or "none exists"
                out.append(Violation(
                    rule, f"component ({u},{v}) is unbalanced; install one of {names}"))
    return out


def is_admissible(n: int, slots) -> bool:
    """True when the configuration breaks no criterion and no rule R1-R6."""
    return not rule_violations(n, slots)


def _count_links(n) -> int:
    return _checks.links(n)


def _ground_sets(n: int):
    """Minimal sets of ground springs under R1 and R2, with S(1,2)'s two patterns."""
    middle = list(range(2, n))
    for size in range(len(middle) + 1):
        for chosen in itertools.combinations(middle, size):
            have = set(chosen) | {n}
            if not all(j in have or j + 1 in have for j in middle):
                continue
            if any(all(j in have - {c} or j + 1 in have - {c} for j in middle) for c in chosen):
                continue  # a spring could be dropped: not minimal
            base = [SpringSlot(1, j) for j in sorted(have) if j != 2]
            if 2 in have:
                yield base + [SpringSlot(1, 2, "(+,+)")]
                yield base + [SpringSlot(1, 2, "(-,-)")]
            else:
                yield base


class _Bits:
    """The enumeration's tables for n links: a configuration is an int, one bit per slot (slots
    numbered in :class:`SpringSlot` order, so ascending bits are the sorted configuration), and
    each slot's positive entries of rows >= 2 (000 Eqs. 23a-d) an int, one bit per entry (u, v)
    in sorted order. The checks of :func:`rule_violations` then cost a few integer operations
    instead of building sets of signs (the enumeration at n = 6: 17 s -> about 2 s)."""

    def __init__(self, n: int):
        self.n = n
        self.slots = sorted(SpringSlot(i, j, p) for i in range(1, n) for j in range(i + 1, n + 1) for p in PATTERNS)
        self.bit = {s: k for k, s in enumerate(self.slots)}
        keys = [(u, v) for u in range(2, n + 1) for v in range(u + 1, n + 1)]
        entry = {key: e for e, key in enumerate(keys)}
        self.positive = [sum(1 << entry[key] for key, sign in contributions(s).items() if key[0] >= 2 and sign == 1)
                         for s in self.slots]
        self.candidates = [[self.bit[c] for c in _rule_candidates(u, v, n)[1]] for u, v in keys]
        self.candidate_mask = [self.mask(c) for c in self.candidates]
        self.span = [s.j - s.i for s in self.slots]
        self.static_bad = self.mask(k for k, s in enumerate(self.slots)  # 000 Eq. (41) and Fig. 10
                                    if (s.pattern not in (("(+,+)", "(-,-)") if s.j == 2 else ("(+,+)",)) if s.ground
                                        else s.pattern == "(-,+)"))
        self.r1 = self.mask(self.bit[SpringSlot(1, n, p)] for p in (("(+,+)", "(-,-)") if n == 2 else ("(+,+)",)))
        self.r2 = [self.mask(self.bit[SpringSlot(1, t, p)] for t in (j, j + 1) for p in PATTERNS) for j in range(2, n)]

    @staticmethod
    def mask(ids) -> int:
        return sum(1 << k for k in set(ids))

    @staticmethod
    def ids(cfg: int) -> list[int]:
        out = []
        while cfg:
            low = cfg & -cfg
            out.append(low.bit_length() - 1)
            cfg ^= low
        return out

    def positives(self, cfg: int) -> int:
        out = 0
        for k in self.ids(cfg):
            out |= self.positive[k]
        return out

    def open_branch(self, cfg: int) -> list[int] | None:
        """The candidates (slot numbers) of the first positive entry none of whose candidates is
        present (as :func:`_violations` orders them), or None."""
        unbalanced = self.positives(cfg)
        while unbalanced:
            low = unbalanced & -unbalanced
            e = low.bit_length() - 1
            if not cfg & self.candidate_mask[e]:
                return self.candidates[e]
            unbalanced ^= low
        return None

    def admissible(self, cfg: int) -> bool:
        """No criterion and no rule R1-R6 broken: :func:`rule_violations` is empty."""
        if cfg & self.static_bad or not cfg & self.r1 or any(not cfg & m for m in self.r2):
            return False
        return self.open_branch(cfg) is None

    def minimal_admissible(self, cfg: int) -> bool:
        """Admissible, and no single spring can be removed with the rest still admissible."""
        return self.admissible(cfg) and not any(self.admissible(cfg & ~(1 << k)) for k in self.ids(cfg))

    def configuration(self, cfg: int) -> tuple[SpringSlot, ...]:
        return tuple(self.slots[k] for k in self.ids(cfg))


@functools.lru_cache(maxsize=16)
def _bits(n: int) -> _Bits:
    return _Bits(n)


def iter_configurations(n: int, *, max_springs: int | None = None, time_limit: float | None = None):
    """Yield the admissible configurations with necessary springs only, for n links,
    in a deterministic order (see :func:`enumerate_configurations`).

    :param time_limit: raise :class:`~springlab.errors.SearchExhaustedError` after this many
        seconds (None: no limit); the enumeration takes about 0.01 s at n = 5, 1.3 s at n = 6
        and grows about twentyfold per link
    """
    n = _count_links(n)
    time_limit = _checks.optional_positive("time_limit", time_limit, "s")
    deadline = None if time_limit is None else time.perf_counter() + time_limit
    found = 0
    if max_springs is not None:
        max_springs = _checks.count("max_springs", max_springs, least=1)
    max_springs = max_springs or n * (n - 1)
    bits = _bits(n)
    seen: set[int] = set()
    stack = [bits.mask(bits.bit[s] for s in g) for g in reversed(list(_ground_sets(n)))]
    while stack:
        if deadline is not None and time.perf_counter() > deadline:
            raise SearchExhaustedError(f"the enumeration for n = {n} stopped at time_limit = {time_limit:g} s after "
                                       f"{found} configurations; it grows about twentyfold per link: raise time_limit")
        current = stack.pop()
        if current in seen or current.bit_count() > max_springs:
            continue
        seen.add(current)
        branch = bits.open_branch(current)
        if branch is not None:
            stack.extend(current | (1 << c) for c in reversed(branch))
        elif bits.minimal_admissible(current):
            found += 1
            yield bits.configuration(current)


def enumerate_configurations(n: int, *, max_springs: int | None = None, time_limit: float | None = None) -> list[tuple[SpringSlot, ...]]:
    """All admissible configurations with necessary springs only, for n links.

    Built as the paper builds them: R1 and R2 choose the ground springs, then
    each unbalanced component is offset by one of the springs its rule (R3-R6)
    allows, branching on every choice. A configuration is kept when it is
    admissible and no single spring can be removed from it with the rest still
    admissible.

    :returns: sorted tuples of :class:`SpringSlot`, in a deterministic order
    """
    return sorted(set(iter_configurations(n, max_springs=max_springs, time_limit=time_limit)))


def group_alternatives(configs) -> list[dict[tuple[int, int], frozenset]]:
    """Merge configurations that differ only in one pair's springs, as Table 1
    writes '1^(+,+)/(-,-)'. Returns, per group, {(i, j): set of alternatives},
    each alternative a sorted tuple of patterns on that pair."""
    groups = []
    for cfg in configs:
        per_pair: dict[tuple[int, int], list[str]] = {}
        for s in cfg:
            per_pair.setdefault((s.i, s.j), []).append(s.pattern)
        groups.append({k: frozenset([tuple(sorted(v))]) for k, v in per_pair.items()})
    merged = True
    while merged:
        merged = False
        for x, y in itertools.combinations(range(len(groups)), 2):
            gx, gy = groups[x], groups[y]
            if gx.keys() != gy.keys():
                continue
            diff = [k for k in gx if gx[k] != gy[k]]
            if len(diff) == 1:
                k = diff[0]
                new = dict(gx)
                new[k] = gx[k] | gy[k]
                groups = [g for idx, g in enumerate(groups) if idx not in (x, y)] + [new]
                merged = True
                break
    return sorted(groups, key=lambda g: sorted((k, sorted(v)) for k, v in g.items()))


def format_group(group, n: int) -> str:
    """One grouped configuration as the paper's matrix: rows i = 1..n-1, columns j = 2..n."""
    rows = []
    for i in range(1, n):
        cells = []
        for j in range(2, n + 1):
            if j <= i:
                cells.append("-")
            elif (i, j) in group:
                alts = ["+".join(f"1{p}" for p in alt) for alt in sorted(group[(i, j)])]
                cells.append("/".join(alts))
            else:
                cells.append("0")
        rows.append(" ".join(f"{c:>16}" for c in cells))
    return "\n".join(rows)


def spans(slots) -> int:
    """Joints spanned, summed over the springs: sum (j - i)."""
    slots = as_slots(slots)
    return sum(s.j - s.i for s in slots)


def best_first_configurations(n: int, *, deadline: float | None = None, step=None):
    """The configurations of :func:`iter_configurations`, fewest springs first and, among
    those, fewest spanned joints (003's efficient configurations, generalised), found
    without enumerating the rest.

    The same branching as the paper's construction, taken best first: a partial
    configuration's (springs, spanned joints) only grows as springs are added, so
    configurations leave the queue in that order. Yields (springs, spans, configuration).

    :param deadline: a ``time.perf_counter()`` value after which the search stops (it can
        take long before its first configuration for n of 9 or more)
    :param step: called with no argument for each partial configuration taken from the queue
        (a progress bar's ``update``)
    """
    import heapq

    n = _count_links(n)
    bits = _bits(n)
    heap = []  # (springs, spans, slot numbers ascending, bits): the numbers order as the sorted slots do
    for g in _ground_sets(n):
        cfg = bits.mask(bits.bit[s] for s in g)
        ids = tuple(bits.ids(cfg))
        heapq.heappush(heap, (len(ids), sum(bits.span[k] for k in ids), ids, cfg))
    seen: set[int] = set()
    while heap:
        if deadline is not None and time.perf_counter() > deadline:
            return
        if step is not None:
            step()
        count, span, ids, current = heapq.heappop(heap)
        if current in seen:
            continue
        seen.add(current)
        branch = bits.open_branch(current)
        if branch is not None:
            for c in branch:
                nxt = current | (1 << c)
                if nxt not in seen:
                    nxt_ids = tuple(bits.ids(nxt))
                    heapq.heappush(heap, (len(nxt_ids), sum(bits.span[k] for k in nxt_ids), nxt_ids, nxt))
        elif bits.minimal_admissible(current):
            yield count, span, bits.configuration(current)


VERDICT_LINKS = 6
"""The most links :func:`verdict` takes (the enumeration it compares with takes about 1.3 s at n = 6)."""


@dataclass(frozen=True)
class Verdict:
    """What paper 000's rules say of one configuration: ``labels`` ('S(1,3)(+,+)', ...),
    whether it is one of the enumerated configurations with necessary springs
    (:func:`enumerate_configurations`), and ``why`` ('enumerated', or the rules it breaks)."""

    labels: tuple
    enumerated: bool
    why: str


@functools.lru_cache(maxsize=8)
def _enumerated_labels(n: int) -> frozenset:
    return frozenset(tuple(sorted(str(s) for s in cfg)) for cfg in enumerate_configurations(n))


def verdict(n: int, springs) -> Verdict:
    """000's verdict on the configuration of ``springs`` (springs with ``i``, ``j`` and
    ``pattern``, or :class:`SpringSlot` objects, or strings for :func:`slot`) on n links
    (2..:data:`VERDICT_LINKS`: the verdict compares with the full enumeration)."""
    n = _count_links(n)
    if n > VERDICT_LINKS:
        raise SpringlabError(f"n = {n}: the verdict needs the full enumeration of the configurations, about "
                             f"{1.3 * 20 ** (n - 6):.0e} s at n = {n}; use rule_violations(n, springs) (the rules alone) "
                             f"for n > {VERDICT_LINKS}")
    if isinstance(springs, str) or not hasattr(springs, "__iter__"):
        raise SpringlabError(f"springs must be a list of springs or labels, got {springs!r}")
    slots = [s if isinstance(s, (str, SpringSlot)) else SpringSlot(s.i, s.j, s.pattern) for s in springs]
    slots = as_slots(slots)
    labels = tuple(str(s) for s in slots)
    enumerated = tuple(sorted(labels)) in _enumerated_labels(n)
    why = "enumerated" if enumerated else "; ".join(v.rule for v in rule_violations(n, slots)) or \
        "admissible, but a spring can be removed (not all necessary)"
    return Verdict(labels, enumerated, why)


@dataclass(frozen=True)
class ConfigurationCounts:
    """Admissible configurations with necessary springs per n (:func:`iter_configurations`),
    the enumeration's time (s), the best-first search's time for its first ten (s) and the
    fewest springs it finds, and the counts beyond the last enumerated n estimated by the
    last growth ratio."""

    counts: dict
    seconds: dict
    first: dict
    ratio: float
    estimate: dict

    def table(self, ns=range(3, 9)) -> Table:
        return Table(["n", "configurations", "enumeration (s)", "fewest springs", "best first, first ten (s)"],
                     [(n, self.counts.get(n, f"~{self.estimate[n]:.0e} (estimate)" if n in self.estimate else "-"),
                       f"{self.seconds[n]:.2f}" if n in self.seconds else "-", self.first[n][1] if n in self.first else "-",
                       f"{self.first[n][0]:.2f}" if n in self.first else "-") for n in ns])


def configuration_counts(enumerate_ns, first_ns, *, first: int = 10) -> ConfigurationCounts:
    """Count the configurations for each n of ``enumerate_ns`` (timed) and time the first
    ``first`` of the best-first search for each n of ``first_ns``."""
    for name, ns in (("enumerate_ns", enumerate_ns), ("first_ns", first_ns)):
        if isinstance(ns, str) or not hasattr(ns, "__iter__"):
            raise SpringlabError(f"{name} must be a list of link counts n, got {ns!r}")
    enumerate_ns = [_count_links(n) for n in enumerate_ns]
    first_ns = [_count_links(n) for n in first_ns]
    first = _checks.count("first", first, least=1)
    if len(enumerate_ns) < 2 or enumerate_ns != list(range(enumerate_ns[0], enumerate_ns[-1] + 1)):
        raise SpringlabError(f"enumerate_ns must be two or more consecutive n (the growth ratio needs them), "
                             f"got {enumerate_ns}")
    counts, seconds, best = {}, {}, {}
    for n in enumerate_ns:
        t0 = time.perf_counter()
        counts[n] = sum(1 for _ in iter_configurations(n))
        seconds[n] = time.perf_counter() - t0
    for n in first_ns:
        t0 = time.perf_counter()
        top = list(itertools.islice(best_first_configurations(n), first))
        best[n] = (time.perf_counter() - t0, top[0][0], top[0][1])
    ratios = [counts[n + 1] / counts[n] for n in list(counts)[:-1]]
    last = max(counts)
    estimate = {last + 1: counts[last] * ratios[-1], last + 2: counts[last] * ratios[-1] ** 2}
    return ConfigurationCounts(counts, seconds, best, ratios[-1], estimate)
