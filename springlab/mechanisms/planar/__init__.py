"""Paper 003's planar arm: :mod:`.model`, :mod:`.quadratic` (route 1, pseudo-stiffness
terms), :mod:`.geometry` (route 2), :mod:`.efficiency` (spring and system efficiency),
:mod:`.synthesis` (balancing equations and designs)."""
