"""ev3sim2d on a Windows-like and a macOS-like Python: every front door works, and gives Linux's runs.

The stand-ins (other_system.py) apply to every process, the CLI's and every brick's and worker's, so
these runs take the portable paths end to end: on the Windows-like one bricks connect over loopback
TCP with a token, grading workers are spawned, nothing of Linux's sandbox is there; on the
macOS-like one bricks keep their socket pair, workers are spawned (Python does not fork by default
there), and the Linux system calls are never made.  Each must give the fingerprint the Linux path
gives: the simulation does not depend on how a brick is reached.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
FOLLOWER = REPO / "examples" / "line_follower.py"
KINDS = ("windows", "macos")


def ev3sim2d(python, *args, cwd=REPO, env=None, timeout=180) -> subprocess.CompletedProcess:
    return subprocess.run(
        [str(python), "-m", "ev3sim2d", *map(str, args)],
        capture_output=True,
        text=True,
        cwd=cwd,
        env=env,
        timeout=timeout,
    )


@pytest.fixture(scope="module")
def linux_run(tmp_path_factory) -> dict:
    """The line follower on `line` for 20 s as this (Linux) Python runs it: summary and picture."""
    folder = tmp_path_factory.mktemp("linux")
    done = ev3sim2d(
        sys.executable, "run", FOLLOWER, "--maze", "line", "--time", 20,
        "--summary", folder / "run.json", "--png", folder / "end.png", "--trace", folder / "run.npz",
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    summary = json.loads((folder / "run.json").read_text())
    return {"summary": summary, "png": (folder / "end.png").read_bytes(), "trace": folder / "run.npz"}


@pytest.mark.parametrize("kind", KINDS)
def test_every_module_imports_without_linuxs_pieces(other_systems, kind):
    """The command line, the Python API, the shim: every module of ev3sim2d and ev3dev2 imports where
    resource, fcntl, termios, pwd, grp, os.fork and the rest are missing (a module that needs one
    imports it where it is used, behind a check)."""
    script = (
        "import importlib, os, pkgutil, sys\n"
        "from ev3sim2d.simulator.bricks import shim_root\n"
        "sys.path.insert(0, str(shim_root()))  # (the shim, as a brick finds it)\n"
        "import ev3sim2d, ev3dev2\n"
        f"assert {kind!r} != 'windows' or not hasattr(os, 'fork')\n"
        "names = []\n"
        "for package in (ev3sim2d, ev3dev2):\n"
        "    for info in pkgutil.walk_packages(package.__path__, package.__name__ + '.'):\n"
        "        if not info.name.endswith('__main__'):\n"
        "            importlib.import_module(info.name)\n"
        "            names.append(info.name)\n"
        "print(len(names))\n"
    )
    done = subprocess.run([str(other_systems[kind]), "-c", script], capture_output=True, text=True, cwd=REPO)
    assert done.returncode == 0, done.stderr
    assert int(done.stdout) > 100
    if kind == "windows":
        blocked = subprocess.run(
            [str(other_systems[kind]), "-c", "import resource"], capture_output=True, text=True
        )
        assert "No module named 'resource'" in blocked.stderr  # the stand-in is really without it


@pytest.mark.parametrize("kind", KINDS)
def test_run_gives_linuxs_fingerprint_and_picture(other_systems, kind, linux_run, tmp_path):
    """The README's run, in every process without Linux's pieces: the same run, the same PNG."""
    done = ev3sim2d(
        other_systems[kind], "run", "examples/line_follower.py", "--maze", "line", "--time", 20,
        "--summary", tmp_path / "run.json", "--png", tmp_path / "end.png",
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    summary = json.loads((tmp_path / "run.json").read_text())
    assert summary["fingerprint"] == linux_run["summary"]["fingerprint"]
    assert summary["robots"] == linux_run["summary"]["robots"]
    assert (tmp_path / "end.png").read_bytes() == linux_run["png"]


@pytest.mark.parametrize("kind", KINDS)
def test_grade_scores_a_lesson_as_on_linux_and_says_what_programs_do_not_get(other_systems, kind, tmp_path):
    """grade on a lesson with hidden variants: every variant and check as on Linux, and one line and the
    JSON say which walls a class's programs lack here; --require-sandbox refuses instead."""
    lesson = REPO / "lessons" / "line-follow"
    programs = [lesson / "solution.py", lesson / "starter.py"]
    here = ev3sim2d(sys.executable, "grade", "line-follow", *programs, "--json", tmp_path / "linux.json")
    there = ev3sim2d(
        other_systems[kind], "grade", "line-follow", *programs, "--json", tmp_path / "there.json"
    )
    assert there.returncode == here.returncode == 1, there.stderr  # the starter does not pass
    linux = json.loads((tmp_path / "linux.json").read_text())
    other = json.loads((tmp_path / "there.json").read_text())
    assert other["submissions"] == linux["submissions"]
    assert other["submissions"][0]["score"] == other["max_score"]
    assert linux["isolation"]["missing"] == []
    assert other["isolation"]["missing"] == ["file confinement", "network", "orphan clean-up"]
    assert "a class's programs get no file confinement, no network, no orphan clean-up" in there.stderr
    refused = ev3sim2d(other_systems[kind], "grade", "line-follow", programs[0], "--require-sandbox")
    assert refused.returncode == 2 and "--require-sandbox" in refused.stderr, refused.stderr


