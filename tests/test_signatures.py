"""Every public function of the library whose arguments a fixture can fill is called once
validly, then once per argument with junk in its place: each junk argument must be refused
with a SpringlabError (or accepted with a finite result), never fail inside numpy, scipy or
sympy with a message that names nothing. The simulation modules (exudyn) and the workbench
are left out: their inputs are checked by tests/test_refusals.py."""

from __future__ import annotations

import importlib
import inspect
import math
import pkgutil

import numpy as np
import pytest
from test_refusals import ARM, COMP, DYAD, PB, SPRINGS, WORKSPACE, X, spec

import springlab
from springlab.errors import SpringlabError

FIXTURES = {"chain": ARM, "springs": SPRINGS, "X": X, "comp": COMP, "dyad": DYAD, "workspace": WORKSPACE,
            "slots": ["S(1,2)", "S(1,4)", "S(2,4)", "S(3,4)(-,-)"], "n": 3, "seed": 0, "samples": 5,
            "phi": [0.5, 1.0], "theta": [[0.1, 0.2, 0.3]], "q": np.zeros((1, PB.n)), "spring": SPRINGS[0],
            "configuration": ["S(1,2)"], "count": 2, "spec": spec(), "spec_or_chain": ARM,
            "rng": 0, "step": 30.0, "angles": np.zeros((1, 3, 3)), "duration": 1.0}
JUNK = ("junk", math.nan, None)
SKIP = ("springlab.workbench", "springlab.energy.simulation", "springlab.energy.multibody",
        "springlab.mechanisms.pseudobase.simulation", "springlab.mechanisms.dyad.simulation")
RETURNS_NOTHING = {"check_attachments"}  # returns None: nothing to test for finiteness


def public_functions():
    for info in pkgutil.walk_packages(springlab.__path__, "springlab."):
        if info.name.startswith(SKIP):
            continue
        module = importlib.import_module(info.name)
        for name, f in vars(module).items():
            if name.startswith("_") or not inspect.isfunction(f) or f.__module__ != info.name:
                continue
            required = [p.name for p in inspect.signature(f).parameters.values()
                        if p.default is p.empty and p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)]
            if required and all(p in FIXTURES for p in required):
                yield f"{info.name}.{name}", f, required


FUNCTIONS = {key: (f, required) for key, f, required in public_functions()}


def test_the_sweep_covers_the_library():
    assert len(FUNCTIONS) >= 60, sorted(FUNCTIONS)


def probe(key, f, required):
    """Call ``f`` validly, then with each junk argument; raise on anything but a refusal by name
    or a finite result."""
    valid = {p: FIXTURES[p] for p in required}
    try:
        f(**valid)
    except SpringlabError:
        pass  # e.g. a configuration the fixture arm cannot balance: refused, by name
    for name in required:
        for junk in JUNK:
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
        probe("naive", naive, ["chain", "phi"])

    def nan_through(phi):
        return np.asarray(phi, dtype=float) if not isinstance(phi, str) else 0.0

    with pytest.raises((AssertionError, TypeError)):
        probe("nan_through", nan_through, ["phi"])
