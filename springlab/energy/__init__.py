"""The total potential energy of a general serial chain by three independent routes:

* :mod:`~springlab.energy.quadratic`, route 1: the papers' algebra, X^T (G + sum K_S) X (000 Eqs. 8-29);
* :mod:`~springlab.energy.geometry`, route 2: direct geometry, sum m g h + k |AB|^2 / 2;
* :mod:`~springlab.energy.simulation`, route 3: exudyn (with the helpers of :mod:`~springlab.energy.multibody`).

Routes 2 and 3 never import route 1, directly or through a helper (an import contract in
``pyproject.toml``, run by the tests). This package's ``__init__`` imports none of them.

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
"""
