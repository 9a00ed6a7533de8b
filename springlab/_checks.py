"""The validators every public function uses: one place for type, shape,
finiteness and range checks, each raising :class:`~springlab.errors.SpringlabError`
with a message that names the parameter, its value and its unit.

>>> positive("k", 2.0)
2.0
>>> positive("k", 0.0)
Traceback (most recent call last):
...
springlab.errors.SpringlabError: k must be finite and > 0, got 0.0
>>> count("restarts", 2.5)
Traceback (most recent call last):
...
springlab.errors.SpringlabError: restarts must be an integer >= 0, got 2.5
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from springlab.errors import SpringlabError

__all__ = ["number", "finite", "positive", "optional_positive", "instance", "at_most", "positive_vector", "vector_rows", "masses", "duration",
           "sample_count", "count", "choice", "real_array", "links", "rng", "memory", "MEMORY_LIMIT", "poses",
           "TIME_LIMIT"]

MEMORY_LIMIT = 2 * 2**30
"""Bytes: the largest array a single request may allocate. Larger requests are refused up
front with their size, rather than failing with a MemoryError after allocating."""


def number(name: str, value) -> float:
    """``value`` as a float: a real number (not a bool, a string or None), possibly infinite or NaN."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        if isinstance(value, np.ndarray) and value.ndim == 0 and np.isrealobj(value) and value.dtype != bool:
            return float(value)
        raise SpringlabError(f"{name} must be a real number, got {value!r} ({type(value).__name__})")
    return float(value)


def finite(name: str, value, unit: str = "") -> float:
    """``value`` as a finite float."""
    out = number(name, value)
    if not np.isfinite(out):
        raise SpringlabError(f"{name} must be finite{_in(unit)}, got {value!r}")
    return out


def positive(name: str, value, *, allow_zero: bool = False, unit: str = "") -> float:
    """``value`` as a float, finite and > 0 (>= 0 with ``allow_zero``)."""
    value = number(name, value)
    if not np.isfinite(value) or value < 0 or (value == 0 and not allow_zero):
        bound = ">= 0" if allow_zero else "> 0"
        raise SpringlabError(f"{name} must be finite and {bound}{_in(unit)}, got {value}")
    return value


def optional_positive(name: str, value, unit: str = "", *, allow_inf: bool = False) -> float | None:
    """None, or a float > 0, finite unless ``allow_inf`` (a limit that may be left unset)."""
    if value is None or (allow_inf and number(name, value) == np.inf):
        return None if value is None else np.inf
    return positive(name, value, unit=unit)


def instance(name: str, value, kind, what: str = ""):
    """``value`` if it is a ``kind`` (a class or a tuple of classes), else an error naming what to pass."""
    if not isinstance(value, kind):
        want = what or (kind.__name__ if isinstance(kind, type) else " or ".join(k.__name__ for k in kind))
        raise SpringlabError(f"{name} must be a {want}, got {_short(value)} ({type(value).__name__})")
    return value


def at_most(name: str, value, limit: float, unit: str = "", *, why: str = "") -> float:
    """A positive finite ``value`` no larger than ``limit``; ``why`` is added to the message."""
    value = positive(name, value, unit=unit)
    if value > limit:
        raise SpringlabError(f"{name} = {value:g}{_in(unit)} is above {limit:g}{why}")
    return value


def _in(unit: str) -> str:
    return f" {unit}" if unit else ""


def positive_vector(name: str, values, *, allow_zero: bool = False, first: int = 2) -> tuple[float, ...]:
    """A non-empty 1-D sequence of finite values > 0 (>= 0 with ``allow_zero``); element
    ``idx`` is named ``{name}_{idx + first}`` (links are numbered from 2 on a chain)."""
    arr = real_array(name, values, finite_only=False)
    if arr.ndim != 1 or arr.size == 0:
        raise SpringlabError(f"{name} must be a non-empty 1-D sequence, got shape {arr.shape}")
    for idx, v in enumerate(arr):
        link = idx + first
        if not np.isfinite(v):
            raise SpringlabError(f"{name}_{link} must be finite, got {v}")
        if v < 0 or (v == 0 and not allow_zero):
            bound = ">= 0" if allow_zero else "> 0"
            raise SpringlabError(f"{name}_{link} must be {bound}, got {v}")
    return tuple(float(v) for v in arr)


def real_array(name: str, value, *, shape=None, finite_only: bool = True) -> np.ndarray:
    """``value`` as a float array of real numbers (no strings, None or complex numbers), of
    ``shape`` if given (None entries in ``shape`` match any length), finite unless
    ``finite_only`` is False."""
    if isinstance(value, str | bytes) or value is None:
        raise SpringlabError(f"{name} must be an array of numbers, got {value!r}")
    try:
        out = np.asarray(value)
    except ValueError as err:  # ragged nesting
        raise SpringlabError(f"{name} must be a rectangular array of numbers: {err}") from None
    if out.dtype == object or out.dtype.kind not in "biuf":
        raise SpringlabError(f"{name} must be an array of real numbers, got dtype {out.dtype} ({_short(value)})")
    out = out.astype(float, copy=False)
    if shape is not None and (out.ndim != len(shape) or any(s is not None and s != o for s, o in zip(shape, out.shape, strict=True))):
        want = "(" + ", ".join("N" if s is None else str(s) for s in shape) + ")"
        raise SpringlabError(f"{name} must have shape {want}, got {out.shape}")
    if finite_only and not np.all(np.isfinite(out)):
        raise SpringlabError(f"{name} contains NaN or infinity: every entry must be finite")
    return out


