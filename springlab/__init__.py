"""springlab: spring gravity balancing of robot arms, reproduced from the papers.

The library is built around one quantity, the total potential energy of an arm
(gravity plus springs) as a function of its pose, evaluated by three independent
routes that share no formula (an import contract in ``pyproject.toml`` says so):

1. the papers' algebra, :mod:`springlab.energy.quadratic` (the quadratic form of
   Juang, Jhuang, Chen 2023, paper 000);
2. direct geometry, :mod:`springlab.energy.geometry`: place every body and attachment
   point in space and sum ``m g h`` and ``k l**2 / 2``;
3. multibody simulation in exudyn, :mod:`springlab.energy.simulation`.

The packages, from the bottom up::

    model/       the arm (chain, rotations, springs, trajectories, arm files)
    energy/      the three routes for the general chain
    mechanisms/  the papers' own mechanisms (pseudobase 001, dyad 002, planar 003,
                 two-spring arm 004), one module per route each
    design/      rules, solving, feasibility, ranking and tolerance of spring designs
    papers/      each paper's printed data
    workbench/   claims, plotting, the notebook runner, the site and the command line

>>> import springlab
>>> arm = springlab.serial_chain(r=[0.4, 0.3], d=[0.2, 0.15], m=[2.0, 1.0])
>>> arm.n
3

Units are SI throughout: metres, kilograms, newtons, joules, radians.
"""

import importlib

from springlab.errors import (
    AttachmentError,
    GeometryError,
    SearchExhaustedError,
    SolverError,
    SpringlabError,
    UnbalanceableError,
)
from springlab.model.chain import UP, Chain, random_directions, serial_chain
from springlab.model.springs import Spring

# Loaded on first use (PEP 562), so that importing one route, e.g. springlab.energy.geometry,
# does not load another through this package's __init__, and the command line starts fast.
_LAZY = {
    "quadratic": ("springlab.energy.quadratic", None),
    "geometry": ("springlab.energy.geometry", None),
    "simulation": ("springlab.energy.simulation", None),
    "SpringSpec": ("springlab.design.solve", "SpringSpec"),
    "solve_design": ("springlab.design.solve", "solve_design"),
    "design_arm": ("springlab.design.rank", "design_arm"),
    "load_arm": ("springlab.model.armfile", "load_arm"),
}


LAZY_EXPORTS = _LAZY
"""Where each lazily loaded export lives: name -> (module, attribute or None for the module)."""


def __getattr__(name):
    if name not in _LAZY:
        raise AttributeError(f"module 'springlab' has no attribute {name!r}")
    module, attribute = _LAZY[name]
    value = importlib.import_module(module)
    return value if attribute is None else getattr(value, attribute)


def __dir__():
    return sorted(set(globals()) | set(_LAZY))


__all__ = [
    "quadratic",
    "geometry",
    "simulation",
    "Chain",
    "serial_chain",
    "random_directions",
    "UP",
    "Spring",
    "SpringSpec",
    "solve_design",
    "design_arm",
    "load_arm",
    "SpringlabError",
    "UnbalanceableError",
    "GeometryError",
    "AttachmentError",
    "SolverError",
    "SearchExhaustedError",
]
__version__ = "0.1.0"