def test_serve_and_join_give_the_run_of_run(other_systems, tmp_path):
    """A world served and joined by Windows-like computers: the same run as `run a.py b.py` on Linux."""
    python = other_systems["windows"]
    sumo = REPO / "examples" / "sumo.py"
    here = ev3sim2d(
        sys.executable, "run", sumo, sumo, "--maze", "sumo", "--time", 5, "--summary", tmp_path / "r.json"
    )
    assert here.returncode == 0, here.stderr
    server = subprocess.Popen(
        [str(python), "-m", "ev3sim2d", "serve", "--maze", "sumo", "--robots", "2", "--port", "0",
         "--time", "5", "--summary", str(tmp_path / "s.json")],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, cwd=REPO,
    )  # fmt: skip
    try:
        address = None
        for line in server.stdout:
            if "127.0.0.1:" in line:
                address = next(word for word in line.split() if word.startswith("127.0.0.1:")).rstrip(".,;)")
                break
        assert address, "serve said no address"
        joins = [
            subprocess.Popen([str(python), "-m", "ev3sim2d", "join", address, str(sumo)], cwd=REPO,
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            for _ in range(2)
        ]  # fmt: skip
        for join in joins:
            out, _ = join.communicate(timeout=120)
            assert join.returncode == 0, out
        server.communicate(timeout=60)
    finally:
        server.kill()
    assert server.returncode == 0
    served = json.loads((tmp_path / "s.json").read_text())
    assert served["fingerprint"] == json.loads((tmp_path / "r.json").read_text())["fingerprint"]


def test_live_runs_and_its_trace_is_the_run_of_run(other_systems, linux_run, tmp_path):
    """ev3sim2d live on a Windows-like Python: the page's API answers, and the trace written when it
    stops is the run that `run` makes on Linux."""
    port = _free_port()
    live = subprocess.Popen(
        [str(other_systems["windows"]), "-m", "ev3sim2d", "live", str(FOLLOWER), "--maze", "line",
         "--max-speed", "--time", "20", "--no-browser", "--port", str(port), "--trace", str(tmp_path / "t.npz")],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, cwd=REPO,
    )  # fmt: skip
    try:
        url = next(word for word in live.stdout.readline().split() if word.startswith("http://"))
        state = {}
        deadline = time.monotonic() + 120
        while state.get("status") != "ended" and time.monotonic() < deadline:
            time.sleep(0.2)
            base, token = url.split("#token=")  # the printed address carries the page's key
            request = urllib.request.Request(f"{base}api/state", headers={"X-Ev3sim2d-Token": token})
            with urllib.request.urlopen(request, timeout=10) as answer:
                state = json.loads(answer.read())
        assert state.get("status") == "ended", state
        live.send_signal(signal.SIGINT)
        out, _ = live.communicate(timeout=60)
    finally:
        live.kill()
    assert "the last run's trace is in" in out, out
    from ev3sim2d.results.trace import Trace

    assert Trace.load(tmp_path / "t.npz").fingerprint() == linux_run["summary"]["fingerprint"]


def test_the_other_commands_work_there(other_systems, linux_run, tmp_path):
    """mazes, lessons, examples, plot, edit and the Python API on a Windows-like Python, and on a
    macOS-like one a video: as on Linux."""
    python = other_systems["windows"]
    for command in (["mazes"], ["lessons"], ["examples", tmp_path / "mine"], ["--version"]):
        done = ev3sim2d(python, *command)
        assert done.returncode == 0, (command, done.stderr)
    assert (tmp_path / "mine" / "line_follower.py").is_file()
    plotted = ev3sim2d(python, "plot", linux_run["trace"], "--png", tmp_path / "plot.png")
    assert plotted.returncode == 0 and (tmp_path / "plot.png").stat().st_size > 1000, plotted.stderr
    api = subprocess.run(
        [str(python), "-c", "from ev3sim2d import simulate; print(simulate('examples/line_follower.py', "
         "'line', time_s=20).trace.fingerprint())"],
        capture_output=True, text=True, cwd=REPO, timeout=120,
    )  # fmt: skip
    assert api.stdout.strip() == linux_run["summary"]["fingerprint"], api.stderr
    world = tmp_path / "arena.yaml"
    port = _free_port()
    editor = subprocess.Popen(
        [str(python), "-m", "ev3sim2d", "edit", str(world), "--new", "8x6", "--no-browser", "--port", str(port)],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, cwd=REPO,
    )  # fmt: skip
    try:
        token = editor.stdout.readline().split("#token=")[1].split()[0]
        request = urllib.request.Request(
            f"http://127.0.0.1:{port}/api/world", headers={"X-Ev3sim2d-Token": token}
        )
        with urllib.request.urlopen(request, timeout=30) as answer:
            assert json.loads(answer.read())["width"] == 8
    finally:
        editor.kill()
        editor.wait()
    video = ev3sim2d(other_systems["macos"], "render", linux_run["trace"], "--video", tmp_path / "m.mp4")
    here = ev3sim2d(sys.executable, "render", linux_run["trace"], "--video", tmp_path / "l.mp4")
    assert video.returncode == here.returncode == 0, video.stderr
    assert (tmp_path / "m.mp4").read_bytes() == (tmp_path / "l.mp4").read_bytes()


def test_the_portable_path_can_be_chosen_on_linux_and_changes_nothing_of_the_run(linux_run, tmp_path):
    """EV3SIM2D_PORTABLE=1: bricks over loopback TCP and spawned grading workers on Linux, with every
    wall of Linux's sandbox still up, and the same run."""
    from ev3sim2d.brick.sandbox import linux_kernel

    env = {**os.environ, "EV3SIM2D_PORTABLE": "1"}
    done = ev3sim2d(
        sys.executable,
        "run",
        FOLLOWER,
        "--maze",
        "line",
        "--time",
        20,
        "--summary",
        tmp_path / "r.json",
        env=env,
    )
    assert done.returncode == 0, done.stderr
    assert json.loads((tmp_path / "r.json").read_text())["fingerprint"] == linux_run["summary"]["fingerprint"]
    code = (
        "from ev3sim2d.grading.grader import can_fork; from ev3sim2d.simulator.run import run_programs; "
        "from tests.inline_world import arena; import json, pathlib; p = pathlib.Path('p.py'); "
        "p.write_text('pass'); r = run_programs([p.resolve()], arena(), time_limit_s=1); "
        "print(json.dumps([can_fork(), r.sandbox[0]]))"
    )
    found = subprocess.run(
        [sys.executable, "-c", f"import sys; sys.path.insert(0, {str(REPO)!r}); {code}"],
        capture_output=True, text=True, cwd=tmp_path, env=env, timeout=120,
    )  # fmt: skip
    forked, report = json.loads(found.stdout)
    assert forked is False
    if linux_kernel():
        assert report["seccomp"] == "on" and report["landlock"].startswith("on"), report


def test_a_macos_like_grader_spawns_its_workers(other_systems):
    """macOS: Python does not fork by default there (a forked child of a process that loaded the
    system's frameworks may crash), so neither does the grader."""
    done = subprocess.run(
        [str(other_systems["macos"]), "-c", "from ev3sim2d.grading.grader import can_fork; print(can_fork())"],
        capture_output=True, text=True, cwd=REPO,
    )  # fmt: skip
    assert done.stdout.strip() == "False", done.stderr


def test_the_command_line_keeps_pythons_own_flags():
    """ev3sim2d no longer starts itself again (it did, for PYTHONHASHSEED): `python -X ...` holds for
    the whole command, and its exit status is its own."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONHASHSEED"}
    done = subprocess.run(
        [sys.executable, "-X", "importtime", "-m", "ev3sim2d", "mazes"],
        capture_output=True, text=True, cwd=REPO, env=env, timeout=60,
    )  # fmt: skip
    assert done.returncode == 0
    assert "ev3sim2d.commands.mazes" in done.stderr  # -X importtime reached the command's own imports
    wrong = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "run", "nowhere.py"], capture_output=True, env=env
    )
    assert wrong.returncode == 2


def test_render_and_show_draw_what_linux_draws(other_systems, linux_run, tmp_path):
    done = ev3sim2d(other_systems["windows"], "render", linux_run["trace"], "--png", tmp_path / "again.png")
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "again.png").read_bytes() == linux_run["png"]
    shown = ev3sim2d(other_systems["macos"], "show", "line", "--png", tmp_path / "line.png")
    assert shown.returncode == 0 and (tmp_path / "line.png").stat().st_size > 1000, shown.stderr


def test_a_program_that_never_yields_is_stopped_as_hung_without_msg_dontwait(other_systems, tmp_path):
    """Windows has no MSG_DONTWAIT: the simulator must still notice a brick that spins without a word
    (it used to block reading it, and `while True: pass` hung for ever)."""
    program = tmp_path / "spin.py"
    program.write_text("import _thread\nlock = _thread.allocate_lock()\nlock.acquire()\nlock.acquire()\n")
    done = ev3sim2d(other_systems["windows"], "run", program, "--time", 30, "--hang-after", 1, timeout=60)
    assert done.returncode == 3, done.stderr  # hung
    assert "stopped" in done.stderr and "without using the robot or the clock" in done.stderr


def test_the_brick_ends_with_its_simulator_where_there_is_no_pdeathsig(other_systems, tmp_path):
    """macOS has no PDEATHSIG: a brick whose simulator is killed (SIGKILL, no clean-up) ends by itself
    within a second, with everything in its session."""
    program = tmp_path / "spin.py"
    program.write_text(
        "import os, time\nopen('pid', 'w').write(str(os.getpid()))\nwhile True:\n    time.sleep(1)\n"
    )
    (tmp_path / "scratch").mkdir()
    simulator = subprocess.Popen(
        [str(other_systems["macos"]), "-m", "ev3sim2d", "run", str(program), "--time", "600"],
        cwd=REPO, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        env={**os.environ, "TMPDIR": str(tmp_path / "scratch")},
    )  # fmt: skip
    try:
        pid_files = []
        deadline = time.monotonic() + 60
        while not pid_files and time.monotonic() < deadline:
            time.sleep(0.1)
            pid_files = list((tmp_path / "scratch").glob("ev3sim2d-brick-*/*/pid"))  # (its working folder)
        assert pid_files, "the brick never started"
        time.sleep(0.2)
        brick = int(pid_files[0].read_text())
        simulator.kill()
        simulator.wait()
        deadline = time.monotonic() + 3
        while _alive(brick) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert not _alive(brick), "the brick outlived its simulator"
    finally:
        simulator.kill()


def test_output_a_console_cannot_show_is_escaped_not_an_error(tmp_path):
    """A Windows console or redirected output there is cp1252: a program printing π, and a class with
    Łukasz.py, are shown with backslash escapes, never a UnicodeEncodeError or an internal error."""
    program = tmp_path / "Łukasz.py"
    program.write_text("print('π ≈ 3.14')\n", encoding="utf-8")
    env = {**os.environ, "PYTHONIOENCODING": "cp1252"}
    done = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "run", str(program), "--time", "1"],
        capture_output=True, cwd=tmp_path, env=env, timeout=120,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert b"\\u03c0 \\u2248 3.14" in done.stdout
    graded = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "grade", "line-follow", str(program)],
        capture_output=True, cwd=tmp_path, env=env, timeout=300,
    )  # fmt: skip
    assert graded.returncode == 1, graded.stderr  # it scores 0: not an internal error (4)
    assert b"\\u0141ukasz.py" in graded.stdout


def test_a_folder_with_an_umlaut_runs_under_a_c_locale(tmp_path):
    """LC_ALL=C without UTF-8 mode: this process's file names are ASCII, the brick's UTF-8; the
    program's path still reaches the brick as the same file."""
    folder = tmp_path / "Übung ä"
    folder.mkdir()
    program = folder / "prog.py"
    program.write_text("print('hello')\n")
    env = {**os.environ, "LC_ALL": "C", "PYTHONUTF8": "0", "PYTHONIOENCODING": ""}
    done = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "run", os.fsencode(program), "--time", "1"],
        capture_output=True, env=env, timeout=120,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert b"hello" in done.stdout


