"""examples/plot_e.py runs and writes a PNG picture."""
import subprocess
import sys

import pytest

pytest.importorskip("matplotlib")


def test_plot_example_writes_a_png(source, tmp_path):
    out = tmp_path / "e.png"
    subprocess.run([sys.executable, f"{source}/examples/plot_e.py", str(out)], check=True,
                   capture_output=True)
    data = out.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 20000
