"""A program runs in a brick process of its own: nothing of the simulator is in it, nothing of the
caller's environment reaches it, and how it ends is told truthfully."""

import json
import os

import pytest

from ev3sim2d.simulator.bricks import PYTHON_P, brick_environment


def printed(result):
    return [line.text for line in result.trace.output]


def test_nothing_of_the_world_or_the_grader_is_loaded_in_the_brick(run):
    result = run(
        """
        import gc, json, sys
        ours = sorted(m for m in sys.modules if m.startswith("ev3sim2d"))
        kinds = sorted({type(o).__name__ for o in gc.get_objects()} & {"Simulation", "World", "Grid",
                       "Trace", "Lesson", "Session", "BrickPort", "Robot", "Physics"})
        print(json.dumps([ours, kinds]))
        """
    )
    ours, kinds = json.loads(printed(result)[0])
    assert all(m == "ev3sim2d" or m.startswith(("ev3sim2d.brick", "ev3sim2d.protocol")) for m in ours), ours
    assert kinds == []


def test_the_brick_gets_a_short_fixed_environment_not_the_callers(run, monkeypatch):
    monkeypatch.setenv("GITHUB_TOKEN", "secret-token-of-the-teacher")
    monkeypatch.setenv("PYTHONHASHSEED", "random")
    result = run("import os, json\nprint(json.dumps(dict(os.environ)))\n")
    environment = json.loads(printed(result)[0])
    assert "GITHUB_TOKEN" not in environment
    assert environment["PYTHONHASHSEED"] == "0"
    assert set(environment) == set(brick_environment(__import__("pathlib").Path("/x")))


def test_the_brick_is_another_process_in_a_folder_of_its_own(run, tmp_path):
    result = run("import os\nprint(os.getpid(), os.getcwd())\n")
    pid, cwd = printed(result)[0].split()
    assert int(pid) != os.getpid()
    assert not cwd.startswith(str(tmp_path))
    assert not os.path.exists(cwd)  # the scratch folder is gone with the run


@pytest.mark.needs_linux("signals")  # told by the signal that ended it: SIGSEGV
def test_a_crash_of_the_interpreter_is_told_as_such(run):
    result = run("import ctypes\nctypes.string_at(0)\n")
    assert result.status == "crashed"
    assert "segmentation fault" in result.reason


@pytest.mark.needs_linux("signals")  # os.kill(..., SIGKILL)
def test_a_program_that_kills_its_own_process_ends_the_run_with_what_it_did(run):
    result = run(
        """
        import os, signal, time
        from ev3dev2.motor import LargeMotor, OUTPUT_B
        LargeMotor(OUTPUT_B).on(30)
        time.sleep(1)
        os.kill(os.getpid(), signal.SIGKILL)
        """
    )
    assert result.status == "crashed"
    assert result.sim_time_s >= 1.0
    assert result.trace.poses(0)[-1][0] != result.trace.poses(0)[0][0]  # it drove before it died


def test_sounds_and_frames_forged_through_the_link_cannot_choke_the_simulator_or_the_video(run, tmp_path):
    """A student calls the shim's link directly: absurd beeps (a billion repeats, a text frequency,
    infinite durations) and an LCD frame flood, all at no cost in time. The trace keeps what is
    playable and a bounded number of events, and the video of the run is still made, quickly."""
    result = run(
        """
        from ev3dev2 import _link
        import time
        _link.call("sound", "beep", {"notes": [{"frequency": "x", "repeats": 10**9, "length_ms": 1e-308}] * 10**4,
                                     "duration": float("inf"), "volume": -5, "evil": "y" * 10**6})
        _link.call("sound", "set_volume", {"pct": float("nan")})
        for i in range(2500):
            _link.call("display", bytes(178 * 128))
        time.sleep(1)
        """
    )
    assert result.status == "finished", result.reason
    sounds = [e for e in result.trace.events if e[2] == "sound"]
    beep = sounds[0][3]
    assert "evil" not in beep and "duration" not in beep and beep["volume"] == 0.0
    assert len(beep["notes"]) == 100 and beep["notes"][0] == {"repeats": 100, "length_ms": 1e-308}
    assert len(result.trace.lcd_frames) == 1 and result.trace.result["dropped_events"] > 0  # (all alike)
    over = run(
        'from ev3dev2 import _link\n_link.call("sound", "beep", {"notes": [{"repeats": 10**9, "length_ms": 1e308}] * 10**4})\n'
    )
    assert over.status == "crashed" and "SOUND_SECONDS" in over.reason  # past a budget: that brick's end
    from ev3sim2d.render.timeline import sound_spans

    assert len(sound_spans(result.trace)) <= 100 * 100


SUBREAPER_SCRIPT = """
import os, subprocess, sys, time
sys.path.insert(0, os.getcwd())
from pathlib import Path
from ev3sim2d.simulator.bricks import become_subreaper
from ev3sim2d.simulator.run import run_programs
from tests.inline_world import arena
assert become_subreaper()
mine = subprocess.Popen(["sleep", "60"])  # a child of this process's own: a browser, a test helper
program = Path(sys.argv[1])
program.write_text(
    "import os, sys, time\\n"
    "if os.fork() == 0:\\n"  # an orphan once the brick is gone (a real sleep, not the brick's clock)
    "    os.execv(sys.executable, [sys.executable, '-c', 'import time; time.sleep(60)'])\\n"
    "time.sleep(0.5)\\n"
)
result = run_programs([program], arena(), time_limit_s=5)
time.sleep(0.2)
children = [int(p) for p in os.listdir("/proc") if p.isdigit() and
            open(f"/proc/{p}/stat").read().rsplit(")", 1)[1].split()[1] == str(os.getpid())]
print(result.status, mine.poll() is None, sorted(set(children) - {mine.pid}))
mine.kill()
"""


@pytest.mark.needs_linux("linux_kernel", "fork", "proc", "sleep_command")  # PR_SET_CHILD_SUBREAPER
def test_a_subreaper_ends_a_bricks_orphans_and_leaves_its_own_children_alone(tmp_path):
    """Orphans of a brick come back to the process that ran it (a subreaper), which kills them; a child it
    started itself (the live page's browser, a test runner's helper) is not an orphan and lives on."""
    import subprocess
    import sys
    from pathlib import Path

    script = tmp_path / "subreaper.py"
    script.write_text(SUBREAPER_SCRIPT)
    done = subprocess.run(
        [sys.executable, *PYTHON_P, str(script), str(tmp_path / "forks.py")],
        capture_output=True, text=True, timeout=120, cwd=Path(__file__).resolve().parents[2],
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["finished", "True", "[]"], done.stdout
