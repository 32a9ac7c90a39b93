"""The README's Python snippet runs as written, in an empty folder, and makes what it says."""

import re
import subprocess
import sys
from pathlib import Path

README = Path(__file__).resolve().parents[2] / "README.md"


def snippet():
    section = README.read_text().split("\n## Python\n", 1)[1]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


def test_the_readme_snippet_runs_as_written(tmp_path):
    code = snippet()
    assert "bumpmap.Renderer" in code and "read_texture" in code
    # Printing what it made, after the snippet's own lines.
    check = code + """
assert normals.shape == (256, 256, 4) and len(chain) == 9
assert texture["format"] == "bc5" and len(texture["levels"]) == 9
assert mesh["tangents"].shape[1] == 4 and image.shape == (256, 256, 4) and len(frames) == 20
assert frames[0][..., :3].max() > 40 and not (frames[0] == frames[5]).all()
assert set(results) >= {"techniques"}, list(results)
assert len(rough) == 9 and rough[0].dtype == np.uint8 and moments[0].shape == (256, 256, 4)
assert bumpy_grid[..., :3].max() > 40 and truth.shape == (64, 64, 4) and len(nm) == 9
print("ran")
"""
    done = subprocess.run([sys.executable, "-c", check], cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "ran" in done.stdout
    # The reference's progress, printed by the snippet's progress= function, ends at its total.
    counts = [tuple(map(int, line.split("/"))) for line in done.stdout.splitlines() if re.fullmatch(r"\d+/\d+", line)]
    assert counts and counts[-1][0] == counts[-1][1] > 1, done.stdout
    assert (tmp_path / "bricks.dds").is_file() and (tmp_path / "out" / "compare" / "report.html").is_file()
