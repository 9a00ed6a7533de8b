"""springlab: spring gravity balancing of robot arms, reproduced from the papers.

The library is built around one quantity, the total potential energy of an arm
(gravity plus springs) as a function of its pose, evaluated by independent routes:

1. the papers' algebra (:mod:`springlab.quadratic`, the quadratic form of
   Juang, Jhuang, Chen 2023);
2. direct geometry (:mod:`springlab.energy`): place every body and attachment
   point in space and sum ``m g h`` and ``k l**2 / 2``.

Units are SI throughout: metres, kilograms, newtons, joules, radians.
"""

from springlab.chain import UP, Chain, random_directions, serial_chain
from springlab.errors import SpringlabError, UnbalanceableError
from springlab.springs import Spring

__all__ = [
    "Chain",
    "serial_chain",
    "random_directions",
    "UP",
    "Spring",
    "SpringlabError",
    "UnbalanceableError",
]
__version__ = "0.1.0"
