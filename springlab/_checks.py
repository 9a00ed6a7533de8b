"""The validators every public function uses: one place for type, shape,
finiteness and range checks, each raising :class:`~springlab.errors.SpringlabError`
with a message that names the parameter, its value and its unit.

>>> positive("k", 2.0)
2.0
>>> positive("k", 0.0)
Traceback (most recent call last):
...
springlab.errors.SpringlabError: k must be finite and > 0, got 0.0
"""

from __future__ import annotations

import numpy as np

from springlab.errors import SpringlabError

__all__ = ["positive", "positive_vector", "vector_rows", "masses", "duration", "sample_count"]


def positive(name: str, value, *, allow_zero: bool = False) -> float:
    """``value`` as a float, finite and > 0 (>= 0 with ``allow_zero``)."""
    value = float(value)
    if not np.isfinite(value) or value < 0 or (value == 0 and not allow_zero):
        bound = ">= 0" if allow_zero else "> 0"
        raise SpringlabError(f"{name} must be finite and {bound}, got {value}")
    return value


def positive_vector(name: str, values, *, allow_zero: bool = False, first: int = 2) -> tuple[float, ...]:
    """A non-empty 1-D sequence of finite values > 0 (>= 0 with ``allow_zero``); element
    ``idx`` is named ``{name}_{idx + first}`` (links are numbered from 2 on a chain)."""
    arr = np.asarray(values, dtype=float)
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


def vector_rows(name: str, value, n: int) -> np.ndarray:
    """An (n, 3) array of finite lengths (m)."""
    out = np.asarray(value, dtype=float)
    if out.shape != (n, 3) or not np.all(np.isfinite(out)):
        raise SpringlabError(f"{name} must be finite with shape ({n}, 3) (m), got shape {np.shape(value)}")
    return out


def masses(name: str, value, n: int) -> np.ndarray:
    """n finite masses >= 0 (kg); element i is link i + 1."""
    out = np.asarray(value, dtype=float)
    if out.shape != (n,) or not np.all(np.isfinite(out)):
        raise SpringlabError(f"{name} must be {n} finite masses (kg), got {value!r}")
    bad = np.flatnonzero(out < 0)
    if bad.size:
        raise SpringlabError(f"{name}[{bad[0]}] (link {bad[0] + 1}) = {out[bad[0]]} kg: masses must be >= 0")
    return out


def duration(value) -> float:
    """A simulated or prescribed duration, finite and > 0 (s)."""
    if not (np.isfinite(value) and value > 0):
        raise SpringlabError(f"duration must be > 0 s, got {value}")
    return float(value)


def sample_count(value, *, least: int = 2, name: str = "samples", why: str = "") -> int:
    """An integer count >= ``least``; ``why`` is added to the message."""
    if int(value) != value or value < least:
        raise SpringlabError(f"{name} must be an integer >= {least}{why}, got {value}")
    return int(value)
