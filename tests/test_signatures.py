"""Every public function of the library (and every public method of the model's chain) whose
arguments a fixture can fill is called once validly, then once per argument (and per keyword
argument of :data:`OPTIONAL`) with junk in its place, the common junk and the junk of the
argument's kind (:data:`EXTRA_JUNK`): each junk argument must be refused
with a SpringlabError (or accepted with a finite result), never fail inside numpy, scipy or
sympy with a message that names nothing. The simulation modules (exudyn) and the workbench
are left out: their inputs are checked by tests/test_refusals.py."""

from __future__ import annotations

import importlib
import inspect
import math
import pkgutil
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest
from test_refusals import ARM, COMP, DYAD, PB, PLANAR, SPRINGS, WORKSPACE, X, spec

import springlab
from springlab.design.tolerance import Tolerances
from springlab.errors import SpringlabError
from springlab.mechanisms import two_spring_arm
from springlab.mechanisms.pseudobase.subsystems import design_equilibrators
from springlab.model.chain import Chain
from springlab.model.springs import Spring
from springlab.papers import juang2022, lenzo2017

ARM_FILE = str(Path(__file__).resolve().parents[1] / "notebooks" / "arms" / "paper000_arm.toml")
PLANAR_SPRINGS = juang2022.SPRINGS_PRINTED
PB_SPRINGS = design_equilibrators(PB, [20e3, 2e3, 15e3, 2e3, 1e3], [0.1, 0.08, 0.08, 0.08, 0.08])
LENZO = lenzo2017.ARM
LENZO_DESIGN = two_spring_arm.solve(LENZO, a2=0.1, a12=0.05, b12=0.4)

FIXTURES = {"chain": ARM, "springs": SPRINGS, "X": X, "comp": COMP, "dyad": DYAD, "workspace": WORKSPACE,
            "slots": ["S(1,2)", "S(1,4)", "S(2,4)", "S(3,4)(-,-)"], "n": 3, "seed": 0, "samples": 5,
            "phi": [0.5, 1.0], "theta": [[0.1, 0.2, 0.3]], "q": np.zeros((1, PB.n)), "spring": SPRINGS[0],
            "configuration": ["S(1,2)"], "count": 2, "spec": spec(), "spec_or_chain": ARM,
            "rng": 0, "step": 30.0, "angles": np.zeros((1, 3, 3)), "duration": 1.0, "poses": X[:2],
            "tol": Tolerances(stiffness=0.1), "C": 200.0, "y": [0.4, 0.45, 0.5], "angle": 0.3, "axis": (0.0, 0.0, 1.0),
            "tau": [0.2, 0.5], "t_I": 0.0, "t_F": 1.0, "theta_I": 0.0, "theta_F": 1.0, "initial": np.zeros((3, 3)),
            "rotation": np.full((3, 3), 0.1), "psi": 0.2, "order": "zyx", "value": 1.5, "text": "S(1,3)(+,-)",
            "r": [0.3, 0.2], "d": [0.1, 0.1], "m": [2.0, 1.0], "size": 4, "path": ARM_FILE,
            "data": {"link": [{"length": 0.3, "com": 0.1, "mass": 1.0}]}, "kind": "length", "where": "here",
            "reading": "magnitudes", "u": 2, "v": 3, "decimals": 2, "Cs": [180.0, 200.0], "config": "Λ3-1",
            "sp": PLANAR_SPRINGS[0], "payload": 1.0, "K": [1e3] * 5, "l_CA": [0.1] * 5, "link": 3,
            "a2": 0.1, "a12": 0.1, "b12": 0.1, "enumerate_ns": [3], "first_ns": [3],
            "rel": np.broadcast_to(np.eye(3), (1, 2, 3, 3)), "start": DYAD, "G": [500.0, 300.0, 90.0],
            "moments": np.ones((2, 3)), "method": "no auxiliary links", "mass": 1.0}
BY_MODULE = {  # the same names meaning other objects in a mechanism's modules
    "springlab.mechanisms.planar": {"arm": PLANAR, "springs": PLANAR_SPRINGS, "r": PLANAR.r,
                                    "m": PLANAR.m[1:], "choices": juang2022.FREE_CHOICES, "config": "Λ3-1"},
    "springlab.mechanisms.pseudobase": {"arm": PB, "springs": PB_SPRINGS, "poses": np.zeros((1, PB.n)),
                                        "m": PB.m, "s": PB.s, "r": PB.link_vectors()},
    "springlab.mechanisms.two_spring_arm": {"arm": LENZO, "design": LENZO_DESIGN},
    "springlab.design.rank": {"arm": spec()},
}
JUNK = ("junk", math.nan, None)
EXTRA_JUNK = {  # the junk one kind of argument takes: each reached a raw error once
    "size": (-3,), "mass": ("0.5",), "C_max": (0.0,), "executor": (ThreadPoolExecutor,),
    "springs": ([Spring(1, 4, 1e200, 0.1, 100.0)],), "choices": ({"k_S99": 1.0},),
}
OPTIONAL = {"C_max": 300.0, "executor": None}
"""Keyword arguments with a default that the probe fills with junk too (their valid value)."""
SKIP = ("springlab.workbench", "springlab.energy.simulation", "springlab.energy.multibody",
        "springlab.mechanisms.pseudobase.simulation", "springlab.mechanisms.dyad.simulation", "springlab._checks")
RETURNS_NOTHING = {"check_attachments"}  # returns None: nothing to test for finiteness


