"""The quickstart notebook a newcomer opens first (examples/quickstart.ipynb): committed without
outputs, and every cell runs headless (nbclient, a fresh kernel of this environment) — a broken
cell fails the suite."""

from __future__ import annotations

import pathlib

import pytest

NOTEBOOK = pathlib.Path(__file__).resolve().parents[1] / "examples" / "quickstart.ipynb"


def test_the_notebook_is_committed_without_outputs():
    nbformat = pytest.importorskip("nbformat")
    nb = nbformat.read(NOTEBOOK, as_version=4)
    nbformat.validate(nb)
    code = [c for c in nb.cells if c.cell_type == "code"]
    assert code, "the notebook has no code"
    assert all(not c.outputs and c.execution_count is None for c in code), "strip the outputs before committing"


@pytest.mark.slow
@pytest.mark.gpu
def test_every_cell_of_the_notebook_runs(tmp_path):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    nb = nbformat.read(NOTEBOOK, as_version=4)
    client = nbclient.NotebookClient(nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}})
    client.execute()  # raises CellExecutionError naming the cell that failed
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    kinds = {k for o in outputs for k in o.get("data", {})}
    # The render shows itself, the plots are images, and the live view is a widget.
    assert {"image/png", "application/vnd.jupyter.widget-view+json"} <= kinds, kinds
    text = "".join(o.get("text", "") for o in outputs if o.output_type == "stream")
    assert "indirect over reference" in text and "reference's own relative error" in text, text
