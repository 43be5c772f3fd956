"""Every notebook runs from top to bottom (its own cells assert what they show) and
holds its figures: a reader opening it sees the cards and curves it talks about."""

from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

NOTEBOOKS = sorted((Path(__file__).resolve().parent.parent / "notebooks").glob("*.ipynb"))


def _figures(nb) -> int:
    return sum(1 for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])
               if "image/png" in o.get("data", {}))


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_notebook_runs_and_holds_its_figures(path, tmp_path):
    stored = nbformat.read(path, as_version=4)
    assert _figures(stored) >= 1, f"{path.name} is stored without its figures"
    nb = nbformat.read(path, as_version=4)
    NotebookClient(nb, timeout=600, kernel_name="python3",
                   resources={"metadata": {"path": str(tmp_path)}}).execute()
    assert _figures(nb) >= _figures(stored), "a run shows fewer figures than are stored"
