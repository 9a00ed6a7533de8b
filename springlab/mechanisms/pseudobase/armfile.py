"""An arm described by its DH frames, for paper 001's pseudobase method: ``load_dh_arm(path)``.

The form of 001 Table 1 and Table 2, in a TOML or JSON arm file, every quantity a bare SI
number or a string with a unit (read by pint, :func:`springlab.model.armfile.parse_quantity`)::

    name = "my arm"
    g = "9.81 m/s^2"
    auxiliary_d1 = "0.1 m"         # d^_1: the auxiliary chain is the primary one lifted along joint 1

    [[frame]]                      # frame i on link i, standard DH: joint i turns theta_i about z_{i-1}
    d = "0 m"
    a = "0.1 m"
    alpha = "90 deg"
    mass = "0 kg"                  # link i's mass
    com = [0, 0, 0]                # s_i: its centre of mass from O_i, in frame i (m)

    [[frame]]
    d = "0 m"
    a = "0.4 m"
    alpha = "0 deg"
    mass = "23.21 kg"
    com = ["-0.20 m", "0 m", "-0.1 m"]
    [frame.module]                 # this link's RSSR module and spring (001 Sections 4-5, Tables 2-3)
    auxiliary_mass = "2.38 kg"     # m^_i
    auxiliary_com = ["-0.17 m", "0.07 m", "0.06 m"]   # s^_i, from Ô_i in frame î (m)
    pseudobase_mass = "0.47 kg"    # m*_i
    joint_centre = ["-0.3 m", "0.1 m", "-0.1 m"]     # c_i: the spherical joint C_i from O_i, frame i (m)
    stiffness = "20 kN/m"          # K_i, chosen
    l_CA = "0.1 m"                 # l_CA,i, chosen; l_CB,i follows from 001 Eq. (16)

The links with a module must be the last ones, from link 1 or 2 on (link 2 when joint 1 is
vertical: link 1's weight never changes the energy), as :class:`~springlab.mechanisms.pseudobase.model.PseudobaseArm` requires.
``notebooks/arms/paper001_arm.toml`` is paper 001's example arm in this form.

References
----------
Lin, P.-Y., Shieh, W.-B., Chen, D.-Z. (2010). Design of a gravity-balanced general spatial
serial-type manipulator. Journal of Mechanisms and Robotics 2(3), 031003. doi:10.1115/1.4001816
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from springlab.errors import SpringlabError
from springlab.mechanisms.pseudobase.model import (
    DH,
    Equilibrator,
    PseudobaseArm,
    aux_offset_from_dh,
)
from springlab.model.armfile import parse_quantity, read_arm_data

_FRAME = {"d", "a", "alpha", "mass", "com", "module"}
_MODULE = {"auxiliary_mass", "auxiliary_com", "pseudobase_mass", "joint_centre", "stiffness", "l_CA"}


@dataclass(frozen=True)
class DHArm:
    """A DH arm file read: the arm with its modules, and each module's chosen K (N/m) and l_CA (m)."""

    name: str
    source: str
    arm: PseudobaseArm
    K: tuple
    l_CA: tuple

    def design(self) -> tuple[Equilibrator, ...]:
        """One spring per module, l_CB from 001 Eq. (16)
        (:func:`springlab.mechanisms.pseudobase.subsystems.design_equilibrators`)."""
        from springlab.mechanisms.pseudobase.subsystems import design_equilibrators

        return design_equilibrators(self.arm, self.K, self.l_CA)


def _vector(value, where: str) -> np.ndarray:
    if not (isinstance(value, list) and len(value) == 3):
        raise SpringlabError(f"{where} = {value!r}: give three lengths [x, y, z], e.g. ['0.1 m', '0 m', '-0.05 m']")
    return np.array([parse_quantity(v, "length", f"{where}[{k}]") for k, v in enumerate(value)])


def _need(table: dict, key: str, where: str):
    if key not in table:
        raise SpringlabError(f"{where}: missing field {key!r}")
    return table[key]