def _short(value) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def vector_rows(name: str, value, n: int) -> np.ndarray:
    """An (n, 3) array of finite lengths (m)."""
    out = real_array(name, value, finite_only=False)
    if out.shape != (n, 3) or not np.all(np.isfinite(out)):
        raise SpringlabError(f"{name} must be finite with shape ({n}, 3) (m), got shape {np.shape(value)}")
    return out


def masses(name: str, value, n: int) -> np.ndarray:
    """n finite masses >= 0 (kg); element i is link i + 1."""
    out = real_array(name, value, finite_only=False)
    if out.shape != (n,) or not np.all(np.isfinite(out)):
        raise SpringlabError(f"{name} must be {n} finite masses (kg), got {value!r}")
    bad = np.flatnonzero(out < 0)
    if bad.size:
        raise SpringlabError(f"{name}[{bad[0]}] (link {bad[0] + 1}) = {out[bad[0]]} kg: masses must be >= 0")
    return out


def duration(value, name: str = "duration") -> float:
    """A simulated or prescribed duration, finite and > 0 (s)."""
    value = number(name, value)
    if not (np.isfinite(value) and value > 0):
        raise SpringlabError(f"{name} must be > 0 s, got {value}")
    return float(value)


def count(name: str, value, *, least: int = 0, why: str = "") -> int:
    """An integer (not a bool, a float with a fraction or a string) >= ``least``."""
    integral = isinstance(value, numbers.Integral) or (isinstance(value, numbers.Real) and math.isfinite(value)
                                                        and float(value).is_integer())
    if isinstance(value, bool) or not integral or value < least:
        raise SpringlabError(f"{name} must be an integer >= {least}{why}, got {value!r}")
    return int(value)


def sample_count(value, *, least: int = 2, name: str = "samples", why: str = "") -> int:
    """An integer count >= ``least``; ``why`` is added to the message."""
    return count(name, value, least=least, why=why)


MAX_LINKS = 10_000
"""The most links (ground included) any function accepts: structures grow as n^2 and searches faster."""

MAX_FILE_BYTES = 16 * 2 ** 20
"""The largest arm file or URDF read (16 MiB), checked before it is read: an arm file, even the URDF of a
large robot, is well under 1 MiB."""


def links(value, name: str = "n (links with the ground)", *, least: int = 2) -> int:
    """A number of links: an integer in ``least``..:data:`MAX_LINKS`."""
    value = count(name, value, least=least)
    if value > MAX_LINKS:
        raise SpringlabError(f"{name} = {value} is above {MAX_LINKS}: no arm has that many links")
    return value


def rng(name: str, seed):
    """A numpy Generator from ``seed``: None, a non-negative integer, a SeedSequence or a Generator."""
    if seed is None or isinstance(seed, np.random.Generator | np.random.SeedSequence):
        return np.random.default_rng(seed)
    return np.random.default_rng(count(name, seed))


def choice(name: str, value, options) -> str:
    """One of ``options``."""
    options = tuple(options)
    if not isinstance(value, str) or value not in options:
        raise SpringlabError(f"{name} must be one of {options}, got {value!r}")
    return value


def memory(what: str, elements: float, *, bytes_per: int = 8, limit: int | None = None, hint: str = "") -> None:
    """Refuse up front a request that would allocate more than ``limit`` bytes
    (default :data:`MEMORY_LIMIT`): ``elements`` float values of ``bytes_per`` bytes."""
    limit = MEMORY_LIMIT if limit is None else limit
    need = float(elements) * bytes_per
    if need > limit:
        raise SpringlabError(f"{what} would need about {_bytes(need)} of memory, over the limit of {_bytes(limit)}"
                             f"{'; ' + hint if hint else ''}")


TIME_LIMIT = 3600.0
"""s: the longest single evaluation a request may ask for, estimated up front (:func:`poses`)."""


def poses(what: str, count: float, *, rate: float, unit: str = "poses", limit: float | None = None,
          hint: str = "") -> None:
    """Refuse up front a request of ``count`` poses (or other ``unit``) that would run longer
    than ``limit`` seconds (default :data:`TIME_LIMIT`) at ``rate`` of them per second."""
    limit = TIME_LIMIT if limit is None else limit
    seconds = float(count) / rate
    if seconds > limit:
        raise SpringlabError(f"{what} is {float(count):.3g} {unit}, about {seconds / 3600:.3g} h at {rate:.0e} {unit}/s, "
                             f"over the limit of {limit / 3600:g} h{'; ' + hint if hint else ''}")


def _bytes(n: float) -> str:
    for unit, size in (("TiB", 2**40), ("GiB", 2**30), ("MiB", 2**20), ("kiB", 2**10)):
        if n >= size:
            return f"{n / size:.3g} {unit}"
    return f"{n:.0f} B"
