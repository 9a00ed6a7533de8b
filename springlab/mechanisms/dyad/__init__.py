"""Paper 002's crank-slider gravity compensator: :mod:`.model`, :mod:`.algebra` (route 1),
:mod:`.geometry` (route 2), :mod:`.simulation` (route 3, exudyn), :mod:`.synthesis`."""
