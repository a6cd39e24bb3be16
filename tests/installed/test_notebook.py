"""docs/python-api.ipynb, as a user runs it: in Jupyter (nbclient) on the installed package, in a folder of
their own, from top to bottom without an error, showing the run (a video), the chart and the table."""

import json
import shutil
import textwrap
from pathlib import Path

NOTEBOOK = Path(__file__).resolve().parents[2] / "docs" / "python-api.ipynb"

RUN = """
    import json, sys
    import nbclient, nbformat
    notebook = nbformat.read("python-api.ipynb", as_version=4)
    nbclient.NotebookClient(notebook, kernel_name="installed", timeout=120,
                            resources={"metadata": {"path": "."}}).execute()
    outputs = [o for cell in notebook.cells if cell.cell_type == "code" for o in cell.outputs]
    print(json.dumps({
        "errors": [o.get("ename") for o in outputs if o.output_type == "error"],
        "html": [o["data"]["text/html"] for o in outputs if "text/html" in o.get("data", {})],
        "pictures": sum(1 for o in outputs if "image/png" in o.get("data", {})),
    }))
"""


def test_the_notebook_runs_on_the_installed_package_and_shows_the_run_the_chart_and_the_table(
    installed, user_folder
):
    done = installed.run("python", "-m", "pip", "install", "-q", "ipykernel", "nbclient", "nbformat",
                         cwd=user_folder)  # fmt: skip
    assert done.returncode == 0, done.stderr
    kernel = user_folder / "kernels" / "kernels" / "installed"
    kernel.mkdir(parents=True)
    argv = [str(installed.bin / "python"), "-m", "ipykernel_launcher", "-f", "{connection_file}"]
    (kernel / "kernel.json").write_text(
        json.dumps({"argv": argv, "display_name": "ev3sim2d", "language": "python"})
    )
    notebook = json.loads(NOTEBOOK.read_text(encoding="utf-8"))
    assert not any(c.get("outputs") for c in notebook["cells"] if c["cell_type"] == "code"), (
        "docs/python-api.ipynb is kept without outputs; clear them before committing"
    )
    shutil.copy(NOTEBOOK, user_folder / "python-api.ipynb")
    (user_folder / "run_notebook.py").write_text(textwrap.dedent(RUN))
    done = installed.run(
        "python",
        "run_notebook.py",
        cwd=user_folder,
        timeout=300,
        env={"JUPYTER_PATH": str(user_folder / "kernels")},
    )
    assert done.returncode == 0, done.stderr[-3000:]
    facts = json.loads(done.stdout.splitlines()[-1])
    assert facts["errors"] == []
    assert any("<video" in page for page in facts["html"])  # the result shows itself
    assert facts["pictures"] >= 2  # the end of the run, and the chart
    assert any("<table>" in page and "x_cm" in page for page in facts["html"])  # the trajectory
