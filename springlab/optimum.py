"""One result type for every optimiser in springlab: the dyad's minimax (paper 002) and
the planar arm's efficiency index (paper 003) both return an :class:`Optimum`.

>>> o = Optimum(design="a dyad", parameters={"r": 0.1}, objective="largest |M_ub| (N m)", value=0.5)
>>> o.value, o.parameters["r"]
(0.5, 0.1)
"""

from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["Optimum"]


@dataclass(frozen=True)
class Optimum:
    """The best design an optimiser found.

    :ivar design: what was chosen (a :class:`~springlab.mechanisms.dyad.model.Dyad`, a
        list of springs, ...)
    :ivar parameters: {name: value} of the free parameters at the optimum (SI units, or
        the ratio the name says)
    :ivar objective: what was optimised, with its unit and sense, e.g. 'largest |M_ub| (N m), minimised'
    :ivar value: the objective at the optimum, in its unit
    :ivar evaluations: objective evaluations the optimiser used (0 when not counted)
    :ivar bounds: {name: (low, high)} the free parameters were kept within
    :ivar settings: anything else the optimum depends on (a configuration's name, a
        stiffness limit, the fixed free length)
    """

    design: object
    parameters: dict
    objective: str
    value: float
    evaluations: int = 0
    bounds: dict = field(default_factory=dict)
    settings: dict = field(default_factory=dict)
