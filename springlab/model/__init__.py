"""The arm, shared by every route: the serial chain and its poses (:mod:`.chain`), rotations
(:mod:`.rotations`), zero-free-length springs and their attachment checks (:mod:`.springs`),
trajectories (:mod:`.trajectories`) and arm files (:mod:`.armfile`).

The model imports nothing above it (an import contract in ``pyproject.toml``)."""
