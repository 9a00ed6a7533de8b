"""Paper 001's pseudobase arm: :mod:`.model`, :mod:`.subsystems` (route 1),
:mod:`.geometry` (route 2), :mod:`.simulation` (route 3, exudyn)."""
