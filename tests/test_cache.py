"""The notebook cache: a notebook re-runs when something it depends on changed, and only then."""

from __future__ import annotations

import json
import shutil

import pytest

from springlab.workbench import cache, notebooks

ROOT = cache.ROOT


def test_a_notebook_depends_on_the_modules_it_imports_and_not_on_others():
    planar = ROOT / "springlab/mechanisms/planar/efficiency.py"
    dyad = ROOT / "springlab/mechanisms/dyad/synthesis.py"
    efficiency = cache.notebook_dependencies(ROOT / "notebooks/juang2022_spring_efficiency.ipynb")
    dyad_nb = cache.notebook_dependencies(ROOT / "notebooks/zhang2023_dyad.ipynb")
    assert planar in efficiency and planar not in dyad_nb
    assert dyad in dyad_nb and dyad not in efficiency
    for deps in (efficiency, dyad_nb):  # what every notebook shares
        assert ROOT / "springlab/__init__.py" in deps and ROOT / "constraints.txt" in deps
        assert ROOT / "springlab/workbench/springlab.mplstyle" in deps
        assert ROOT / "notebooks/arms/paper000_arm.toml" in deps


def test_a_change_to_one_module_changes_the_keys_of_the_notebooks_that_import_it(tmp_path, monkeypatch):
    copy = tmp_path / "project"
    for part in ("springlab", "notebooks"):
        shutil.copytree(ROOT / part, copy / part, ignore=shutil.ignore_patterns("__pycache__", ".ipynb_checkpoints"))
    for name in ("pyproject.toml", "constraints.txt"):
        shutil.copy(ROOT / name, copy / name)
    monkeypatch.setattr(cache, "ROOT", copy)
    monkeypatch.setattr(cache, "PACKAGE", copy / "springlab")
    before = {nb.stem: cache.digest(cache.notebook_dependencies(nb)) for nb in sorted((copy / "notebooks").glob("*.ipynb"))}
    with open(copy / "springlab/mechanisms/planar/efficiency.py", "a") as f:
        f.write("\n# a change\n")
    after = {nb.stem: cache.digest(cache.notebook_dependencies(nb)) for nb in sorted((copy / "notebooks").glob("*.ipynb"))}
    changed = sorted(stem for stem in before if before[stem] != after[stem])
    importers = sorted(stem for stem in before
                       if copy / "springlab/mechanisms/planar/efficiency.py" in cache.notebook_dependencies(
                           copy / "notebooks" / f"{stem}.ipynb"))
    assert changed == importers and "juang2022_spring_efficiency" in changed and "zhang2023_dyad" not in changed
    # negative control: a change to a file no notebook reads changes no key
    (copy / "springlab" / "unused_note.txt").write_text("not a module")
    assert {nb.stem: cache.digest(cache.notebook_dependencies(nb))
            for nb in sorted((copy / "notebooks").glob("*.ipynb"))} == after


def test_the_cache_reuses_a_run_only_while_its_key_and_outputs_stand(tmp_path):
    store = cache.Cache(tmp_path / "cache")
    out = tmp_path / "out.ipynb"
    assert not store.fresh("nb", "k1", [out])
    store.store("nb", "k1")
    assert not store.fresh("nb", "k1", [out])  # the executed copy is missing
    out.write_text("{}")
    assert store.fresh("nb", "k1", [out]) and not store.fresh("nb", "k2", [out])
    store.forget("nb")
    assert not store.fresh("nb", "k1", [out])


