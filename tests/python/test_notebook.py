"""Notebooks: the example notebook runs without error, and models and
results display themselves."""

from __future__ import annotations

import base64
import re
from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

import camlink

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


def _png(html: str) -> bytes:
    m = re.search(r'<img src="data:image/png;base64,([A-Za-z0-9+/=]+)"', html)
    assert m, html[:200]
    data = base64.b64decode(m.group(1))
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return data


def test_model_and_results_show_themselves() -> None:
    model = camlink.load(EXAMPLES / "four_bar.toml")
    html = model._repr_html_()
    assert "<table>" in html and "revolute (ground – crank)" in html
    _png(html)
    res = model.run()
    html = res._repr_html_()
    assert "<table" in html and "crank.x" in html and "31 more channels" in html
    _png(html)


def test_cam_notebook_runs(tmp_path: Path) -> None:
    nb = nbformat.read(EXAMPLES / "cam_seed_notebook.ipynb", as_version=4)
    client = NotebookClient(nb, timeout=300, kernel_name="python3",
                            resources={"metadata": {"path": str(EXAMPLES)}})
    client.execute()
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    html = [o["data"]["text/html"] for o in outputs if "text/html" in o.get("data", {})]
    assert any("data:image/gif;base64," in h for h in html)
    assert sum("image/png" in o.get("data", {}) for o in outputs) >= 3
    nbformat.write(nb, tmp_path / "executed.ipynb")


@pytest.mark.parametrize("name", ["cam_seed_notebook.ipynb"])
def test_notebook_is_stored_without_outputs(name: str) -> None:
    nb = nbformat.read(EXAMPLES / name, as_version=4)
    assert all(not c.get("outputs") for c in nb.cells if c.cell_type == "code")
