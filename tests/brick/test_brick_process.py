"""A program runs in a brick process of its own: nothing of the simulator is in it, nothing of the
caller's environment reaches it, and how it ends is told truthfully."""

import json
import os

from ev3sim2d.brick_process import brick_environment


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


def test_a_crash_of_the_interpreter_is_told_as_such(run):
    result = run("import ctypes\nctypes.string_at(0)\n")
    assert result.status == "crashed"
    assert "segmentation fault" in result.reason


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
