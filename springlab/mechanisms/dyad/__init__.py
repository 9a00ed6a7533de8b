"""Paper 002's crank-slider gravity compensator: :mod:`~springlab.mechanisms.dyad.model`, :mod:`~springlab.mechanisms.dyad.algebra` (route 1),
:mod:`~springlab.mechanisms.dyad.geometry` (route 2), :mod:`~springlab.mechanisms.dyad.simulation` (route 3, exudyn), :mod:`~springlab.mechanisms.dyad.synthesis`."""
