"""A new user's first steps with the installed package (a wheel in a fresh venv), in a folder of their
own: the version, the lessons, the example programs, the worlds, robots by name, two programs at once."""

import configparser
import json
import zipfile
from pathlib import Path

import yaml

from tests.installed.installed_venv import ROOT


def shipped(folder: str) -> dict[str, dict]:
    """The repository's lesson.yaml or maze files by name, as the wheel should ship them."""
    if folder == "lessons":
        return {
            p.parent.name: yaml.safe_load(p.read_text()) for p in (ROOT / "lessons").glob("*/lesson.yaml")
        }
    return {p.stem: yaml.safe_load(p.read_text()) for p in (ROOT / folder).glob("*.yaml")}


def test_the_installed_package_is_the_wheels_not_the_checkout(installed, user_folder):
    done = installed.run("python", "-c", "import ev3sim2d; print(ev3sim2d.__file__)", cwd=user_folder)
    assert done.returncode == 0, done.stderr
    assert Path(done.stdout.strip()).is_relative_to(installed.venv)


def test_version_is_the_packages(installed, user_folder):
    metadata = configparser.ConfigParser()
    metadata.read(ROOT / "setup.cfg")
    done = installed.run("ev3sim2d", "--version", cwd=user_folder)
    assert done.returncode == 0, done.stderr
    first, second = done.stdout.splitlines()[:2]
    assert first == f"ev3sim2d {metadata['metadata']['version']}"
    assert second.startswith("isolation: ")


def test_lessons_lists_each_shipped_lesson_on_a_line_with_its_title_and_goal(installed, user_folder):
    done = installed.run("ev3sim2d", "lessons", cwd=user_folder)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    lessons = shipped("lessons")
    assert [line.split()[0] for line in lines] == sorted(lessons)
    for line in lines:
        lesson = lessons[line.split()[0]]
        assert f"{lesson['title']}: " in line
        assert " ".join(lesson["goal"].split()).startswith(line.split(f"{lesson['title']}: ", 1)[1])


def test_lessons_lists_a_teachers_own_folder_too(installed, user_folder):
    mine = user_folder / "my-lessons" / "spin"
    mine.mkdir(parents=True)
    (mine / "lesson.yaml").write_text(
        "title: Spin\ngoal: Turn round twice. Then stop.\ntime_s: 10\n"
        "variants:\n  - {name: loop, world: line}\n"
        "checks:\n  - {name: lap, kind: lap, goal: true, points: 1, min_away_cm: 60, min_path_cm: 350}\n"
    )
    done = installed.run("ev3sim2d", "lessons", "--dir", "my-lessons", cwd=user_folder)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines()[-1].split() == [
        str(Path("my-lessons", "spin")),
        "Spin:",
        "Turn",
        "round",
        "twice.",
    ]
    missing = installed.run("ev3sim2d", "lessons", "--dir", "nowhere", cwd=user_folder)
    assert missing.returncode == 2 and "nowhere" in missing.stderr


def test_examples_copies_every_example_and_the_readme_command_runs_it(installed, user_folder):
    done = installed.run("ev3sim2d", "examples", cwd=user_folder)
    assert done.returncode == 0, done.stderr
    expected = sorted(
        p.relative_to(ROOT / "examples")
        for p in (ROOT / "examples").rglob("*")
        if p.suffix in (".py", ".yaml") and "__pycache__" not in p.parts
    )
    copied = sorted(p.relative_to(user_folder / "examples") for p in (user_folder / "examples").rglob("*.*"))
    assert copied == expected
    for name in expected:
        assert (user_folder / "examples" / name).read_bytes() == (ROOT / "examples" / name).read_bytes()
    run = installed.run(
        "ev3sim2d", "run", "examples/line_follower.py", "--maze", "line", "--time", "5",
        "--summary", "run.json", cwd=user_folder,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    assert json.loads((user_folder / "run.json").read_text())["robots"][0]["path_cm"] > 50


def test_examples_leaves_a_students_edited_copy_alone_unless_forced(installed, user_folder):
    installed.run("ev3sim2d", "examples", "mine", cwd=user_folder)
    edited = user_folder / "mine" / "leds.py"
    edited.write_text("# my own\n")
    again = installed.run("ev3sim2d", "examples", "mine", cwd=user_folder)
    assert again.returncode == 2 and "leds.py" in again.stderr and "--force" in again.stderr
    assert edited.read_text() == "# my own\n"
    forced = installed.run("ev3sim2d", "examples", "mine", "--force", cwd=user_folder)
    assert forced.returncode == 0 and edited.read_bytes() == (ROOT / "examples" / "leds.py").read_bytes()


def test_mazes_lists_every_shipped_world_with_its_title(installed, user_folder):
    done = installed.run("ev3sim2d", "mazes", cwd=user_folder)
    assert done.returncode == 0, done.stderr
    listed = {line.split()[0]: line.split(None, 1)[1] for line in done.stdout.splitlines()}
    assert listed == {name: maze["title"] for name, maze in shipped("mazes").items()}


def test_a_shipped_world_and_robot_are_found_by_name(installed, user_folder):
    robots = [Path(name).stem for name in zipfile.ZipFile(installed.wheel).namelist()
              if name.startswith("ev3sim2d/robots/") and name.endswith(".yaml")]  # fmt: skip
    assert robots
    (user_folder / "prog.py").write_text("import time\ntime.sleep(1)\nprint('done')\n")
    for robot in robots:
        done = installed.run(
            "ev3sim2d", "run", "prog.py", "--maze", "line", "--robot", robot, cwd=user_folder
        )
        assert done.returncode == 0, done.stderr
        assert "done" in done.stdout
    wrong = installed.run("ev3sim2d", "run", "prog.py", "--robot", "no-such-robot", cwd=user_folder)
    assert wrong.returncode == 2
    assert "no-such-robot" in wrong.stderr and robots[0] in wrong.stderr


def test_two_programs_run_without_a_world_of_their_own(installed, user_folder):
    for name in ("a.py", "b.py"):
        (user_folder / name).write_text(
            "from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank\n"
            "MoveTank(OUTPUT_B, OUTPUT_C).on_for_seconds(30, 30, 1)\n"
        )
    done = installed.run("ev3sim2d", "run", "a.py", "b.py", "--summary", "run.json", cwd=user_folder)
    assert done.returncode == 0, done.stderr
    robots = json.loads((user_folder / "run.json").read_text())["robots"]
    assert len(robots) == 2
    assert robots[0]["start"] != robots[1]["start"]
    assert all(robot["path_cm"] > 10 and robot["wall_contacts"] == 0 for robot in robots)
