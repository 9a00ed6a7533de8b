"""Paper 003's planar arm: :mod:`~springlab.mechanisms.planar.model`, :mod:`~springlab.mechanisms.planar.quadratic` (route 1, pseudo-stiffness
terms), :mod:`~springlab.mechanisms.planar.geometry` (route 2), :mod:`~springlab.mechanisms.planar.efficiency` (spring and system efficiency),
:mod:`~springlab.mechanisms.planar.synthesis` (balancing equations and designs)."""