TINY = {"cells": [{"cell_type": "code", "execution_count": None, "id": "p", "metadata": {"tags": ["parameters"]},
                   "outputs": [], "source": ["quick = False"]},
                  {"cell_type": "code", "execution_count": None, "id": "a", "metadata": {}, "outputs": [],
                   "source": ["x = 1 + 1"]}],
        "metadata": {"kernelspec": {"name": "python3", "display_name": "Python 3", "language": "python"}},
        "nbformat": 4, "nbformat_minor": 5}


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_the_runner_skips_an_unchanged_notebook_and_reruns_a_changed_one(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "notebooks").mkdir()
    (tmp_path / "figures" / "tiny").mkdir(parents=True)
    nb = tmp_path / "notebooks" / "tiny.ipynb"
    nb.write_text(json.dumps(TINY))
    argv = ["--out", "build/notebooks", "--jobs", "1"]
    assert notebooks.main(argv) == 0
    assert "running notebooks/tiny.ipynb" in capsys.readouterr().out
    executed = tmp_path / "build" / "notebooks" / "tiny.ipynb"
    ran = json.loads(executed.read_text())["cells"][1]
    assert "".join(ran["source"]) == "x = 1 + 1" and ran["execution_count"] is not None
    assert notebooks.main(argv) == 0
    assert "unchanged notebooks/tiny.ipynb" in capsys.readouterr().out
    TINY["cells"][1]["source"] = ["x = 1 + 2"]
    nb.write_text(json.dumps(TINY))
    assert notebooks.main(argv) == 0
    assert "running notebooks/tiny.ipynb" in capsys.readouterr().out
    assert "".join(json.loads(executed.read_text())["cells"][1]["source"]) == "x = 1 + 2"  # and run again
    assert notebooks.main([*argv, "--no-cache"]) == 0
    assert "running notebooks/tiny.ipynb" in capsys.readouterr().out


def test_the_longest_notebook_is_expected_first(tmp_path):
    from springlab.workbench.notebooks import _record_seconds, expected_seconds, notebook_paths

    paths = {p.stem: p for p in notebook_paths(ROOT / "notebooks")}
    hinted = sorted(paths.values(), key=lambda p: -expected_seconds(p, tmp_path))
    assert all(expected_seconds(p, tmp_path) > 0 for p in paths.values())  # every notebook carries a hint
    assert hinted[-1].stem == "lenzo2017_two_spring_arm"  # the shortest starts last
    _record_seconds(tmp_path, "lenzo2017_two_spring_arm", 500.0)  # a recorded run beats the hint
    assert expected_seconds(paths["lenzo2017_two_spring_arm"], tmp_path) == 500.0
    (tmp_path / "durations.json").write_text("not json")
    assert expected_seconds(paths["lenzo2017_two_spring_arm"], tmp_path) < 500.0  # a broken record: the hint


def test_notebooks_validate_without_the_iri_format_checker():
    """The runner keeps jsonschema from loading rfc3987_syntax (0.9 s per process); nbformat
    still validates a notebook, and still refuses a broken one."""
    import subprocess
    import sys

    code = ("from springlab.workbench.notebooks import skip_unused_format_checker\n"
            "skip_unused_format_checker()\n"
            "import sys, nbformat\n"
            f"nb = nbformat.read({str(ROOT / 'notebooks' / 'lenzo2017_two_spring_arm.ipynb')!r}, as_version=4)\n"
            "nbformat.validate(nb)\n"
            "nb.cells[0]['cell_type'] = 'no such type'\n"
            "try:\n    nbformat.validate(nb)\nexcept nbformat.ValidationError:\n    print('refused')\n"
            "print('rfc3987_syntax' in sys.modules and sys.modules['rfc3987_syntax'] is not None)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    assert out == ["refused", "False"]


def test_the_sites_key_follows_the_pages_written_beside_the_notebooks(tmp_path, monkeypatch):
    # the guide, the glossary and the benchmarks' page are the site's inputs too: an edit to one rebuilds it
    import argparse

    from springlab.workbench import book, site

    page = tmp_path / "glossary.md"
    page.write_text("# Glossary\n\none\n")
    monkeypatch.setitem(book.PAGES, "glossary", page)
    args = argparse.Namespace(notebooks=tmp_path / "nb", figures=tmp_path / "fig", site=tmp_path / "site",
                              work=tmp_path / "work")
    before = site._site_key(args)
    assert site._site_key(args) == before  # the control: nothing changed, the same key
    page.write_text("# Glossary\n\ntwo\n")
    assert site._site_key(args) != before
