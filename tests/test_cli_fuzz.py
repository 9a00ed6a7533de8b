"""Random malformed arm files fed to ``springlab design``: it designs a verified arm, or
exits 2 with one line, or (the limits admit no spring) exits 1 naming why. Never a
traceback, an internal error, a NaN in what it prints, or a hang."""

from __future__ import annotations

import contextlib
import io
import json
import math
import time

import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from springlab.design.rank import VERIFY_TOLERANCE
from springlab.workbench.cli import main

VALID_LINK = {"length": "0.3 m", "com": "150 mm", "mass": "2 kg"}

junk = st.one_of(
    st.none(), st.booleans(), st.integers(min_value=-10**30, max_value=10**30),
    st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=12),
    st.sampled_from(["1 furlong", "-3 mm", "1e400 kg", "0 m", "2 kg", "9.81 m/s^2", "5 N/mm", "nan m", "1e-300 m",
                     "10 kN/m", "0.1 m", "kg", "1.5", " 3 cm "]),
    st.lists(st.integers(-2, 2), max_size=4), st.dictionaries(st.text(max_size=4), st.integers(), max_size=2),
)
link_fields = st.sampled_from(["length", "com", "mass", "joint", "colour"])
top_fields = st.sampled_from(["name", "g", "payload", "limits", "workspace", "link", "extra"])
sub_fields = {"payload": st.sampled_from(["mass", "volume"]),
              "limits": st.sampled_from(["max_stiffness", "max_attachment", "min_force"]),
              "workspace": st.sampled_from(["samples", "seed", "grid"])}


@st.composite
def malformed_arm(draw):
    data = {"name": "fuzz", "link": [dict(VALID_LINK) for _ in range(draw(st.integers(1, 3)))],
            "workspace": {"samples": 50}}
    for _ in range(draw(st.integers(1, 3))):
        kind = draw(st.sampled_from(["link field", "drop link field", "top field", "sub field", "drop top field"]))
        if kind == "link field":
            link = draw(st.sampled_from(data["link"])) if isinstance(data.get("link"), list) and data["link"] else None
            if isinstance(link, dict):
                link[draw(link_fields)] = draw(junk)
        elif kind == "drop link field" and isinstance(data.get("link"), list) and data["link"]:
            link = draw(st.sampled_from(data["link"]))
            if isinstance(link, dict):
                link.pop(draw(link_fields), None)
        elif kind == "top field":
            data[draw(top_fields)] = draw(junk)
        elif kind == "sub field":
            table = draw(st.sampled_from(sorted(sub_fields)))
            if not isinstance(data.get(table), dict):
                data[table] = {}
            data[table][draw(sub_fields[table])] = draw(junk)
        else:
            data.pop(draw(top_fields), None)
    return data


def run(argv) -> tuple[int, str, str, float]:
    out, err = io.StringIO(), io.StringIO()
    t0 = time.perf_counter()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(argv)
        except SystemExit as exit_:  # argparse's own errors exit from parse_args
            code = exit_.code
    return code, out.getvalue(), err.getvalue(), time.perf_counter() - t0


def check_outcome(code, out, err, seconds, design_file, refuse_within=60):
    assert "Traceback" not in out + err and "internal error" not in err, err
    assert seconds < 60, f"took {seconds:.0f} s"
    if code == 2:
        lines = err.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("springlab: "), err
        assert seconds < refuse_within, f"the refusal took {seconds:.1f} s: {err}"
    elif code == 1:
        assert "no design found" in err, err
    else:
        assert code == 0, (code, err)
        design = json.loads(design_file.read_text())
        assert design["energy_variation"] < VERIFY_TOLERANCE
        assert all(math.isfinite(design[key]) for key in ("max_force_N", "stiffness_sum_N_per_m", "efficiency"))
        assert all(math.isfinite(s["k_N_per_m"]) and s["k_N_per_m"] > 0 for s in design["springs"])
    cells = [c.strip().lower() for line in out.splitlines() if line.startswith("| ") for c in line.split("|")]
    assert not {"nan", "inf", "-inf"} & set(cells), out


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture,
                                                                  HealthCheck.too_slow])
@given(data=malformed_arm())
def test_malformed_arm_files_design_or_exit_with_one_line(tmp_path, data):
    arm = tmp_path / "arm.json"
    arm.write_text(json.dumps(data, allow_nan=True))
    design_file = tmp_path / "arm.design.json"
    design_file.unlink(missing_ok=True)
    code, out, err, seconds = run(["design", str(arm), "--quiet", "--max-designs", "1", "--time-limit", "20",
                                   "--json", str(design_file)])
    check_outcome(code, out, err, seconds, design_file)


