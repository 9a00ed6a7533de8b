"""Spring designs for an arm (paper 000's method and its extensions): the rules R1-R6
(:mod:`~springlab.design.rules`), solving 000 Eqs. (39) and searching for a design (:mod:`~springlab.design.solve`), which
configurations can balance at all (:mod:`~springlab.design.feasibility`), designs ranked for a user's arm
(:mod:`~springlab.design.rank`), fewer springs and the n - 1 ground springs (:mod:`~springlab.design.ground`), the methods
compared (:mod:`~springlab.design.methods`), the spatial system spring efficiency (:mod:`~springlab.design.efficiency`) and
their sensitivity to manufacturing tolerances (:mod:`~springlab.design.tolerance`).

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
"""
