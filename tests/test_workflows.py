"""The repository's own CI workflow (.github/workflows/tests.yml): a valid workflow file (GitHub's
schema, checked offline with check-jsonschema's copy of it) that runs the README's test command on
Linux, Windows and macOS (arm64 and Intel) with every supported Python, none cut short by another's
failure, and then runs ev3sim2d as a user does on each of them, in each system's own shell."""

import re
from pathlib import Path

import yaml

from tests.workflow_schema import schema_problems

ROOT = Path(__file__).resolve().parents[1]
WORKFLOW = ROOT / ".github" / "workflows" / "tests.yml"
SYSTEMS = ["ubuntu-latest", "windows-latest", "macos-latest", "macos-15-intel"]
PYTHONS = ["3.11", "3.12", "3.13"]


def job() -> dict:
    [only] = yaml.safe_load(WORKFLOW.read_text(encoding="utf-8"))["jobs"].values()
    return only


def runs() -> list[str]:
    return [" ".join(step["run"].split()) for step in job()["steps"] if "run" in step]


def test_the_workflow_is_valid_against_githubs_workflow_schema():
    assert schema_problems(WORKFLOW) is None, schema_problems(WORKFLOW)


def test_every_system_with_every_python_and_no_failure_cancels_the_others():
    strategy = job()["strategy"]
    assert strategy["fail-fast"] is False
    assert strategy["matrix"]["os"] == SYSTEMS
    assert strategy["matrix"]["python"] == PYTHONS
    # the oldest Python setup.cfg admits runs too, on Linux
    setup_cfg = (ROOT / "setup.cfg").read_text(encoding="utf-8")
    oldest = re.search(r"python_requires = >=(3\.\d+)", setup_cfg).group(1)
    assert {"os": "ubuntu-latest", "python": oldest} in strategy["matrix"]["include"]
    assert job()["runs-on"] == "${{ matrix.os }}"
    [setup] = [
        step for step in job()["steps"] if str(step.get("uses", "")).startswith("actions/setup-python@")
    ]
    assert setup["with"]["python-version"] == "${{ matrix.python }}"


def test_it_runs_the_readmes_test_command():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert ".venv/bin/pip install -e '.[test]' && .venv/bin/python -m pytest -q" in readme
    assert 'python -m pip install -e ".[test]"' in runs()  # (double quotes: PowerShell's and bash's alike)
    assert "python -m pytest -q" in runs()
    steps = [step.get("run", "") for step in job()["steps"]]
    install = next(i for i, run in enumerate(steps) if "pip install" in run)
    assert install < next(i for i, run in enumerate(steps) if "pytest" in run)


def test_the_smoke_test_runs_on_every_system_in_its_own_shell():
    smoke = [step for step in job()["steps"] if step.get("name", "").startswith("Smoke test")]
    assert {step["if"] for step in smoke} == {"runner.os != 'Windows'", "runner.os == 'Windows'"}
    assert {step["shell"] for step in smoke} == {"bash", "pwsh"}
    for step in smoke:
        script = step["run"]
        assert "ev3sim2d --version" in script
        assert re.search(r"ev3sim2d run .*drive_square\.py", script)
        assert re.search(r"ev3sim2d run pi\.py .*> out\.txt", script)
        assert "my robot" in script
    [pwsh] = [step for step in smoke if step["shell"] == "pwsh"]
    ran = sum(line.strip().startswith("ev3sim2d ") for line in pwsh["run"].splitlines())
    assert pwsh["run"].count("$LASTEXITCODE -ne 0") == ran, "PowerShell stops on no native exit code"
    assert pwsh["run"].isascii()


def test_every_system_names_the_browser_the_browser_tests_drive_before_they_run():
    steps = job()["steps"]
    [browser] = [i for i, step in enumerate(steps) if "tests.headless_chromium" in step.get("run", "")]
    assert "if" not in steps[browser]  # (GitHub sets CI=true: without a browser those tests fail)
    assert browser < next(i for i, step in enumerate(steps) if "pytest" in step.get("run", ""))


def test_python_ev3dev2s_own_tests_run_from_their_checkout_and_must_not_skip():
    """tests/ev3dev2/test_upstream_suite.py skips where no checkout is named; here one must be."""
    steps = job()["steps"]
    [upstream] = [
        step for step in steps if step.get("with", {}).get("repository") == "ev3dev/ev3dev-lang-python"
    ]
    assert upstream["with"]["ref"] == "ev3dev-stretch/2.1.0" and upstream["with"]["submodules"] is True
    [tests] = [step for step in steps if step.get("run", "").strip() == "python -m pytest -q"]
    assert tests["env"]["EV3SIM2D_REQUIRE_UPSTREAM_EV3DEV2"] == "1"
    assert tests["env"]["EV3SIM2D_UPSTREAM_EV3DEV2"].endswith(upstream["with"]["path"])
    assert steps.index(upstream) < steps.index(tests)
