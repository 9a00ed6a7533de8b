"""The arm, shared by every route: the serial chain and its poses (:mod:`~springlab.model.chain`), rotations
(:mod:`~springlab.model.rotations`), zero-free-length springs and their attachment checks (:mod:`~springlab.model.springs`),
trajectories (:mod:`~springlab.model.trajectories`) and arm files (:mod:`~springlab.model.armfile`).

The model imports nothing above it (an import contract in ``pyproject.toml``)."""