UP_RPY = {"0,0,1": "0 0 0", "0,1,0": "-1.5707963267948966 0 0", "1,0,0": "0 1.5707963267948966 0",
          "0,-1,0": "1.5707963267948966 0 0", "-1,0,0": "0 -1.5707963267948966 0"}
"""A base joint's rpy that stands an arm built along +z along each up (a CAD export's frames)."""


def urdf_arm(elbows: int, extra: int, tool: int, up: str) -> str:
    """A URDF arm that loads read with ``up``: a column on a joint about up, ``elbows`` links on
    parallel level axes, ``extra`` more revolute joints beyond them (links like the elbows' up to 30,
    beyond that a whole robot's worth at one point, without inertia) and ``tool`` bodies fixed in a row beyond
    the tool frame."""
    def joint(name, parent, child, z, axis="0 1 0", kind="revolute", rpy="0 0 0"):
        return (f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
                f'<origin xyz="0 0 {z}" rpy="{rpy}"/><axis xyz="{axis}"/></joint>')

    def link(name, com, mass):
        return f'<link name="{name}"><inertial><origin xyz="0 0 {com}"/><mass value="{mass}"/></inertial></link>'

    parts = ['<robot name="fuzz arm"><link name="base"/>', joint("yaw", "base", "l1", 0.1, "0 0 1", "continuous",
                                                                  UP_RPY[up]), link("l1", 0.1, 4.0)]
    for k in range(2, elbows + 2):
        parts += [joint(f"j{k}", f"l{k - 1}", f"l{k}", 0.3), link(f"l{k}", 0.12, 2.0)]
    last = f"l{elbows + 1}"
    for k in range(1, extra + 1):  # a few more links, or a long string of joints without inertia 1 mm apart
        parts += ([joint(f"x{k}", last, f"x{k}", 0.3), link(f"x{k}", 0.12, 2.0)] if extra <= 30 else
                  [f'<joint name="x{k}" type="revolute"><parent link="{last}"/><child link="x{k}"/></joint>'
                   f'<link name="x{k}"/>'])
        last = f"x{k}"
    parts += [joint("flange", last, "tool0", 0.3, kind="fixed"), '<link name="tool0"/>']
    for k in range(1, tool + 1):
        parts += [joint(f"t{k}", "tool0" if k == 1 else f"t{k - 1}", f"t{k}", 0.0005, kind="fixed"),
                  link(f"t{k}", 0, 0.001)]
    return "".join(parts) + "</robot>"


@st.composite
def urdf_case(draw):
    return {"elbows": draw(st.integers(1, 3)), "extra": draw(st.sampled_from([0, 0, 0, 6, 30, 100_000])),
            "tool": draw(st.sampled_from([0, 1, 2000])), "up": draw(st.sampled_from(sorted(UP_RPY))),
            "give_up": draw(st.booleans())}


@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture,
                                                                  HealthCheck.too_slow])
@given(case=urdf_case())
@example(case={"elbows": 2, "extra": 100_000, "tool": 0, "up": "0,0,1", "give_up": False})  # once 40 s to refuse
@example(case={"elbows": 2, "extra": 0, "tool": 2000, "up": "0,0,1", "give_up": False})  # once a RecursionError
@example(case={"elbows": 2, "extra": 0, "tool": 0, "up": "0,1,0", "give_up": False})  # once "an offset shoulder"
def test_urdf_arms_design_or_exit_at_once_saying_what_to_do(tmp_path, case):
    arm = tmp_path / "arm.urdf"
    arm.write_text(urdf_arm(case["elbows"], case["extra"], case["tool"], case["up"]))
    design_file = tmp_path / "arm.design.json"
    design_file.unlink(missing_ok=True)
    code, out, err, seconds = run(["design", str(arm), "--quiet", "--max-designs", "1", "--method", "ground springs",
                                   "--time-limit", "20", "--json", str(design_file)]
                                  + ([f"--up={case['up']}"] if case["give_up"] else []))
    check_outcome(code, out, err, seconds, design_file, refuse_within=5)
    movable = 1 + case["elbows"] + case["extra"]
    if movable > 21:  # more than 8 links, whatever wrists the joints make: refused by their count
        assert code == 2 and f"{movable} movable joints" in err and "at most 8 links" in err, err
    elif case["up"] != "0,0,1" and not case["give_up"]:  # read z-up, its column lies down
        flag = f"--up={case['up']}" if case["up"].startswith("-") else f"--up {case['up']}"  # as argparse takes it
        assert code == 2 and f"pass {flag} " in err, err
    elif 1 + movable > 8:
        assert code == 2 and "--allow-large" in err, err
    else:
        assert code == 0, err


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(blob=st.binary(max_size=200))
def test_garbage_toml_files_exit_with_one_line(tmp_path, blob):
    arm = tmp_path / "arm.toml"
    arm.write_bytes(blob)
    code, out, err, seconds = run(["design", str(arm), "--quiet", "--json", str(tmp_path / "x.json")])
    check_outcome(code, out, err, seconds, tmp_path / "x.json")
    assert code == 2


