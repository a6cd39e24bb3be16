"""docs/python-api.ipynb runs from top to bottom without an error and shows the run, the chart and the table."""

import json
import sys
from pathlib import Path

import pytest

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")
pytest.importorskip("ipykernel")
pytest.importorskip("matplotlib")

NOTEBOOK = Path(__file__).resolve().parents[2] / "docs" / "python-api.ipynb"


@pytest.fixture
def this_python_kernel(tmp_path, monkeypatch):
    """A kernel spec that runs this interpreter (the venv's), whatever kernels the machine has."""
    spec = tmp_path / "kernels" / "ev3sim2d-test"
    spec.mkdir(parents=True)
    argv = [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"]
    (spec / "kernel.json").write_text(
        json.dumps({"argv": argv, "display_name": "test", "language": "python"})
    )
    monkeypatch.setenv("JUPYTER_PATH", str(tmp_path))
    return "ev3sim2d-test"


def test_the_notebook_runs_and_shows_the_run_the_chart_and_the_table(this_python_kernel):
    notebook = nbformat.read(NOTEBOOK, as_version=4)
    assert not any(cell.get("outputs") for cell in notebook.cells if cell.cell_type == "code"), (
        "docs/python-api.ipynb is kept without outputs; clear them before committing"
    )
    client = nbclient.NotebookClient(
        notebook,
        kernel_name=this_python_kernel,
        timeout=60,
        resources={"metadata": {"path": str(NOTEBOOK.parent)}},
    )
    client.execute()
    outputs = [output for cell in notebook.cells if cell.cell_type == "code" for output in cell.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    html = [o.data["text/html"] for o in outputs if "text/html" in o.get("data", {})]
    pictures = [o for o in outputs if "image/png" in o.get("data", {})]
    assert any("<video" in page for page in html)  # the result shows itself
    assert len(pictures) >= 2  # the end of the run, and the chart
    assert any("<table>" in page and "x_cm" in page for page in html)  # the trajectory
