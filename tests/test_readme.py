"""The README's Python example runs as written."""

import re
from pathlib import Path

README = Path(__file__).resolve().parents[1] / "README.md"


def test_readme_python_blocks_run(capsys):
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(), flags=re.S)
    assert blocks
    namespace = {}  # one session, as a reader would run the blocks in turn
    for block in blocks:
        exec(compile(block, "README.md", "exec"), namespace)
    assert "total energy varies" in capsys.readouterr().out
