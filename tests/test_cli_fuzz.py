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
from hypothesis import HealthCheck, given, settings
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


def check_outcome(code, out, err, seconds, design_file):
    assert "Traceback" not in out + err and "internal error" not in err, err
    assert seconds < 60, f"took {seconds:.0f} s"
    if code == 2:
        lines = err.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("springlab: "), err
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
