"""The ev3sim2d command as a user runs it: exit status, outputs, messages."""

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def cli(*args, cwd=None):
    return subprocess.run(
        [sys.executable, "-m", "ev3sim2d", *map(str, args)],
        capture_output=True,
        text=True,
        cwd=cwd or ROOT,
        timeout=120,
    )


def test_run_writes_summary_and_png(tmp_path):
    summary, png = tmp_path / "run.json", tmp_path / "end.png"
    result = cli(
        "run",
        "examples/line_follower.py",
        "--maze",
        "line",
        "--time",
        "5",
        "--summary",
        summary,
        "--png",
        png,
        "--trace",
        tmp_path / "run.npz",
    )
    assert result.returncode == 0, result.stderr
    data = json.loads(summary.read_text())
    assert data["status"] == "time_limit"
    assert data["sim_time_s"] == 5.0
    assert data["wall_time_s"] > 0
    assert len(data["fingerprint"]) == 16
    robot = data["robots"][0]
    assert set(robot) >= {"start", "end", "path_cm", "wall_contacts"}
    assert set(robot["end"]) == {"x_cm", "y_cm", "heading_deg"}
    assert robot["path_cm"] > 50
    assert png.stat().st_size > 1000 and png.read_bytes()[:4] == b"\x89PNG"
    assert (tmp_path / "run.npz").exists()


def test_same_run_twice_gives_the_same_fingerprint(tmp_path):
    prints = []
    for i in range(2):
        out = tmp_path / f"s{i}.json"
        cli("run", "examples/line_follower.py", "--maze", "line", "--time", "3", "--summary", out)
        prints.append(json.loads(out.read_text())["fingerprint"])
    assert prints[0] == prints[1]


def test_printed_lines_show_the_simulated_time(tmp_path):
    prog = tmp_path / "hello.py"
    prog.write_text("import time\nprint('hi')\ntime.sleep(2.5)\nprint('later')\n")
    result = cli("run", prog, "--maze", "empty")
    assert result.returncode == 0
    assert "[   0.000 s] hi" in result.stdout
    assert "[   2.501 s] later" in result.stdout


def test_a_crashing_program_exits_non_zero_with_its_traceback(tmp_path):
    prog = tmp_path / "crash.py"
    prog.write_text("import time\ntime.sleep(1)\n{}['missing']\n")
    summary = tmp_path / "s.json"
    result = cli("run", prog, "--summary", summary)
    assert result.returncode == 1
    assert f'File "{prog}", line 3' in result.stderr
    assert "KeyError: 'missing'" in result.stderr
    assert "at 1.00 s" in result.stderr
    assert json.loads(summary.read_text())["status"] == "error"


def test_a_hung_program_is_stopped_with_a_reason(tmp_path):
    prog = tmp_path / "spin.py"
    prog.write_text("import _thread\nlock = _thread.allocate_lock()\nlock.acquire()\nlock.acquire()\n")
    summary = tmp_path / "s.json"
    result = cli("run", prog, "--hang-after", "0.5", "--summary", summary)
    assert result.returncode == 3
    assert "without using the robot or the clock" in result.stderr
    assert json.loads(summary.read_text())["status"] == "hung"


def test_a_program_looping_forever_ends_normally_at_the_time_limit(tmp_path):
    prog = tmp_path / "forever.py"
    prog.write_text("import time\nwhile True:\n    time.sleep(0.5)\n")
    result = cli("run", prog, "--time", "3")
    assert result.returncode == 0
    assert "time limit of 3.00 s" in result.stderr


def test_a_broken_world_file_names_file_and_line(tmp_path):
    maze = tmp_path / "bad.yaml"
    maze.write_text("cell_cm: 10\ngrid: |\n  #####\n  #.Q.#\n  #####\nstart:\n  cell: [2, 1]\n")
    prog = tmp_path / "p.py"
    prog.write_text("pass\n")
    result = cli("run", prog, "--maze", maze)
    assert result.returncode == 2
    assert f"{maze}:4" in result.stderr
    assert "Q" in result.stderr
    assert "Traceback" not in result.stderr