def _free_port() -> int:
    import socket

    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def _alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


@pytest.mark.parametrize("kind", ["windows", "macos"])
def test_the_editor_lines_and_init_work_there(other_systems, kind, tmp_path):
    """What an editor needs, on the other systems: a failing run's one-line place (a program stopped as
    stuck too, where its brick's main thread answers for it) and `init vscode`."""
    python = other_systems[kind]
    (tmp_path / "zero.py").write_text("import time\ntime.sleep(0.2)\nx = 1 / 0\n")
    (tmp_path / "stuck.py").write_text(
        "import _thread\nlock = _thread.allocate_lock()\nlock.acquire()\nlock.acquire()\n"
    )
    failed = ev3sim2d(python, "run", "zero.py", cwd=tmp_path)
    assert "zero.py:3: error: ZeroDivisionError: division by zero" in failed.stderr.splitlines(), (
        failed.stderr
    )
    stuck = ev3sim2d(python, "run", "stuck.py", "--hang-after", 1, cwd=tmp_path)
    assert "stuck.py:4: error: stuck here, so the run was stopped (thread MainThread)" in stuck.stderr, (
        stuck.stderr
    )
    assert ev3sim2d(python, "init", "vscode", cwd=tmp_path).returncode == 0
    settings = json.loads((tmp_path / ".vscode" / "settings.json").read_text())
    assert settings["ev3sim2d.world"] == "line" and settings["ev3sim2d.debugToken"]
    stopped = subprocess.run(  # the debugger's prompt, through the portable brick's connection
        [str(python), "-m", "ev3sim2d", "run", "zero.py", "--debug"],
        input="n\np time.monotonic() > 0\nc\n", capture_output=True, text=True, cwd=tmp_path, timeout=120,
    )  # fmt: skip
    assert "stopped at zero.py:1 in <module>" in stopped.stdout and "(ev3sim2d) True" in stopped.stdout