def dh_arm_from_dict(data: dict, *, source: str = "arm") -> DHArm:
    """Validate a parsed DH arm description (see the module docstring) into a :class:`DHArm`."""
    if not isinstance(data, dict):
        raise SpringlabError(f"{source}: expected a table of fields, got {type(data).__name__}")
    unknown = sorted(set(data) - {"name", "g", "auxiliary_d1", "frame"})
    if unknown:
        raise SpringlabError(f"{source}: unknown field(s) {unknown} (known: name, g, auxiliary_d1, frame)")
    frames = data.get("frame")
    if not isinstance(frames, list) or not frames:
        raise SpringlabError(f"{source}: 'frame' must be a list of DH frame tables ([[frame]] in TOML), one per joint")
    d, a, alpha, m, s = [], [], [], [], []
    modules, m_hat, s_hat, m_star, c, K, l_CA = [], [], [], [], [], [], []
    for i, frame in enumerate(frames, start=1):
        where = f"{source}: frame {i}"
        if not isinstance(frame, dict):
            raise SpringlabError(f"{where}: expected a table with d, a, alpha, mass, com")
        extra = sorted(set(frame) - _FRAME)
        if extra:
            raise SpringlabError(f"{where}: unknown field(s) {extra} (known: {', '.join(sorted(_FRAME))})")
        d.append(parse_quantity(_need(frame, "d", where), "length", f"{where}: d"))
        a.append(parse_quantity(_need(frame, "a", where), "length", f"{where}: a"))
        alpha.append(parse_quantity(_need(frame, "alpha", where), "angle", f"{where}: alpha"))
        m.append(parse_quantity(_need(frame, "mass", where), "mass", f"{where}: mass"))
        if m[-1] < 0:
            raise SpringlabError(f"{where}: mass = {m[-1]:g} kg must be >= 0")
        s.append(_vector(_need(frame, "com", where), f"{where}: com"))
        module = frame.get("module")
        if module is None:
            m_hat.append(0.0), s_hat.append(np.zeros(3)), m_star.append(0.0), c.append(np.zeros(3))
            continue
        where = f"{where}: module"
        if not isinstance(module, dict):
            raise SpringlabError(f"{where}: expected a table ([frame.module] in TOML)")
        extra = sorted(set(module) - _MODULE)
        missing = sorted(_MODULE - set(module))
        if extra or missing:
            raise SpringlabError(f"{where}: " + (f"unknown field(s) {extra}" if extra else f"missing field(s) {missing}")
                                 + f" (fields: {', '.join(sorted(_MODULE))})")
        modules.append(i)
        m_hat.append(parse_quantity(module["auxiliary_mass"], "mass", f"{where}: auxiliary_mass"))
        s_hat.append(_vector(module["auxiliary_com"], f"{where}: auxiliary_com"))
        m_star.append(parse_quantity(module["pseudobase_mass"], "mass", f"{where}: pseudobase_mass"))
        c.append(_vector(module["joint_centre"], f"{where}: joint_centre"))
        K.append(parse_quantity(module["stiffness"], "stiffness", f"{where}: stiffness"))
        l_CA.append(parse_quantity(module["l_CA"], "length", f"{where}: l_CA"))
        for name, value, unit in (("auxiliary_mass", m_hat[-1], "kg"), ("pseudobase_mass", m_star[-1], "kg"),
                                  ("stiffness", K[-1], "N/m"), ("l_CA", l_CA[-1], "m")):
            if not value > 0:
                raise SpringlabError(f"{where}: {name} = {value:g} {unit} must be > 0")
    if not modules:
        raise SpringlabError(f"{source}: no frame has a module ([frame.module]): paper 001's method balances "
                             "each link by its module's spring")
    g = parse_quantity(data.get("g", 9.81), "acceleration", f"{source}: g")
    lift = parse_quantity(_need(data, "auxiliary_d1", source), "length", f"{source}: auxiliary_d1")
    try:
        primary = DH(d=d, a=a, alpha=alpha)
        aux = DH(d=[d[0] + lift, *d[1:]], a=a, alpha=alpha)
        arm = PseudobaseArm(dh=primary, m=m, s=s, modules=tuple(modules), m_hat=m_hat, s_hat=s_hat,
                            m_star=m_star, c=c, aux_offset=aux_offset_from_dh(primary, aux), g=g)
    except SpringlabError as err:
        raise SpringlabError(f"{source}: {err}") from None
    return DHArm(str(data.get("name", source)), source, arm, tuple(K), tuple(l_CA))


def load_dh_arm(path) -> DHArm:
    """Read a DH arm file (.toml or .json, see the module docstring) into a :class:`DHArm`."""
    path, data = read_arm_data(path)
    if path.suffix == ".urdf":
        raise SpringlabError(f"{path}: a URDF file is read by springlab.model.armfile.load_arm")
    return dh_arm_from_dict(data, source=str(path))