def test_unknown_maze_lists_the_shipped_ones(tmp_path):
    prog = tmp_path / "p.py"
    prog.write_text("pass\n")
    result = cli("run", prog, "--maze", "lnie")
    assert result.returncode == 2
    assert "line" in result.stderr and "Traceback" not in result.stderr


def test_missing_program_and_syntax_error(tmp_path):
    result = cli("run", tmp_path / "nope.py")
    assert result.returncode == 2 and "no such program file" in result.stderr
    bad = tmp_path / "bad.py"
    bad.write_text("print('a'\n")
    result = cli("run", bad)
    assert result.returncode == 1
    assert "line 1" in result.stderr and "Traceback" not in result.stderr


def test_mazes_lists_the_shipped_worlds_and_names_work_from_anywhere(tmp_path):
    result = cli("mazes")
    for name in ("empty", "line", "maze", "colors"):
        assert name in result.stdout
    prog = tmp_path / "p.py"
    prog.write_text("pass\n")
    assert cli("run", prog, "--maze", "line.yaml", cwd=tmp_path).returncode == 0
    assert cli("run", prog, "--maze", "mazes/line.yaml", cwd=tmp_path).returncode == 0


def test_robot_file_replaces_the_port_mapping(tmp_path):
    from ev3sim2d.world.robot_spec import default_robot

    text = Path(default_robot().source).read_text()
    swapped = text.replace("{port: B, kind: large, wheel: left}", "{port: D, kind: large, wheel: left}")
    assert swapped != text
    robot = tmp_path / "robot.yaml"
    robot.write_text(swapped)
    prog = tmp_path / "p.py"
    prog.write_text(
        "from ev3dev2.motor import MoveTank, OUTPUT_D, OUTPUT_C\n"
        "MoveTank(OUTPUT_D, OUTPUT_C).on_for_rotations(50, 50, 1)\n"
    )
    summary = tmp_path / "s.json"
    assert cli("run", prog, "--robot", robot, "--summary", summary).returncode == 0
    end = json.loads(summary.read_text())["robots"][0]["end"]
    start = json.loads(summary.read_text())["robots"][0]["start"]
    assert abs(end["x_cm"] - start["x_cm"] - 17.59) < 0.2


def test_runs_iterate_sets_of_strings_the_same_way_every_time(tmp_path):
    prog = tmp_path / "sets.py"
    prog.write_text('print(list({"alpha", "beta", "gamma", "delta", "epsilon", "zeta"}))\n')
    outputs = set()
    for i in range(3):
        summary = tmp_path / f"s{i}.json"
        env = {k: v for k, v in __import__("os").environ.items() if k != "PYTHONHASHSEED"}
        subprocess.run(
            [sys.executable, "-m", "ev3sim2d", "run", str(prog), "--quiet", "--summary", str(summary)],
            check=True,
            timeout=60,
            env=env,
        )
        outputs.add(json.loads(summary.read_text())["fingerprint"])
    assert len(outputs) == 1


def test_lessons_names_a_broken_lesson_of_a_teachers_and_still_lists_the_others(tmp_path):
    broken = tmp_path / "mine" / "broken"
    broken.mkdir(parents=True)
    (broken / "lesson.yaml").write_text(
        "title: Broken\ngoal: Nothing.\ntime_s: 10\nvariants: []\nchecks: []\n"
    )
    result = cli("lessons", "--dir", tmp_path / "mine")
    assert result.returncode == 2
    assert str(broken / "lesson.yaml") in result.stderr
    listed = [line.split()[0] for line in result.stdout.splitlines()]
    assert listed == sorted(p.parent.name for p in (ROOT / "lessons").glob("*/lesson.yaml"))


def test_examples_will_not_copy_into_a_file(tmp_path):
    (tmp_path / "examples").write_text("not a folder")
    result = cli("examples", cwd=tmp_path)
    assert result.returncode == 2 and "is a file" in result.stderr
