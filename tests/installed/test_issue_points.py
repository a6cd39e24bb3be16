"""Issue 15 ("A teacher's first hour"), point by point, and the test that runs each against the installed
wheel (tests/installed/, a fresh venv, a folder that is not the checkout; `.ci/run` builds the wheel once
and runs them). "in-tree" marks a check that needs no installed package (a document's text, a schema).
The test below fails when a test named here no longer exists.

Install and first steps
- `ev3sim2d --version`
    test_first_steps.py::test_version_is_the_packages
- `lessons` lists the lessons, one line each (a teacher's own folder too)
    test_first_steps.py::test_lessons_lists_each_shipped_lesson_on_a_line_with_its_title_and_goal
    test_first_steps.py::test_lessons_lists_a_teachers_own_folder_too
- `examples [DIR]` copies the example programs out of the wheel, and the README's command runs one
    test_first_steps.py::test_examples_copies_every_example_and_the_readme_command_runs_it
    test_first_steps.py::test_examples_leaves_a_students_edited_copy_alone_unless_forced
- `mazes` lists the worlds, one line each
    test_first_steps.py::test_mazes_lists_every_shipped_world_with_its_title
- the README: activating the venv, installing from a wheel (the fixture installs the wheel as the README
  says); every command in README and docs/ run by a doc-test
    test_doc_commands.py::test_every_command_in_the_document_runs
    test_doc_commands.py::test_the_reader_finds_commands_leaves_synopses_and_honours_skip_markers
    test_doc_commands.py::test_skip_markers_are_few_and_each_says_why
- `--robot NAME` takes the built-in robots by name
    test_first_steps.py::test_a_shipped_world_and_robot_are_found_by_name
- a world with two starts ships: `ev3sim2d run a.py b.py`
    test_first_steps.py::test_two_programs_run_without_a_world_of_their_own

Grading outputs a Classroom can use
- the wheel ships no hidden variant, solution or wrong program; the teacher's lesson folder has them
    test_wheel_contents.py::test_the_wheel_holds_no_hidden_variant_solution_or_wrong_program_anywhere
    test_wheel_contents.py::test_the_wheel_holds_the_worlds_robots_and_examples_a_user_starts_with
    test_grade_outputs.py::test_a_class_graded_with_hidden_variants_into_csv_junit_and_json  (--hidden)
- the Classroom workflow: permissions, students' pushes only, partial points, nothing hidden uploaded
    test_classroom_workflow.py::test_the_workflow_is_valid_against_githubs_workflow_schema  (in-tree)
    test_classroom_workflow.py::test_the_reporter_gets_only_its_declared_inputs_and_each_runners_result
    test_classroom_workflow.py::test_only_students_pushes_with_the_permissions_the_reporter_needs
    test_classroom_workflow.py::test_nothing_of_the_hidden_variants_is_uploaded
    test_classroom_workflow.py::test_the_grade_step_gives_classroom_points_out_of_the_lessons_max
- `--csv` with a BOM, `--junit` with the XSD's attributes only, a class with failures exits 1
    test_grade_outputs.py::test_a_class_graded_with_hidden_variants_into_csv_junit_and_json
- exit codes in `--help` (and in docs/lessons.md: tests/grading/test_grade_outputs.py, in-tree)
    test_grade_outputs.py::test_exit_codes_are_in_the_help_and_a_usage_error_is_2
- the JSON keeps what each visible variant printed, trimmed and marked, none of a hidden one's
    test_grade_outputs.py::test_a_class_graded_with_hidden_variants_into_csv_junit_and_json
- `grade ... | head` ends quietly; a syntax error said once, with its line and a caret
    test_grade_outputs.py::test_grade_into_head_ends_quietly
    test_grade_outputs.py::test_a_syntax_error_is_said_once_with_its_line_and_a_caret

A Python API and notebooks
- `simulate` on a program file or source, a world by name, file or object; timelines as numpy arrays, a
  table, printed output; `.png()`, `.video()` (through `_repr_html_`), `.plot()` (the `plot` extra, and
  the install command without it); a result shows itself in Jupyter
    test_python_api.py::test_simulate_runs_a_shipped_example_in_a_shipped_world_by_name
    test_python_api.py::test_a_chart_with_the_plot_extra_and_the_install_command_without_it
- the notebook docs/python-api.ipynb executed (nbclient), on a kernel of the installed venv
    test_notebook.py::test_the_notebook_runs_on_the_installed_package_and_shows_the_run_the_chart_and_the_table
- the API reference generated from docstrings: tests/api/test_api_reference.py (in-tree)
- worlds built in Python (`World.from_text`, a cell, a region), saved as YAML and read back
    test_python_api.py::test_a_world_built_in_python_is_saved_read_back_and_run_from_the_command_line

Extending
- a new device type: one class and an entry point, in a package of one's own pip-installed next to
  ev3sim2d (docs/devices.md); no raw KeyError for an unknown kind
    test_device_plugin.py::test_the_pages_package_installed_with_pip_gives_run_its_kind
    test_device_plugin.py::test_without_the_package_the_robot_file_names_the_unknown_kind

Done when
- the README's first screen: what it is, a picture, the two commands, what to do next  (in-tree)
    test_issue_points.py::test_the_readmes_first_screen_says_what_picture_commands_what_next
"""

import ast
import re
from pathlib import Path

from tests.installed.installed_venv import ROOT

HERE = Path(__file__).parent


def named_tests() -> list[tuple[str, str]]:
    return re.findall(r"^\s+(test_\w+\.py)::(test_\w+)", __doc__, flags=re.MULTILINE)


def test_every_test_the_checklist_names_exists():
    missing = []
    for file, name in named_tests():
        path = HERE / file
        defined = (
            {node.name for node in ast.walk(ast.parse(path.read_text())) if isinstance(node, ast.FunctionDef)}
            if path.is_file()
            else set()
        )
        if name not in defined:
            missing.append(f"{file}::{name}")
    assert len(named_tests()) > 25 and not missing, missing


def test_the_readmes_first_screen_says_what_picture_commands_what_next():
    readme = (ROOT / "README.md").read_text()
    first_screen = readme[: readme.index("\n## ", readme.index("## What next") + 1)]
    picture = re.search(r"!\[[^\]]+\]\(([^)]+)\)", first_screen)
    assert picture and (ROOT / picture[1]).is_file()
    order = [
        first_screen.index("python-ev3dev2"),  # what it is
        picture.start(),
        first_screen.index("ev3sim2d run examples/line_follower.py"),  # the two commands
        first_screen.index("python -m pytest"),
        first_screen.index("## What next"),
        *(
            first_screen.index(f"**{part}**")
            for part in ("Lessons", "Editor", "Grading", "Python and notebooks")
        ),
    ]
    assert order == sorted(order), order
