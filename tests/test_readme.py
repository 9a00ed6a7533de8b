"""The README is the door: at most 200 lines, its Python examples run as written; the user's guide
(the book's Using springlab page) runs as written too, and its layout lists every module of the package."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
GUIDE = ROOT / "notebooks" / "using_springlab.md"


def _run_python_blocks(path: Path) -> None:
    blocks = re.findall(r"```python\n(.*?)```", path.read_text(), flags=re.S)
    assert blocks
    namespace = {}  # one session, as a reader would run the blocks in turn
    for block in blocks:
        exec(compile(block, path.name, "exec"), namespace)


def test_readme_python_blocks_run(capsys):
    _run_python_blocks(README)
    out = capsys.readouterr().out
    assert "total energy varies" in out and "route 2 against Pinocchio" in out


def test_the_guides_python_blocks_run(capsys):
    _run_python_blocks(GUIDE)
    assert "total energy varies" in capsys.readouterr().out


def test_the_readme_is_a_door():
    assert len(README.read_text().splitlines()) <= 200


def listed_modules(block: str) -> set[str]:
    """The modules a layout block lists, as paths under ``springlab/``: a line's first word, nested by its
    indent (two spaces a level) under the folders above it (words ending in '/')."""
    folders: list[tuple[int, str]] = []
    out = set()
    for line in block.splitlines():
        if not line.strip():
            continue
        indent, word = len(line) - len(line.lstrip()), line.split()[0]
        while folders and folders[-1][0] >= indent:
            folders.pop()
        path = "".join(f for _, f in folders) + word
        if word.endswith("/"):
            folders.append((indent, word))
        elif path.startswith("springlab/") and path.endswith(".py"):
            out.add(path.removeprefix("springlab/"))
    return out


def package_modules(root: Path) -> set[str]:
    return {str(p.relative_to(root / "springlab")) for p in (root / "springlab").rglob("*.py")
            if p.name != "__init__.py" and "__pycache__" not in p.parts}


def layout_block(text: str) -> str:
    section = text[text.index("\n## Layout"):]
    return re.search(r"```(?:text)?\n(springlab/.*?)```", section, flags=re.S).group(1)


def test_the_layout_lists_every_module_and_no_other():
    listed, present = listed_modules(layout_block(GUIDE.read_text())), package_modules(ROOT)
    assert not present - listed, f"modules missing from the guide's layout: {sorted(present - listed)}"
    assert not listed - present, f"modules listed in the guide's layout but gone: {sorted(listed - present)}"


def test_the_layout_check_catches_a_module_added_or_gone(tmp_path):
    """The negative control: a package with one module more, and a listing with one module more."""
    block = layout_block(GUIDE.read_text())
    (tmp_path / "springlab" / "design").mkdir(parents=True)
    for module in listed_modules(block):
        (tmp_path / "springlab" / module).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / "springlab" / module).touch()
    (tmp_path / "springlab" / "design" / "new_idea.py").touch()
    assert package_modules(tmp_path) - listed_modules(block) == {"design/new_idea.py"}
    gone = block.replace("springlab/\n", "springlab/\n  vanished.py   a module that is not there\n", 1)
    assert listed_modules(gone) - package_modules(ROOT) == {"vanished.py"}
    assert "mechanisms/dyad/algebra.py" in listed_modules(block)  # nested folders are read as nested
