"""A program started as on a real EV3 finds what it finds there: site's builtins, the brick's name and
machine, python-ev3dev2's platform modules, its arguments in sys.argv.

On an EV3 running ev3dev-stretch, Brickman's file browser and `brickrun` start the program's file
itself: console-runner's server spawns the command it is given (ev3dev/console-runner, src/server.vala:
`proc = launcher.spawnv (args)`), and the file's first line `#!/usr/bin/env python3` (python-ev3dev2
2.1.0, README.rst: "The first line should be included in every Python program you write for ev3dev")
starts Python with `site`.  The values of the machine are those of the last ev3dev-stretch release,
R3, image ev3dev-stretch-ev3-generic-2020-04-10 (https://github.com/ev3dev/ev3dev/releases).
"""

from __future__ import annotations

import ast
import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
EV3_UNAME = (
    "Linux",
    "ev3dev",
    "4.14.117-ev3dev-2.3.5-ev3",
    "#1 PREEMPT Sat Mar 7 12:54:39 CST 2020",
    "armv5tejl",
)


def lines(result, stream: str = "stdout") -> list[str]:
    return [line.text for line in result.trace.output if line.stream == stream]


# ---------------------------------------------------------------- site's builtins: exit() and quit()


def test_a_program_that_ends_with_exit_finishes_as_after_sys_exit(run):
    """CPython's Lib/site.py, setquit(): "Define new builtins 'quit' and 'exit'. These are objects which
    make the interpreter exit when called" (_sitebuiltins.Quitter, whose repr says how to leave the
    interpreter: "Use exit() or Ctrl-D (i.e. EOF) to exit" on Linux); the brick's Python starts with -S,
    which adds none of them, while a program on an EV3 runs with site (module docstring)."""
    result = run(
        """\
        print(repr(exit))
        print(repr(quit))
        print(type(exit).__module__, type(exit).__name__, callable(copyright), callable(help))
        exit()
        print("not reached")
        """
    )
    assert result.status == "finished", result.reason
    assert lines(result) == [
        "Use exit() or Ctrl-D (i.e. EOF) to exit",
        "Use quit() or Ctrl-D (i.e. EOF) to exit",
        "_sitebuiltins Quitter True True",
    ]


def test_exit_zero_and_quit_finish_and_exit_with_a_number_is_that_status(run):
    """site's Quitter raises SystemExit(code) (CPython Lib/_sitebuiltins.py); Python's docs, SystemExit:
    "if it is an integer, it specifies the system exit status ...; if it is None, the exit status is
    zero": exit(0) and quit() end the program as finished, exit(3) ends it with that status."""
    assert run("exit(0)\n").status == "finished"
    assert run("import time\ntime.sleep(0.5)\nquit()\nprint('not reached')\n").status == "finished"
    failed = run("exit(3)\n")
    assert failed.status == "error"
    assert (failed.error["type"], failed.error["message"]) == ("SystemExit", "3")


def test_exit_with_a_message_prints_it_to_stderr_and_ends_as_an_error(run):
    """Python's docs, SystemExit: "if it has another type (such as a string), the object's value is
    printed and the exit status is one" (CPython Python/pythonrun.c, handle_system_exit, prints it to
    sys.stderr); `exit("message")` raises SystemExit("message") (Lib/_sitebuiltins.py, Quitter.__call__).
    On an EV3 the message is on the program's stderr (brickrun passes it on); here it is a stderr line of
    the run, which ends with the program's error, its traceback ending at the program's own line."""
    result = run(
        """\
        print("looking for the line")
        exit("no line found: put the robot on the line")
        """
    )
    assert result.status == "error"
    assert lines(result) == ["looking for the line"]
    assert lines(result, "stderr") == ["no line found: put the robot on the line"]
    assert result.error["type"] == "SystemExit"
    assert result.error["line"] == 2
    assert "_sitebuiltins" not in result.error["traceback"]


# ---------------------------------------------------------------- the brick's name and machine


def test_the_brick_is_called_ev3dev_and_is_an_armv5_running_ev3dev_stretch(run):
    """The host name of an ev3dev-stretch image is `ev3dev` (ev3dev/docker-library,
    ev3dev-stretch/layers/base/brickstrap/_tar-only/etc/hostname); `uname -a` on the image
    ev3dev-stretch-ev3-generic-2020-04-10 says `Linux ev3dev 4.14.117-ev3dev-2.3.5-ev3 #1 PREEMPT Sat Mar
    7 12:54:39 CST 2020 armv5tejl` (https://github.com/ev3dev/ev3dev/issues/1411, its ev3dev-sysinfo:
    "Kernel version: 4.14.117-ev3dev-2.3.5-ev3"; also ev3dev/ev3dev#1442: `uname -r`).  CPython's
    platform.uname() is os.uname()'s, and its processor '' where `uname -p` says "unknown" (Debian's).
    The brick's own machinery keeps the real machine: the sandbox, entered after the program's machine
    is installed, picks its seccomp filter by platform.machine()."""
    result = run(
        """\
        import os, platform, socket
        print(socket.gethostname(), socket.getfqdn(), platform.node(), os.uname().nodename)
        print(tuple(os.uname()))
        print(tuple(platform.uname()))
        print(platform.system(), platform.release(), platform.machine(), repr(platform.processor()))
        print(platform.version())
        if platform.machine().startswith("armv5"):
            print("on the EV3")
        """
    )
    assert result.status == "finished", result.reason
    assert lines(result) == [
        "ev3dev ev3dev ev3dev ev3dev",
        repr(EV3_UNAME),
        repr((*EV3_UNAME, "")),
        "Linux 4.14.117-ev3dev-2.3.5-ev3 armv5tejl ''",
        "#1 PREEMPT Sat Mar 7 12:54:39 CST 2020",
        "on the EV3",
    ]
    assert "armv5tejl" not in json.dumps(
        result.sandbox
    )  # (seccomp: "off: no filter for the ... architecture")


