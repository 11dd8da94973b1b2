"""The example notebook runs from top to bottom (it asserts its own closed-form check), as a
user would run it in Jupyter; the executed copy is kept in the build tree."""

import os
from pathlib import Path

import pytest
from conftest import SOURCE_DIR

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")


def test_roll_to_slip_notebook_runs(tmp_path):
    path = SOURCE_DIR / "examples" / "notebooks" / "roll_to_slip.ipynb"
    notebook = nbformat.read(path, as_version=4)
    os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # the kernel's debugger notice
    client = nbclient.NotebookClient(notebook, timeout=600, kernel_name="python3",
                                     resources={"metadata": {"path": str(tmp_path)}})
    client.execute()  # raises CellExecutionError on any failing cell
    outputs = [o for cell in notebook.cells if cell.cell_type == "code" for o in cell.get("outputs", [])]
    assert any(o.get("output_type") == "display_data" and "image/png" in o.get("data", {}) for o in outputs)
    executed = Path(os.environ.get("STICTION_NOTEBOOK_OUT", tmp_path)) / "roll_to_slip.executed.ipynb"
    nbformat.write(notebook, executed)