@pytest.mark.parametrize("args, fragment", [
    (["--max-designs", "0"], "--max-designs must be an integer >= 1"),
    (["--pick", "0"], "--pick must be"),
    (["--pick", "5", "--max-designs", "2"], "--pick = 5 is above --max-designs = 2"),
    (["--seed", "-1"], "--seed must be"),
    (["--time-limit", "0"], "--time-limit must be"),
    (["--time-limit", "nan"], "--time-limit must be"),
    (["--max-configurations", "0"], "--max-configurations must be"),
    (["--method", "magic"], "argument --method: invalid choice"),
    (["--pick", "x"], "argument --pick: invalid int value"),
    (["--json", "/nonexistent-folder/out.json"], "the folder /nonexistent-folder does not exist"),
    (["--json", "."], "is a directory"),
])
def test_bad_command_lines_exit_2_with_one_line(tmp_path, args, fragment):
    arm = tmp_path / "arm.json"
    arm.write_text(json.dumps({"link": [VALID_LINK]}))
    code, out, err, _ = run(["design", str(arm), "--quiet", *args])
    assert code == 2 and err.count("\n") == 1 and fragment in err, err


@pytest.mark.parametrize("make, fragment", [
    (lambda p: p, "is not a file"),
    (lambda p: p / "missing.toml", "does not exist"),
    (lambda p: (p / "arm.toml").write_bytes(b"\xff\xfe\x00binary") and p / "arm.toml", "not a text file"),
    (lambda p: (p / "arm.yaml").write_text("link: []") and p / "arm.yaml", "arm files are .toml, .json or .urdf"),
    (lambda p: (p / "arm.toml").write_text("[[link]]\nlength = ") and p / "arm.toml", "not valid TOML"),
])
def test_bad_arm_paths_exit_2_with_one_line(tmp_path, make, fragment, capsys):
    code = main(["design", str(make(tmp_path)), "--quiet"])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and fragment in err, err


def test_the_output_path_is_checked_before_the_search(tmp_path, capsys, monkeypatch):
    import springlab.design.rank as rank

    def never(*args, **kwargs):
        raise AssertionError("the search started before the output path was checked")

    monkeypatch.setattr(rank, "design_arm", never)
    arm = tmp_path / "arm.json"
    arm.write_text(json.dumps({"link": [VALID_LINK]}))
    assert main(["design", str(arm), "--quiet", "--json", str(tmp_path / "no" / "out.json")]) == 2
    assert "does not exist" in capsys.readouterr().err


def test_no_design_within_the_limits_names_the_reasons(tmp_path, capsys):
    arm = tmp_path / "arm.json"
    arm.write_text(json.dumps({"link": [VALID_LINK, VALID_LINK], "limits": {"max_stiffness": "1 N/m"}}))
    assert main(["design", str(arm), "--quiet", "--json", str(tmp_path / "out.json")]) == 1
    err = capsys.readouterr().err
    assert "no design found" in err and "max_stiffness = 1 N/m" in err, err


def test_a_ten_link_arm_stops_at_the_time_limit_and_says_so(tmp_path, capsys):
    arm = tmp_path / "arm.json"
    arm.write_text(json.dumps({"link": [VALID_LINK] * 9}))
    assert main(["design", str(arm), "--quiet"]) == 2  # more than 8 links needs --allow-large
    assert "--allow-large" in capsys.readouterr().err
    t0 = time.perf_counter()
    code = main(["design", str(arm), "--quiet", "--allow-large", "--method", "no auxiliary links", "--time-limit", "1",
                 "--json", str(tmp_path / "o.json")])
    err = capsys.readouterr().err
    assert code == 1 and time.perf_counter() - t0 < 30
    assert "the time limit of 1 s was reached" in err and "--method 'ground springs'" in err, err
    # the advised method designs it
    code = main(["design", str(arm), "--quiet", "--allow-large", "--method", "ground springs",
                 "--json", str(tmp_path / "o.json")])
    assert code == 0 and json.loads((tmp_path / "o.json").read_text())["energy_variation"] < VERIFY_TOLERANCE
    # the default tries the ground springs before paper 000's configurations (here on a 7-link arm)
    arm.write_text(json.dumps({"link": [VALID_LINK] * 6}))
    code = main(["design", str(arm), "--quiet", "--max-designs", "1", "--json", str(tmp_path / "d.json")])
    assert code == 0 and json.loads((tmp_path / "d.json").read_text())["method"] == "ground springs"
    assert "not screened" in capsys.readouterr().out  # 3.5 million sets of five springs: more than the budget
