"""Each paper's data as typed constants, with the table it came from, and the
registry of the notebooks that reproduce them (used by the site and the report).

A paper's key ("000" .. "004", the order in which the project took the papers up) is how
the code cites it, the key before the equation's own number. :data:`BY_KEY` maps a key to its
entry.

References
----------
001: P.-Y. Lin, W.-B. Shieh, D.-Z. Chen (2010), Design of a Gravity-Balanced General Spatial
Serial-Type Manipulator (cited in its key figure's caption).
002: Y. Zhang, V. Arakelian (2023), Design and Synthesis of the Gravity Compensator with a
Non-zero Length Spring (cited in its key figure's caption).
"""

PAPERS = {
    "juang2023_spatial_balance": {
        "key": "000",
        "authors": "C.-W. Juang, C.-S. Jhuang, D.-Z. Chen",
        "year": 2023,
        "title": "A novel spring gravity-balance method for spatial articulated manipulators without auxiliary links",
        "venue": "Mechanism and Machine Theory 191, 105497",
        "doi": "10.1016/j.mechmachtheory.2023.105497",
        "key_figure": "fig16_spatial.png",
        "key_caption": "Fig. 16 recomputed: the gravity, spring and total potential energy (J) along Table 4's "
                       "spatial trajectory; the total stays constant",
    },
    "lin2010_pseudobases": {
        "key": "001",
        "authors": "P.-Y. Lin, W.-B. Shieh, D.-Z. Chen",
        "year": 2010,
        "title": "Design of a Gravity-Balanced General Spatial Serial-Type Manipulator",
        "venue": "Journal of Mechanisms and Robotics 2, 031003",
        "doi": "10.1115/1.4001816",
        "key_figure": "fig9_energies.png",
        "key_caption": "Fig. 9 recomputed by direct geometry: the gravity, spring and total potential energy (J) of "
                       "the six-link arm along 001 Eq. (26)",
    },
    "springlab_design_your_arm": {
        "key": None,  # built on 000 and 003, not a paper
        "builds_on": ("000", "003"),  # the papers whose printed values its prose may quote
        "authors": "springlab, from papers 000 and 003",  # the book names them (springlab.workbench.prose)
        "year": 2026,
        "title": "Design springs for your own arm: ranked, verified designs, a tolerance study, an exudyn check",
        "venue": "",
        "doi": None,
        "key_figure": "best_design.png",
        "key_caption": "The best design for the example arm, drawn at a random pose: the links, the ground column "
                       "and each spring between its attachment points",
    },
    "springlab_real_arms": {
        "key": None,  # springlab's general model, not a paper
        "authors": "springlab",
        "year": 2026,
        "title": "Real arms: springs for robots from their published URDFs (UR5, Panda, SO-101)",
        "venue": "",
        "doi": None,
        "key_figure": "panda.png",
        "key_caption": "The Franka Panda from its published URDF with the ideal springs of its best design "
                       "(the chapter gives their share of each joint's peak): front, side and top views",
    },
    "zhang2023_dyad": {
        "key": "002",
        "authors": "Y. Zhang, V. Arakelian",
        "year": 2023,
        "title": "Design and Synthesis of the Gravity Compensator with a Non-zero Length Spring",
        "venue": "",
        "doi": None,  # the paper's text gives none
        "key_figure": "exudyn_drive.png",
        "key_caption": "Design B driven slowly in exudyn: the input torque (N m) against the link angle (deg) "
                       "equals virtual work's unbalanced moment, not the printed 002 Eqs. (20)-(30)",
    },
    "juang2022_spring_efficiency": {
        "key": "003",
        "authors": "C.-W. Juang, C.-S. Jhuang, D.-Z. Chen",
        "year": 2022,
        "title": "Spring efficiency assessment and efficient use of spring methods of statically balanced planar "
                 "serial manipulators with revolute joints only",
        "venue": "Mechanical Sciences (2022)",
        "doi": None,  # the text does not print the paper's own DOI
        "key_figure": "fig7a_attachments.png",
        "key_caption": "Fig. 7a recomputed: the efficiency index over the attachment ratios A_S(1,4) and A_S(2,4), "
                       "Table 4's design marked",
    },
    "lenzo2017_two_spring_arm": {
        "key": "004",
        "authors": "B. Lenzo",
        "year": 2017,
        "title": "Gravity balancing of a spatial serial 4-dof arm without auxiliary links using minimum number of springs",
        "venue": "AIMETA 2017",
        "doi": None,  # the text prints none; it gives the archive's address below
        "url": "http://shura.shu.ac.uk/16806/",
        "key_figure": "fig5_layouts.png",
        "key_caption": "The four layouts of Fig. 5 drawn to scale: the two springs of each on the illustrative arm",
    },
}
"""Notebook stem -> the paper it reproduces (authors, year, title, venue, DOI) and its key figure
(a file in ``figures/<stem>/``, with a caption that is also its alt text)."""

BY_KEY = {entry["key"]: {"notebook": stem, **entry} for stem, entry in PAPERS.items() if entry["key"]}
"""Paper key ("000".."004") -> its registry entry and notebook stem."""
