"""docs/python.md is what docs/python-walkthrough.py prints now (tools/python-notebook.py)."""
import os
import pathlib
import subprocess
import sys

import pytest

SOURCE = pathlib.Path(os.environ.get("IMAGEPRO_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


def test_the_page_matches_its_script(tmp_path):
    pytest.importorskip("matplotlib", reason="the walk-through plots with python3-matplotlib")
    (tmp_path / "docs").mkdir()
    page = tmp_path / "docs" / "python.md"
    subprocess.run(
        [sys.executable, str(SOURCE / "tools" / "python-notebook.py"), str(SOURCE / "docs" / "python-walkthrough.py"),
         "--out", str(page)],
        cwd=tmp_path, check=True)
    assert (tmp_path / "docs" / "python-pose-error.png").stat().st_size > 10000
    committed = (SOURCE / "docs" / "python.md").read_text().splitlines()
    # The page names its script by the path it was run with.
    made = page.read_text().replace(str(SOURCE / "docs"), "docs").splitlines()
    assert made == committed, "docs/python.md differs from its script's output: tools/regenerate-docs.sh --only python"
