"""docs/python.md's examples run as written: its python blocks, in order, in one namespace,
from a folder that has the source tree's cells (the page runs them from the top of it)."""

import os
import re

from conftest import SOURCE


def test_the_pages_examples_run(tmp_path, capsys):
    page = (SOURCE / "docs" / "python.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", page, flags=re.S)
    assert len(blocks) >= 8
    (tmp_path / "cells").symlink_to(SOURCE / "cells")
    here = os.getcwd()
    os.chdir(tmp_path)
    try:
        namespace = {}
        for k, block in enumerate(blocks):
            exec(compile(block, f"docs/python.md block {k + 1}", "exec"), namespace)
    finally:
        os.chdir(here)
    out = capsys.readouterr().out
    assert "unknown key fingers[1].mas" in out and "static friction mu_s is 0.5" in out
    assert (tmp_path / "plan.json").is_file()
