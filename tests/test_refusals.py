"""Bad input across the public entry points: each call raises the stated springlab error,
and its message names the parameter (the fragment). None may return a NaN, hang or fail
inside numpy, sympy or exudyn with a message that names nothing."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from springlab import Spring, random_directions, serial_chain
from springlab.design import efficiency as deff
from springlab.design import feasibility, ground, rank, rules, solve, tolerance
from springlab.design.rules import SpringSlot
from springlab.design.solve import SpringSpec
from springlab.energy import geometry, quadratic, simulation
from springlab.energy.multibody import SimSettings
from springlab.errors import (
    AttachmentError,
    GeometryError,
    SearchExhaustedError,
    SpringlabError,
    UnbalanceableError,
)
from springlab.mechanisms import two_spring_arm as lenzo
from springlab.mechanisms.dyad import algebra as dyad_algebra
from springlab.mechanisms.dyad import geometry as dyad_geometry
from springlab.mechanisms.dyad import simulation as dyad_simulation
from springlab.mechanisms.dyad import synthesis as dyad_synthesis
from springlab.mechanisms.dyad.model import Compensator, Dyad
from springlab.mechanisms.planar import efficiency as planar_eff
from springlab.mechanisms.planar import geometry as planar_geometry
from springlab.mechanisms.planar.model import PlanarArm, PlanarSpring, Workspace
from springlab.mechanisms.pseudobase import geometry as pb_geometry
from springlab.mechanisms.pseudobase.model import DH, Equilibrator
from springlab.mechanisms.pseudobase.subsystems import design_equilibrators
from springlab.model import trajectories
from springlab.model.armfile import ArmSpec, arm_from_dict, parse_quantity
from springlab.papers import juang2022, lin2010

ARM = serial_chain([0.3, 0.24, 0.2], [0.15, 0.12, 0.1], [4.0, 3.2, 2.8], g=9.8)
SPRINGS = (Spring(1, 2, 0.1, 0.15, 300.0), Spring(2, 4, -0.1, 0.1, 200.0))
X = random_directions(4, 5, 0)
COMP = Compensator(G=20.0, s=0.3, k=1000.0, l0=0.6)
DYAD = Dyad(r=0.13, l=0.53, beta=0.0)
PLANAR = juang2022.ARM
WORKSPACE = Workspace(low=(0, -90, -90), high=(180, 90, 90))
PB = lin2010.arm()
LINK = {"length": 0.3, "com": 0.15, "mass": 2.0}


def arm_file(**changes):
    data = {"link": [dict(LINK), dict(LINK)]}
    for key, value in changes.items():
        if key.startswith("link_"):
            data["link"][0][key[5:]] = value
        elif value is None:
            data.pop(key, None)
        else:
            data[key] = value
    return data


def spec(**changes):
    base = dict(name="arm", r=(0.3, 0.3), d=(0.15, 0.15), m=(2.0, 2.0), joints=("spherical", "spherical"))
    return ArmSpec(**{**base, **changes})


CASES = {
    # --- the chain (model layer) ---
    "chain r string": (lambda: serial_chain("0.3", [0.1], [1.0]), SpringlabError, "r must be"),
    "chain d None": (lambda: serial_chain([0.3], [None], [1.0]), SpringlabError, "d must be"),
    "chain m nested ragged": (lambda: serial_chain([0.3, 0.2], [0.1, 0.1], [[1.0], [1.0, 2.0]]), SpringlabError, "m must be"),
    "chain g string": (lambda: serial_chain([0.3], [0.1], [1.0], g="9.81"), SpringlabError, "g must be"),
    "chain g zero": (lambda: serial_chain([0.3], [0.1], [1.0], g=0.0), SpringlabError, "g must be"),
    "chain g inf": (lambda: serial_chain([0.3], [0.1], [1.0], g=math.inf), SpringlabError, "g must be"),
    "chain mass overflow": (lambda: serial_chain([0.3], [0.1], [1e307], g=1e10), SpringlabError, "overflow"),
    "chain empty": (lambda: serial_chain([], [], []), SpringlabError, "r must be a non-empty"),
    "chain joints string": (lambda: serial_chain([0.3], [0.1], [1.0], joints="spherical"), SpringlabError, "joints"),
    "chain joint zero axis": (lambda: serial_chain([0.3], [0.1], [1.0], joints=[[0, 0, 0]]), SpringlabError, "axis of joint 2"),
    "chain joint bad word": (lambda: serial_chain([0.3], [0.1], [1.0], joints=["revolute"]), SpringlabError, "joint 2"),
    "payload negative": (lambda: ARM.with_payload(-1.0), SpringlabError, "payload"),
    "payload nan": (lambda: ARM.with_payload(math.nan), SpringlabError, "payload"),
    "link index": (lambda: ARM.length(7), SpringlabError, "link index"),
    "angles nan": (lambda: ARM.frames(np.full((2, 3, 3), np.nan)), SpringlabError, "angles"),
    "angles shape": (lambda: ARM.frames(np.zeros((2, 2, 3))), SpringlabError, "angles must have shape"),
    "angles strings": (lambda: ARM.frames([["a"]]), SpringlabError, "angles"),
    "random directions n": (lambda: random_directions(1, 5), SpringlabError, "n must be"),
    "random directions size float": (lambda: random_directions(3, 2.5), SpringlabError, "size must be"),
    "random directions billion": (lambda: random_directions(4, 10**10), SpringlabError, "memory"),
    # --- springs ---
    "spring float index": (lambda: Spring(1.5, 3, 0.1, 0.1, 10.0), SpringlabError, "index i"),
    "spring string index": (lambda: Spring("1", 3, 0.1, 0.1, 10.0), SpringlabError, "index i"),
    "spring k string": (lambda: Spring(1, 3, 0.1, 0.1, "10"), SpringlabError, "k of S"),
    "spring k None": (lambda: Spring(1, 3, 0.1, 0.1, None), SpringlabError, "k of S"),
    "spring b inf": (lambda: Spring(1, 3, 0.1, math.inf, 10.0), SpringlabError, "b of S"),
    "spring free length nan": (lambda: Spring(1, 3, 0.1, 0.1, 10.0, math.nan), SpringlabError, "free_length"),
    "spring k overflow": (lambda: geometry.total_energy(ARM, [Spring(1, 2, 10.0, 10.0, 1e308)], X), SpringlabError, "overflows"),
    "springs not a list": (lambda: geometry.total_energy(ARM, SPRINGS[0], X), SpringlabError, "springs must be"),
    "springs of strings": (lambda: geometry.total_energy(ARM, ["S(1,2)"], X), SpringlabError, "Spring objects"),
    "slot label unclosed": (lambda: rules.slot("S(1,4"), SpringlabError, "S\\(1,4"),
    "slot label letters": (lambda: rules.slot("S(a,b)(+,+)"), SpringlabError, "write S\\(i,j\\)"),
    "slot label pattern": (lambda: rules.slot("S(1,4)(+,0)"), SpringlabError, "S\\(1,4\\)\\(\\+,0\\)"),
    "slot not a string": (lambda: rules.slot(14), SpringlabError, "spring label"),
    "slot pattern": (lambda: SpringSlot(1, 3, "++"), SpringlabError, "pattern of S\\(1,3\\)"),
    "slot float index": (lambda: SpringSlot(1, 2.5), SpringlabError, "index j"),
    "spec pattern contradiction": (lambda: SpringSpec(1, 3, "(+,+)", a=-0.1), SpringlabError, "contradicts its pattern"),
    "spec k zero": (lambda: SpringSpec(1, 3, "(+,+)", k=0.0), SpringlabError, "k of S\\(1,3\\)"),
    "spec a string": (lambda: SpringSpec(1, 3, "(+,+)", a="0.1"), SpringlabError, "a of S\\(1,3\\)"),
    # --- route 1 and route 2 ---
    "poses zero": (lambda: geometry.total_energy(ARM, SPRINGS, np.zeros((0, 4, 3))), SpringlabError, "poses"),
    "poses wrong n": (lambda: geometry.total_energy(ARM, SPRINGS, random_directions(3, 2, 0)), SpringlabError, "shape"),
    "poses nan quadratic": (lambda: quadratic.quadratic_energy(ARM, SPRINGS, np.full((2, 4, 3), np.nan)), SpringlabError, "NaN"),
    "poses strings": (lambda: geometry.total_energy(ARM, SPRINGS, "up"), SpringlabError, "poses"),
    "chain not a chain": (lambda: quadratic.energy_matrix("arm", SPRINGS), SpringlabError, "chain must be"),
    "holding torques zero poses": (lambda: geometry.holding_torques(ARM, SPRINGS, np.zeros((0, 4, 3))), SpringlabError, "poses"),
    "efficiency zero poses": (lambda: deff.spatial_system_efficiency(ARM, SPRINGS, np.zeros((0, 4, 3))), SpringlabError, "poses"),
    # --- the designer ---
    "find restarts negative": (lambda: solve.find_design(ARM, ["S(1,2)"], restarts=-1), SpringlabError, "restarts"),
    "find restarts float": (lambda: solve.find_design(ARM, ["S(1,2)"], restarts=2.5), SpringlabError, "restarts"),
    "find max stiffness zero": (lambda: solve.find_design(ARM, ["S(1,2)"], max_stiffness=0.0), SpringlabError, "max_stiffness"),
    "find max extension zero": (lambda: solve.find_design(ARM, ["S(1,2)"], max_extension=0.0), SpringlabError, "max_extension"),
    "find max extension nan": (lambda: solve.find_design(ARM, ["S(1,2)"], max_extension=math.nan), SpringlabError, "max_extension"),
    "find slots empty": (lambda: solve.find_design(ARM, []), SpringlabError, "slots is empty"),
    "find slots beyond chain": (lambda: solve.find_design(ARM, ["S(1,5)"]), SpringlabError, "S\\(1,5\\)"),
    "find seed negative": (lambda: solve.find_design(ARM, ["S(1,2)"], seed=-3), SpringlabError, "seed"),
    "find tol zero": (lambda: solve.find_design(ARM, ["S(1,2)"], tol=0.0), SpringlabError, "tol"),
    "find exhausted": (lambda: solve.find_design(ARM, ["S(1,2)", "S(1,4)", "S(2,4)(-,-)", "S(3,4)(-,-)"], restarts=0),
                       SearchExhaustedError, "restarts"),
    "relaxation slots string": (lambda: solve.relaxation_margin(ARM, "S(1,2)"), SpringlabError, "slots must be"),
    "solve design specs": (lambda: solve.solve_design(ARM, ["S(1,2)"]), SpringlabError, "SpringSpec"),
    "solve design max extension": (lambda: solve.solve_design(ARM, [SpringSpec(1, 2)], max_extension=-1.0),
                                   SpringlabError, "max_extension"),
    "design_for restarts": (lambda: solve.design_for(ARM, restarts=-1), SpringlabError, "restarts"),
    "design_for exhausted": (lambda: solve.design_for(ARM, restarts=0), SearchExhaustedError, "restarts = 0"),
    "enumerate n float": (lambda: list(rules.iter_configurations(3.5)), SpringlabError, "n \\(links"),
    "enumerate n string": (lambda: list(rules.iter_configurations("4")), SpringlabError, "n \\(links"),
    "verdict n": (lambda: rules.verdict(0, ["S(1,2)"]), SpringlabError, "n \\(links"),
    "verdict n too large": (lambda: rules.verdict(8, ["S(1,2)"]), SpringlabError, "rule_violations"),
    "enumeration time limit": (lambda: rules.enumerate_configurations(7, time_limit=0.2), SearchExhaustedError,
                               "time_limit = 0.2 s"),
    "enumeration n huge": (lambda: rules.enumerate_configurations(10**6), SpringlabError, "above 10000"),
    "design_arm max designs zero": (lambda: rank.design_arm(spec(), max_designs=0), SpringlabError, "max_designs"),
    "design_arm method": (lambda: rank.design_arm(spec(), method="magic"), SpringlabError, "method"),
    "design_arm time limit": (lambda: rank.design_arm(spec(), time_limit=0), SpringlabError, "time_limit"),
    "design_arm max configurations": (lambda: rank.design_arm(spec(), max_configurations=0), SpringlabError,
                                      "max_configurations"),
    "design_arm restarts": (lambda: rank.design_arm(spec(), restarts=None), SpringlabError, "restarts"),
    "design_arm force starts": (lambda: rank.design_arm(spec(), force_starts=0), SpringlabError, "force_starts"),
    "design_arm missing file": (lambda: rank.design_arm("/nonexistent/arm.toml"), SpringlabError, "does not exist"),
    "random poses zero samples": (lambda: rank.random_poses(ARM, 0, 1), SpringlabError, "samples"),
    "random poses billion": (lambda: rank.random_poses(ARM, 10**9, 1), SpringlabError, "memory"),
    "verify one pose": (lambda: rank.verify(ARM, SPRINGS, X[:1]), SpringlabError, "samples >= 2"),
    "ground springs n": (lambda: rank.ground_springs(1), SpringlabError, "n \\(links"),
    "tolerance negative": (lambda: tolerance.Tolerances(stiffness=-0.1), SpringlabError, "stiffness"),
    "tolerance string": (lambda: tolerance.Tolerances(attachment="1 mm"), SpringlabError, "attachment"),
    # --- arm descriptions ---
    "spec samples one": (lambda: spec(samples=1), SpringlabError, "samples"),
    "spec samples billion": (lambda: spec(samples=10**9), SpringlabError, "memory"),
    "spec seed negative": (lambda: spec(seed=-1), SpringlabError, "seed"),
    "spec max stiffness zero": (lambda: spec(max_stiffness=0.0), SpringlabError, "max_stiffness"),
    "spec max attachment negative": (lambda: spec(max_attachment=-0.1), SpringlabError, "max_attachment"),
    "spec payload nan": (lambda: spec(payload=math.nan), SpringlabError, "payload"),
    "spec g zero": (lambda: spec(g=0.0), SpringlabError, "g must be"),
    "spec d off link": (lambda: spec(d=(0.15, 0.5)), SpringlabError, "d_3"),
    "spec joints short": (lambda: spec(joints=("spherical",)), SpringlabError, "joints"),
    "spec name": (lambda: spec(name=None), SpringlabError, "name"),
    "file samples one": (lambda: arm_from_dict(arm_file(workspace={"samples": 1})), SpringlabError, "samples"),
    "file samples float": (lambda: arm_from_dict(arm_file(workspace={"samples": 2.5})), SpringlabError, "samples"),
    "file unit": (lambda: arm_from_dict(arm_file(link_length="30 smoots")), SpringlabError, "link 2: length"),
    "file unit of wrong kind": (lambda: arm_from_dict(arm_file(link_mass="2 m")), SpringlabError, "link 2: mass"),
    "file missing mass": (lambda: arm_from_dict({"link": [{"length": 0.3, "com": 0.1}]}), SpringlabError, "mass"),
    "file extra field": (lambda: arm_from_dict(arm_file(colour="red")), SpringlabError, "colour"),
    "file link not a table": (lambda: arm_from_dict({"link": [0.3]}), SpringlabError, "link 2"),
    "file no links": (lambda: arm_from_dict({"link": []}), SpringlabError, "link"),
    "file huge integer": (lambda: arm_from_dict(arm_file(link_mass=10**400)), SpringlabError, "link 2: mass"),
    "file bool length": (lambda: arm_from_dict(arm_file(link_length=True)), SpringlabError, "link 2: length"),
    "file joint of bools": (lambda: arm_from_dict(arm_file(link_joint=[True, 0, 0])), SpringlabError, "joint"),
    "file limits zero": (lambda: arm_from_dict(arm_file(limits={"max_stiffness": 0})), SpringlabError, "max_stiffness"),
    "file payload negative": (lambda: arm_from_dict(arm_file(payload={"mass": "-1 kg"})), SpringlabError, "payload"),
    "quantity nan": (lambda: parse_quantity("nan m", "length", "x"), SpringlabError, "x ="),
    "quantity list": (lambda: parse_quantity([1, 2], "length", "x"), SpringlabError, "x ="),
    # --- paper 001's pseudobases ---
    "dh strings": (lambda: DH(d=["a"], a=[0.1], alpha=[0.0]), SpringlabError, "d"),
    "dh angles nan": (lambda: PB.dh.frames(np.full(PB.n, np.nan)), SpringlabError, "joint angles"),
    "pseudobase zero poses": (lambda: pb_geometry.energies(PB, [], np.zeros((0, PB.n))), SpringlabError, "poses"),
    # --- paper 002's dyad ---
    "dyad phi nan": (lambda: dyad_geometry.energies(COMP, DYAD, [0.1, math.nan]), SpringlabError, "phi"),
    "dyad phi empty": (lambda: dyad_geometry.max_unbalanced(COMP, DYAD, []), SpringlabError, "phi"),
    "dyad phi string": (lambda: dyad_geometry.unbalanced_moment(COMP, DYAD, "90 deg"), SpringlabError, "phi"),
    "dyad dead centre": (lambda: dyad_geometry.unbalanced_moment(COMP, Dyad(0.13, 0.13, 0.0), np.pi / 2),
                         GeometryError, "cannot close"),
    "dyad beta nan": (lambda: Dyad(0.13, 0.5, math.nan), SpringlabError, "beta"),
    "dyad r string": (lambda: Dyad("0.13", 0.5, 0.0), SpringlabError, "r must be"),
    "compensator k zero": (lambda: Compensator(G=20.0, s=0.3, k=0.0, l0=0.6), SpringlabError, "k must be"),
    "slider C nan": (lambda: dyad_algebra.slider_positions(COMP, math.nan, [0.5]), SpringlabError, "C"),
    "synthesise phi nan": (lambda: dyad_algebra.synthesise([0.5, math.nan, 1.0], [0.5, 0.5, 0.5]), SpringlabError, "phi"),
    "position sets step zero": (lambda: dyad_synthesis.position_sets(step_deg=0.0), SpringlabError, "step_deg"),
    # --- paper 003's planar arms ---
    "planar arm strings": (lambda: PlanarArm(r=["1", "a"], s=[0, 0.1], m=[0, 1]), SpringlabError, "r"),
    "planar arm g zero": (lambda: PlanarArm(r=[1.0, 0.3], s=[0, 0.1], m=[0, 1], g=0.0), SpringlabError, "g must be"),
    "planar arm mass overflow": (lambda: PlanarArm(r=[1.0, 0.3], s=[0, 0.1], m=[0, 1e308], g=1e10), SpringlabError,
                                 "overflow"),
    "planar spring k nan": (lambda: PlanarSpring(1, 2, math.nan, 0.1, 0.1, 0.0, 0.0), SpringlabError, "k"),
    "planar spring float index": (lambda: PlanarSpring(1.5, 2, 10.0, 0.1, 0.1, 0.0, 0.0), SpringlabError, "index i"),
    "planar theta nan": (lambda: planar_geometry.energies(PLANAR, [], [[math.nan, 0.0, 0.0]]), SpringlabError, "theta"),
    "planar theta empty": (lambda: planar_geometry.energies(PLANAR, [], np.zeros((0, 3))), SpringlabError, "theta"),
    "planar torques zero delta": (lambda: planar_geometry.holding_torques(PLANAR, [], [[0.1, 0.2, 0.3]], delta=0.0),
                                  SpringlabError, "delta"),
    "workspace nan": (lambda: Workspace(low=(math.nan,), high=(1.0,)), SpringlabError, "finite"),
    "workspace strings": (lambda: Workspace(low=("a",), high=(1.0,)), SpringlabError, "low"),
    "index grid too fine": (lambda: planar_eff.efficiency_index(PLANAR, [], WORKSPACE, step=0.001), SpringlabError,
                            "step = 0.001"),
    "index step zero": (lambda: planar_eff.efficiency_index(PLANAR, [], WORKSPACE, step=0.0), SpringlabError, "step"),
    "index samples zero": (lambda: planar_eff.efficiency_index(PLANAR, [], WORKSPACE, samples=0, seed=1),
                           SpringlabError, "samples"),
    "index samples huge": (lambda: planar_eff.efficiency_index(PLANAR, [], WORKSPACE, samples=10**13, seed=1),
                           SpringlabError, "samples"),
    # --- paper 004's two-spring arm ---
    "lenzo mass string": (lambda: lenzo.Arm(m1="2", m2=1.0, l1=0.3, h1=0.1, h2=0.1), SpringlabError, "m1"),
    "lenzo solve a2 nan": (lambda: lenzo.solve(lenzo.Arm(2.0, 1.0, 0.3, 0.1, 0.1), a2=math.nan, a12=0.1, b12=0.1),
                           SpringlabError, "a2"),
    # --- trajectories ---
    "sweep nan": (lambda: trajectories.linear_sweep([[math.nan, 0, 0]], [[0.1, 0, 0]], 1.0, 5), SpringlabError,
                  "initial"),
    "sweep samples one": (lambda: trajectories.linear_sweep([[0, 0, 0]], [[0.1, 0, 0]], 1.0, 1), SpringlabError,
                          "samples"),
    "sweep duration zero": (lambda: trajectories.Sweep([[0, 0, 0]], [[0.1, 0, 0]], 0.0), SpringlabError, "duration"),
    "sweep times nan": (lambda: trajectories.Sweep([[0, 0, 0]], [[0.1, 0, 0]], 1.0).angles([math.nan]),
                        SpringlabError, "t"),
    "cubic times reversed": (lambda: trajectories.rest_to_rest_cubic(2.0, 1.0, 0.0, 1.0), SpringlabError, "t_F"),
    "cubic angle nan": (lambda: trajectories.rest_to_rest_cubic(0.0, 1.0, math.nan, 1.0), SpringlabError, "theta_I"),
    "pseudobase dh not a DH": (lambda: replace(PB, dh="DH"), SpringlabError, "dh must be"),
    "pseudobase modules strings": (lambda: replace(PB, modules=("a", "b")), SpringlabError, "modules"),
    "pseudobase g string": (lambda: replace(PB, g="9.81"), SpringlabError, "g must be"),
    "pseudobase up strings": (lambda: replace(PB, up=["z"]), SpringlabError, "up"),
    "pseudobase star height nan": (lambda: replace(PB, star_height=math.nan), SpringlabError, "star_height"),
    "equilibrator K negative": (lambda: Equilibrator(2, -1.0, 0.1, 0.1, np.zeros(3), np.zeros(3)), SpringlabError,
                                "K of spring 2"),
    "equilibrator b shape": (lambda: Equilibrator(2, 10.0, 0.1, 0.1, np.zeros(2), np.zeros(3)), SpringlabError,
                             "b of spring 2"),
    "equilibrators K strings": (lambda: design_equilibrators(PB, ["a"] * 5, [0.1] * 5), SpringlabError, "K must be"),
    "equilibrators l_CA short": (lambda: design_equilibrators(PB, [100.0] * 5, [0.1] * 4), SpringlabError, "l_CA"),
    "equilibrators max l_CB zero": (lambda: design_equilibrators(PB, [100.0] * 5, [0.1] * 5, max_l_CB=0.0),
                                    SpringlabError, "max_l_CB"),
    "pseudobase torques delta": (lambda: pb_geometry.holding_torques(PB, [], np.zeros((1, PB.n)), delta=-1.0),
                                 SpringlabError, "delta"),
    "pseudobase torques scale": (lambda: pb_geometry.holding_torques(PB, [], np.zeros((1, PB.n)), spring_scale=math.nan),
                                 SpringlabError, "spring_scale"),
    "tolerance study tol": (lambda: tolerance.tolerance_study(ARM, SPRINGS, X, {"stiffness": 0.1}, progress=False),
                            SpringlabError, "tol must be"),
    "tolerance study samples": (lambda: tolerance.tolerance_study(ARM, SPRINGS, X, tolerance.Tolerances(stiffness=0.1),
                                                                  samples=0, progress=False), SpringlabError, "samples"),
    "hold test control": (lambda: simulation.hold_test(ARM, SPRINGS, X[:1], control_scale=1.0), SpringlabError,
                          "control_scale"),
    "hold test duration": (lambda: simulation.hold_test(ARM, SPRINGS, X[:1], duration=0.0), SpringlabError, "duration"),
    "hold test settings": (lambda: simulation.hold_test(ARM, SPRINGS, X[:1], settings={"step": 1e-3}), SpringlabError,
                           "settings"),
    "hold test poses empty": (lambda: simulation.hold_test(ARM, SPRINGS, np.zeros((0, 4, 3))), SpringlabError, "poses"),
    "dyad follow phi nan": (lambda: dyad_simulation.follow(COMP, DYAD, math.nan, 1.0), SpringlabError, "phi_start"),
    "dyad follow step": (lambda: dyad_simulation.follow(COMP, DYAD, 0.5, 1.0, duration=1.0, step=2.0), SpringlabError,
                         "step"),
    "screen too many candidates": (lambda: ground.relaxation_screen(serial_chain([0.3] * 9, [0.1] * 9, [1.0] * 9), 8),
                                   SpringlabError, "8 springs on 10 links is 1.99e\\+12 candidate configurations"),
    "screen count zero": (lambda: ground.relaxation_screen(ARM, 0), SpringlabError, "count must be"),
    "fewer springs count float": (lambda: ground.fewer_springs(ARM, 2.5), SpringlabError, "count must be"),
    "minimal multisets max nodes": (lambda: feasibility.minimal_balanceable(ARM, max_nodes=0), SpringlabError,
                                    "max_nodes"),
    "minimal multisets exhausted": (lambda: feasibility.minimal_balanceable(ARM, max_nodes=3),
                                    SearchExhaustedError, "max_nodes = 3"),
    "alphabet signs": (lambda: feasibility.alphabet(4, "some"), SpringlabError, "signs must be one of"),
    # --- simulation settings ---
    "settings step zero": (lambda: SimSettings(step=0.0), SpringlabError, "step"),
    "settings damping negative": (lambda: SimSettings(damping=-1.0), SpringlabError, "damping"),
    "settings tolerance string": (lambda: SimSettings(relative_tolerance="tight"), SpringlabError, "relative_tolerance"),
}


@pytest.mark.parametrize("name", list(CASES))
def test_bad_input_is_refused_with_its_name(name):
    call, error, fragment = CASES[name]
    with pytest.raises(error, match=fragment):
        call()


def test_there_are_at_least_eighty_cases():
    assert len(CASES) >= 80


def test_bad_numbers_are_not_verdicts():
    # a NaN is bad input, never a proof that a design cannot exist
    for call in (lambda: lenzo.solve(lenzo.Arm(2.0, 1.0, 0.3, 0.1, 0.1), a2=math.nan, a12=0.1, b12=0.1),
                 lambda: solve.find_design(ARM, ["S(1,2)"], max_extension=math.nan),
                 lambda: rank.design_arm(spec(), restarts=-1)):
        with pytest.raises(SpringlabError) as caught:
            call()
        assert not isinstance(caught.value, UnbalanceableError | SearchExhaustedError), caught.value


def test_the_error_classes_are_not_confused():
    # an exhausted search is not a proof; an attachment off a link is both a geometry and a design refusal
    assert not issubclass(SearchExhaustedError, UnbalanceableError)
    assert issubclass(AttachmentError, GeometryError) and issubclass(AttachmentError, UnbalanceableError)
    assert all(issubclass(e, ValueError) for e in (SpringlabError, SearchExhaustedError, GeometryError))


def test_a_spring_with_free_length_whose_ends_meet_has_no_torque_direction():
    # S(1,2) with a = 0 and b = 0 has both ends on the base joint at every pose
    with pytest.raises(GeometryError, match="ends coincide"):
        geometry.holding_torques(ARM, [Spring(1, 2, 0.0, 0.0, 100.0, free_length=0.1)], X)
    # zero free length: the force is k (B - A) = 0 there, no direction needed
    assert np.all(np.isfinite(geometry.holding_torques(ARM, [Spring(1, 2, 0.0, 0.0, 100.0)], X)))


def test_the_efficiency_is_one_where_no_spring_term_and_no_gravity_moment_act():
    horizontal = np.zeros((1, 4, 3))
    horizontal[0, 0] = [1.0, 0.0, 0.0]
    horizontal[0, 1:] = [0.0, 1.0, 0.0]  # every link horizontal: x_1 . x_j = 0
    e = deff.spatial_system_efficiency(ARM, [Spring(1, 2, 0.1, 0.1, 10.0)], horizontal)
    assert np.all(np.isfinite(e)) and e[0] == 1.0


def test_an_empty_multiset_is_answered_not_refused():
    # removing the only spring of a configuration leaves none: a valid question with answer "no"
    assert feasibility.is_balanceable(ARM, []) == "no"
    assert feasibility.relaxation_feasible(ARM, []) is False and feasibility.confirm(ARM, []) is None
