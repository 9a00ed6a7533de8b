"""Paper 001's pseudobase arm: :mod:`~springlab.mechanisms.pseudobase.model`, :mod:`~springlab.mechanisms.pseudobase.subsystems` (route 1),
:mod:`~springlab.mechanisms.pseudobase.geometry` (route 2), :mod:`~springlab.mechanisms.pseudobase.simulation` (route 3, exudyn)."""