def fixtures_for(module: str) -> dict:
    out = dict(FIXTURES)
    for prefix, extra in BY_MODULE.items():
        if module.startswith(prefix):
            out |= extra
    return out


def public_functions():
    for info in pkgutil.walk_packages(springlab.__path__, "springlab."):
        if info.name.startswith(SKIP):
            continue
        module = importlib.import_module(info.name)
        for name, f in vars(module).items():
            if name.startswith("_") or not inspect.isfunction(f) or f.__module__ != info.name:
                continue
            yield from _callable(f"{info.name}.{name}", f, fixtures_for(info.name))
    for cls, instance in ((Chain, ARM),):  # the model's methods, on a fixture's instance
        for name, f in inspect.getmembers(instance, inspect.ismethod):
            if not name.startswith("_"):
                yield from _callable(f"{cls.__module__}.{cls.__name__}.{name}", f, fixtures_for(cls.__module__))


def _callable(key, f, fixtures):
    params = inspect.signature(f).parameters.values()
    required = [p.name for p in params
                if p.default is p.empty and p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)]
    optional = [p.name for p in params if p.default is not p.empty and p.name in OPTIONAL]
    if required and all(p in fixtures for p in required):
        yield key, f, {p: fixtures[p] for p in required}, {p: OPTIONAL[p] for p in optional}


FUNCTIONS = {key: (f, valid, optional) for key, f, valid, optional in public_functions()}


def test_the_sweep_covers_the_library():
    assert len(FUNCTIONS) >= 150, sorted(FUNCTIONS)


def probe(key, f, valid, optional=None):
    """Call ``f`` validly, then with each junk argument (and each of ``optional``'s keyword
    arguments given junk); raise on anything but a refusal by name or a finite result."""
    try:
        f(**valid)
    except SpringlabError:
        pass  # e.g. a configuration the fixture arm cannot balance: refused, by name
    for name in [*valid, *(optional or {})]:
        for junk in JUNK + EXTRA_JUNK.get(name, ()):
            try:
                out = f(**(valid | {name: junk}))
            except SpringlabError:
                continue
            if f.__name__ in RETURNS_NOTHING or out is None:
                continue
            try:
                values = np.asarray(out, dtype=float)
            except (TypeError, ValueError):
                continue  # not numbers (a table, a list of slots)
            assert np.all(np.isfinite(values)), f"{key}({name}={junk!r}) returned {out!r}"


@pytest.mark.parametrize("key", sorted(FUNCTIONS))
def test_junk_arguments_are_refused_by_name(key):
    probe(key, *FUNCTIONS[key])


def test_the_probe_catches_a_function_that_checks_nothing():
    def naive(chain, phi):
        return np.cos(np.asarray(phi, dtype=float)) * chain.n

    with pytest.raises((AttributeError, ValueError, TypeError, AssertionError)):
        probe("naive", naive, {"chain": ARM, "phi": [0.5]})

    def nan_through(phi):
        return np.asarray(phi, dtype=float) if not isinstance(phi, str) else 0.0

    with pytest.raises((AssertionError, TypeError)):
        probe("nan_through", nan_through, {"phi": [0.5]})


def test_the_probe_reaches_the_junk_that_once_got_through():
    """Each of these once failed inside numpy or the standard library. Written to refuse the
    common junk by name, as they did, they must still be caught: by the junk of their kind."""
    def number(name, value):
        if isinstance(value, bool) or not isinstance(value, int | float) or value != value:
            raise SpringlabError(f"{name} must be a number")
        return value

    def old_payload(mass):
        if mass is None or mass != mass:
            raise SpringlabError("payload mass must be >= 0 kg")
        if not (np.isfinite(mass) and mass >= 0):  # a string reaches numpy
            raise SpringlabError("payload mass must be >= 0 kg")
        return mass

    def old_random_angles(size):
        return np.zeros((int(number("size", size)), 3))  # numpy's "negative dimensions"

    def old_springs(springs):
        if not isinstance(springs, list) or not all(isinstance(x, Spring) for x in springs):
            raise SpringlabError("springs must be Spring objects")
        return float(springs[0].k * (1.0 + abs(springs[0].a)) ** 2)  # a Python float overflows

    def old_executor(chain, executor=None):
        if executor is not None and not callable(getattr(executor, "submit", None)):
            raise SpringlabError("executor must have submit")
        return executor.submit(len, [1]).result() if executor is not None else 1  # the class's unbound submit

    def old_C(C, C_max=None):
        C = number("C", C)
        if C_max is not None and number("C_max", C_max) < C:
            raise ValueError("no C in the search range")  # names nothing
        return C

    for f, valid, optional in ((old_payload, {"mass": 1.0}, {}), (old_random_angles, {"size": 4}, {}),
                               (old_springs, {"springs": list(SPRINGS)}, {}),
                               (old_executor, {"chain": ARM}, {"executor": None}),
                               (old_C, {"C": 200.0}, {"C_max": 300.0})):
        with pytest.raises((TypeError, ValueError, OverflowError, AttributeError)):
            probe(f.__name__, f, valid, optional)


def test_the_sweep_reaches_the_model_methods_and_the_keyword_arguments():
    assert {"springlab.model.chain.Chain.with_payload", "springlab.model.chain.Chain.random_angles"} <= set(FUNCTIONS)
    assert FUNCTIONS["springlab.mechanisms.dyad.synthesis.choose_C"][2] == {"C_max": 300.0}
    assert any(optional.get("executor", 0) is None for _f, _valid, optional in FUNCTIONS.values())