def test_the_brick_has_one_cpu(run):
    """/proc/cpuinfo on an EV3 lists one processor, `processor : 0`, an ARM926EJ-S (model name "ARM926EJ-S
    rev 5 (v5l)", https://gist.github.com/jabrena/b31585ee6f6b8b3deb00); so os.cpu_count() is 1 there,
    and a pool sized by it (multiprocessing, concurrent.futures) has the same size on every computer."""
    result = run(
        """\
        import multiprocessing, os
        print(os.cpu_count(), multiprocessing.cpu_count())
        print(sorted(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else [0])
        print(os.process_cpu_count() if hasattr(os, "process_cpu_count") else 1)
        """
    )
    assert result.status == "finished", result.reason
    assert lines(result) == ["1 1", "[0]", "1"]


# ---------------------------------------------------------------- python-ev3dev2's platform modules


def test_every_platform_module_of_python_ev3dev2_imports_as_on_an_ev3(run):
    """python-ev3dev2 2.1.0 ships ev3dev2/_platform/{ev3,evb,pistorms,brickpi,brickpi3,fake}.py, and
    ev3dev2/__init__.py's get_current_platform() reads /sys/class/board-info/*/uevent, where an EV3's
    BOARD_INFO_MODEL is "LEGO MINDSTORMS EV3" (ev3dev-sysinfo in ev3dev/ev3dev#1411): 'ev3'.  A program
    may import any of the modules, and finds their values (2.1.0's files, e.g. brickpi3.py's sixteen
    outputs 'spi0.1:MA' to 'spi0.1:MP')."""
    result = run(
        """\
        import ev3dev2
        from ev3dev2._platform import brickpi, brickpi3, ev3, evb, fake, pistorms
        from ev3dev2._platform.brickpi3 import OUTPUT_P, INPUT_16
        print(ev3dev2.get_current_platform())
        print(brickpi.OUTPUT_A, brickpi.LED_DEFAULT_COLOR, list(brickpi.LED_GROUPS))
        print(OUTPUT_P, INPUT_16, brickpi3.LEDS["amber_led"])
        print(evb.BUTTONS_FILENAME, evb.EVDEV_DEVICE_NAME, evb.LEDS)
        print(fake.OUTPUT_A, fake.INPUT_4, fake.BUTTONS_FILENAME)
        print(pistorms.OUTPUT_C, pistorms.LED_COLORS["MAGENTA"], pistorms.EVDEV_DEVICE_NAME)
        print(ev3.OUTPUT_A, ev3.LED_DEFAULT_COLOR)
        """
    )
    assert result.status == "finished", result.reason
    assert lines(result) == [
        "ev3",
        "serial0-0:MA BLUE ['LED1', 'LED2']",
        "spi0.1:MP spi0.1:S16 led1:amber:brick-status",
        "/dev/input/by-path/platform-evb-buttons-event evb-input {}",
        "outA in4 None",
        "pistorms:BBM1 (1, 0, 1) PiStorms",
        "ev3-ports:outA GREEN",
    ]


# ---------------------------------------------------------------- the program's arguments

ARGV = """\
import os, sys
from ev3sim2d.brick.environment import BrickEnvironment
from ev3sim2d.brick.scheduler import Scheduler


class Link:
    def output(self, t_us, stream, text):
        pass

    def flush(self):
        pass


given = {given}
env = BrickEnvironment(Scheduler(10_000, lambda tick_us: None), Link(), 0, "/brick/prog.py", [], **given)
env.install()
os.write(1, repr(sys.argv).encode())
"""


def brick_argv(**given) -> list[str]:
    """sys.argv after a BrickEnvironment is installed (in a process of its own: it patches the process)."""
    done = subprocess.run(
        [sys.executable, "-c", ARGV.format(given=repr(given))],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=60,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )
    assert done.returncode == 0, done.stderr
    return ast.literal_eval(done.stdout)


def test_sys_argv_is_what_the_welcome_says_else_the_programs_path():
    """`brickrun -- ./prog.py 26 1.5` runs the file with its arguments (brickrun(1): "brickrun
    [--directory=dir] [--redirect] [--] command [arg ...]"; console-runner spawns them as given), so
    sys.argv is ['./prog.py', '26', '1.5'] there; the simulator's welcome carries that list as "argv"
    (simulator/bricks.py), and the brick makes it sys.argv; without one, sys.argv is [the program's path]."""
    assert brick_argv(argv=["prog.py", "26", "1.5"]) == ["prog.py", "26", "1.5"]
    assert brick_argv(argv=None) == ["/brick/prog.py"]
    assert brick_argv() == ["/brick/prog.py"]


# ---------------------------------------------------------------- as a user runs it: `ev3sim2d run`


def test_ev3sim2d_run_of_a_program_ending_with_exit_succeeds(tmp_path):
    """The same program as on the brick (module docstring: a shebang line, site's exit()), run with the
    real `ev3sim2d run` command: it finishes, the command succeeds, and what it printed is the EV3's."""
    program = tmp_path / "hello.py"
    program.write_text(
        "#!/usr/bin/env python3\n"
        "import platform, socket\n"
        "print('hello from', socket.gethostname(), platform.machine())\n"
        "exit()\n",
        encoding="utf-8",
    )
    summary = tmp_path / "run.json"
    done = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "run", str(program), "--time", "5", "--summary", str(summary)],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    report = json.loads(summary.read_text())
    assert (report["status"], report["output"]) == ("finished", ["hello from ev3dev armv5tejl"])
