"""The papers' own mechanisms, each with one module per route it has:

* :mod:`~springlab.mechanisms.pseudobase` (paper 001): ``model``, ``subsystems`` (route 1), ``geometry``
  (route 2), ``simulation`` (route 3);
* :mod:`~springlab.mechanisms.dyad` (paper 002): ``model``, ``algebra`` (route 1), ``geometry`` (route 2),
  ``simulation`` (route 3), ``synthesis`` (the readings of the choice of C);
* :mod:`~springlab.mechanisms.planar` (paper 003): ``model``, ``quadratic`` (route 1), ``geometry`` (route 2),
  ``efficiency``, ``synthesis``;
* :mod:`~springlab.mechanisms.two_spring_arm` (paper 004): the two-spring arm's derivation, mapped onto the
  general chain so that the general routes 2 and 3 check it.
"""
