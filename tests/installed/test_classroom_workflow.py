"""The GitHub Classroom workflow of docs/github-classroom.md: a valid workflow file (GitHub's schema),
the reporter given only the inputs it declares, students' pushes only, no hidden variant uploaded; and its
Grade step run with the installed package as the workflow runs it, giving Classroom points out of the
lesson's max."""

import base64
import json
import re
import shlex

import pytest
import yaml

from tests.installed.installed_venv import ROOT
from tests.workflow_schema import schema_problems

WORKFLOW = ROOT / "docs" / "github-classroom.yml"
DOCUMENT = ROOT / "docs" / "github-classroom.md"

# The inputs classroom-resources/autograding-grading-reporter declares, from its action.yml at tag v1
# (commit d13b5912daf5042ac1b71bc38bdb4a6bcd61d8ca),
# https://github.com/classroom-resources/autograding-grading-reporter/blob/v1/action.yml
# It reads each runner's result from the environment variable <STEP ID IN CAPITALS>_RESULTS (src/main.js).
REPORTER = "classroom-resources/autograding-grading-reporter@v1"
REPORTER_INPUTS = {"token": {"required": False}, "runners": {"required": True}}


def workflow() -> dict:
    return yaml.safe_load(WORKFLOW.read_text())


def steps() -> list[dict]:
    [job] = workflow()["jobs"].values()
    return job["steps"]


def test_the_workflow_is_valid_against_githubs_workflow_schema():
    assert schema_problems(WORKFLOW) is None, schema_problems(WORKFLOW)


def test_the_document_shows_the_workflow_file_as_it_is():
    blocks = re.findall(r"```yaml\n(.*?)```", DOCUMENT.read_text(), re.S)
    assert WORKFLOW.read_text() in blocks


def test_the_reporter_gets_only_its_declared_inputs_and_each_runners_result():
    [reporter] = [step for step in steps() if step.get("uses") == REPORTER]
    given = set(reporter.get("with", {}))
    assert given <= set(REPORTER_INPUTS), given - set(REPORTER_INPUTS)
    assert {name for name, spec in REPORTER_INPUTS.items() if spec["required"]} <= given
    ids = {step.get("id") for step in steps()}
    for runner in reporter["with"]["runners"].split(","):
        assert runner in ids
        assert re.fullmatch(r"[a-zA-Z0-9]+", runner)  # what the reporter accepts (src/main.js)
        assert reporter["env"][f"{runner.upper()}_RESULTS"] == f"${{{{ steps.{runner}.outputs.result }}}}"


def test_only_students_pushes_with_the_permissions_the_reporter_needs():
    document = workflow()
    [job] = document["jobs"].values()
    assert job["if"] == "github.actor != 'github-classroom[bot]'"  # not Classroom's own commits
    assert document["permissions"] == {"checks": "write", "actions": "read", "contents": "read"}
    assert "push" in document["on"]


def test_nothing_of_the_hidden_variants_is_uploaded():
    text = WORKFLOW.read_text()
    assert "--hidden-videos" not in text
    for step in steps():
        if str(step.get("uses", "")).startswith("actions/upload-artifact"):
            paths = step["with"]["path"].split()
            assert ".hidden" not in " ".join(paths) and "." not in paths and "*" not in " ".join(paths)


@pytest.mark.needs_linux("posix_shell")  # the step's command, as the workflow's ubuntu job's bash runs it
def test_the_grade_step_gives_classroom_points_out_of_the_lessons_max(installed, user_folder):
    [grade] = [step for step in steps() if step.get("id") == "grade"]
    command = " ".join(grade["run"].split())
    (user_folder / "main.py").write_text((ROOT / "lessons" / "line-follow" / "starter.py").read_text())
    output = user_folder / "github_output"
    output.write_text("")
    done = installed.run(
        command.replace('"$GITHUB_OUTPUT"', shlex.quote(str(output))), cwd=user_folder, shell=True
    )
    assert done.returncode in (0, 1), done.stderr  # 1: below full marks
    assert "Traceback" not in done.stderr
    [line] = output.read_text().splitlines()
    result = json.loads(base64.b64decode(line.removeprefix("result=")))
    graded = json.loads((user_folder / "grade.json").read_text())
    [submission] = graded["submissions"]
    assert result["max_score"] == graded["max_score"] == submission["max_score"]
    assert sum(test["score"] for test in result["tests"]) == submission["score"]
    assert result["status"] == ("pass" if done.returncode == 0 else "fail")
    assert (user_folder / "grade.xml").is_file()
