"""`ev3sim2d serve` and `ev3sim2d join` as a class uses them: real processes, real TCP sockets on 127.0.0.1.

A world served for N robots runs when every robot has a program, and gives the run `ev3sim2d run`
gives with the same programs, fingerprint for fingerprint.  A connection that goes away, stalls,
brings a wrong token, speaks nonsense or comes when the world is full is dropped or refused with a
clear message, and the run goes on for the others.  Some tests play a joining computer by hand, with
a raw socket speaking the protocol (protocol/joining.py, docs/network.md), to misbehave exactly.
"""

from __future__ import annotations

import json
import os
import re
import signal
import socket
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from ev3sim2d.protocol import PROTOCOL, decode, encode
from ev3sim2d.protocol.joining import join_message

REPO = Path(__file__).resolve().parent.parent
LINE_FOLLOWER = REPO / "examples" / "line_follower.py"

SPINNER = """\
from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
from ev3dev2.sound import Sound
import time
tank = MoveTank(OUTPUT_B, OUTPUT_C)
Sound().beep()
for second in range(4):
    print("second", second)
    tank.on(-20, 20)
    time.sleep(1)
tank.off()
print("done")
"""

TALKER = """\
import time
from ev3dev2.sensor.lego import ColorSensor
ColorSensor().reflected_light_intensity  # answered by the world: what follows happens in the run
for second in range({seconds}):
    print("tick", second)
    time.sleep(1)
print("done")
"""


def _env() -> dict:
    return {**os.environ, "PYTHONHASHSEED": "0", "PYTHONUNBUFFERED": "1"}


def _command(*args: str) -> list[str]:
    return [sys.executable, "-m", "ev3sim2d", *args]


class Served:
    """An `ev3sim2d serve` process and the port it listens on."""

    def __init__(self, tmp_path: Path, *args: str) -> None:
        self.err_path = tmp_path / "serve.err"
        self.out_path = tmp_path / "serve.out"
        self.process = subprocess.Popen(
            _command("serve", "--port", "0", *args),
            stdout=open(self.out_path, "w"),
            stderr=open(self.err_path, "w"),
            cwd=tmp_path,
            env=_env(),
        )
        try:
            self.port = int(self.wait_for(r"serving .* on \S+:(\d+)").group(1))
        except BaseException:
            self.stop()
            raise
        self.address = f"127.0.0.1:{self.port}"

    def log(self) -> str:
        return self.err_path.read_text()

    def wait_for(self, pattern: str, timeout_s: float = 60.0) -> re.Match:
        end = time.monotonic() + timeout_s
        while time.monotonic() < end:
            found = re.search(pattern, self.log())
            if found:
                return found
            if self.process.poll() is not None:
                found = re.search(pattern, self.log())
                if found:
                    return found
                raise AssertionError(
                    f"serve ended ({self.process.returncode}) before {pattern!r}:\n{self.log()}"
                )
            time.sleep(0.02)
        raise AssertionError(f"no {pattern!r} in serve's log:\n{self.log()}")

    def finish(self, timeout_s: float = 120.0) -> int:
        return self.process.wait(timeout=timeout_s)

    def stop(self) -> None:
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait()


@pytest.fixture
def serve(tmp_path):
    started: list[Served] = []

    def _serve(*args: str) -> Served:
        served = Served(tmp_path, *args)
        started.append(served)
        return served

    yield _serve
    for served in started:
        served.stop()


def _join(address: str, program: Path, *args: str, cwd: Path) -> subprocess.Popen:
    return subprocess.Popen(
        _command("join", address, str(program), *args),
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=cwd,
        env=_env(),
        start_new_session=True,
    )


def _program(tmp_path: Path, name: str, source: str) -> Path:
    path = tmp_path / name
    path.write_text(textwrap.dedent(source))
    return path


class FakeJoin:
    """A joining computer played by hand: a raw TCP socket that says what the test tells it to."""

    def __init__(self, address: str) -> None:
        host, port = address.rsplit(":", 1)
        self.sock = socket.create_connection((host, int(port)), timeout=30)
        self.buffer = b""

    def send(self, message: list) -> None:
        self.sock.sendall(encode(message))

    def receive(self) -> list | None:
        """The next message, None when the other side closed the connection."""
        while b"\n" not in self.buffer:
            data = self.sock.recv(65536)
            if not data:
                return None
            self.buffer += data
        line, self.buffer = self.buffer.split(b"\n", 1)
        return decode(line)

    def join(self, robot: int | None = None, token: str | None = None, name: str = "fake") -> list | None:
        self.send(join_message(token, robot, name, "fake.py", "/nowhere/fake.py"))
        return self.receive()

    def close(self) -> None:
        self.sock.close()


def _summary(path: Path) -> dict:
    return json.loads(path.read_text())


# ------------------------------------------------------------------------------------------ the run


def test_a_served_run_is_the_run_of_one_command_fingerprint_for_fingerprint(serve, tmp_path):
    spinner = _program(tmp_path, "spinner.py", SPINNER)
    subprocess.run(
        _command(
            "run", str(LINE_FOLLOWER), str(spinner), "--maze", "line-shared", "--time", "6", "--quiet",
            "--summary", "run.json",
        ),
        cwd=tmp_path, env=_env(), check=True, capture_output=True,
    )  # fmt: skip
    served = serve("--maze", "line-shared", "--robots", "2", "--time", "6", "--summary", "served.json")
    # the second robot's program joins first: robots are taken by number, not by order of arrival
    second = _join(served.address, spinner, "--robot", "2", "--name", "bob", cwd=tmp_path)
    served.wait_for("robot 2: bob")
    first = _join(served.address, LINE_FOLLOWER, "--name", "alice", cwd=tmp_path)
    out2, err2 = second.communicate(timeout=120)
    out1, err1 = first.communicate(timeout=120)
    assert served.finish() == 0, served.log()
    ran, joined = _summary(tmp_path / "run.json"), _summary(tmp_path / "served.json")
    assert joined["fingerprint"] == ran["fingerprint"]
    assert joined["robots"] == ran["robots"]
    assert first.returncode == 0 and second.returncode == 0, err1 + err2
    # each student sees their own program's output, as it comes, on their own computer
    assert "] second 0" in out2 and "] done" in out2 and "second" not in out1
    assert "joined 'line-shared' as robot 2 of 2" in err2
    assert "robot 1: ran until the time limit of 6.00 s" in err1
    assert "alice" in served.log() and "bob" in served.log()


def test_a_join_that_disconnects_mid_run_is_dropped_and_the_others_run_on(serve, tmp_path, monkeypatch):
    (tmp_path / "tmp").mkdir()
    monkeypatch.setenv(
        "TMPDIR", str(tmp_path / "tmp")
    )  # (the join killed outright leaves its brick's folder)
    talker = _program(tmp_path, "talker.py", TALKER.format(seconds=10**6))  # never ends by itself
    ender = _program(tmp_path, "ender.py", TALKER.format(seconds=20))
    # (programs that mostly sleep run thousands of times faster than real time: the limit is far away)
    served = serve("--maze", "line-shared", "--time", "100000", "--summary", "served.json")
    victim = _join(served.address, talker, "--robot", "1", cwd=tmp_path)
    other = _join(served.address, ender, "--robot", "2", cwd=tmp_path)
    assert "tick 0" in victim.stdout.readline()  # the run has started
    if hasattr(os, "killpg"):  # the student's computer goes away (join and brick with it)
        os.killpg(victim.pid, signal.SIGKILL)
    else:  # (no process groups: the brick's Job Object ends it with its join)
        victim.kill()
    victim.wait()
    out, err = other.communicate(timeout=120)
    served.finish()
    assert "] done" in out and other.returncode == 0, err
    summary = _summary(tmp_path / "served.json")
    assert summary["sim_time_s"] < 100000, "the run ended when the dropped robot's connection did"
    assert "connection to the program's computer was lost" in summary["reason"]
    assert "robot1" in served.log() and "connection to the program's computer was lost" in served.log()
    assert "robot2 (ender: " in served.log() and "finished at 20" in served.log()


def test_a_joined_program_that_fails_is_shown_with_its_line_on_its_computer_only(serve, tmp_path):
    broken = _program(tmp_path, "broken.py", "import time\ntime.sleep(0.5)\nprint(1 / 0)\n")
    ender = _program(tmp_path, "ender.py", TALKER.format(seconds=3))
    served = serve("--maze", "line-shared", "--time", "10")
    failing = _join(served.address, broken, "--robot", "1", cwd=tmp_path)
    other = _join(served.address, ender, "--robot", "2", cwd=tmp_path)
    out, err = failing.communicate(timeout=120)
    other_out, other_err = other.communicate(timeout=120)
    served.finish()
    assert failing.returncode == 1
    assert "ZeroDivisionError" in err and f'{broken}", line 3' in err
    assert "robot 1: ZeroDivisionError: division by zero" in err
    assert other.returncode == 0 and "ZeroDivisionError" not in other_out + other_err.split("the run:")[0]


# ------------------------------------------------------------------------------- who may join


def test_a_world_served_beyond_this_computer_prints_a_token_and_refuses_joins_without_it(serve, tmp_path):
    served = serve("--maze", "line-shared", "--robots", "1", "--host", "0.0.0.0", "--time", "2")
    token = served.wait_for(r"--token (\S+)").group(1)
    address = served.address  # (every address of this computer: its loopback too)
    talker = _program(tmp_path, "talker.py", TALKER.format(seconds=1))
    for given in ([], ["--token", "guessed"]):
        refused = _join(address, talker, *given, cwd=tmp_path)
        _, err = refused.communicate(timeout=60)
        assert refused.returncode == 2
        assert "the world refused this brick" in err and "give it with --token" in err
    assert "no join token" in served.log() and "a wrong join token" in served.log()
    joined = _join(address, talker, "--token", token, cwd=tmp_path)
    out, err = joined.communicate(timeout=120)
    assert joined.returncode == 0 and "] done" in out, err
    assert served.finish() == 0


def test_garbage_and_silence_on_the_socket_are_dropped_and_the_world_still_fills(serve, tmp_path):
    served = serve("--maze", "line-shared", "--robots", "1", "--time", "2")
    host, port = served.address.split(":")
    noise = socket.create_connection((host, int(port)))
    noise.sendall(b"GET / HTTP/1.1\r\nHost: x\r\n\r\n")  # a browser, a port scanner
    answer = noise.recv(4096)
    assert b"refused" in answer and b"protocol" in answer
    noise.close()
    served.wait_for("does not speak ev3sim2d's protocol")
    binary = socket.create_connection((host, int(port)))
    binary.sendall(os.urandom(8000).replace(b"\n", b" "))  # no line end in sight, longer than any join
    served.wait_for("a join message longer than")
    binary.close()
    joined = _join(served.address, _program(tmp_path, "t.py", TALKER.format(seconds=1)), cwd=tmp_path)
    out, err = joined.communicate(timeout=120)
    assert joined.returncode == 0 and "] done" in out, err


def test_a_world_that_is_full_refuses_more_joins_and_a_taken_robot_cannot_be_taken(serve, tmp_path):
    served = serve("--maze", "line-shared", "--robots", "2", "--time", "2")
    first, second = FakeJoin(served.address), FakeJoin(served.address)
    assert first.join(robot=2)[0] == "seat"
    taken = FakeJoin(served.address).join(robot=2)
    assert taken[0] == "refused" and "robot 2 already has a program" in taken[1]
    too_high = FakeJoin(served.address).join(robot=3)
    assert too_high[0] == "refused" and "choose --robot 1 to 2" in too_high[1]
    assert second.join()[0] == "seat"  # the free one: robot 1
    full = FakeJoin(served.address).join()
    assert full == ["refused", "the world is full: all 2 robots have programs"]
    late = _join(served.address, _program(tmp_path, "t.py", TALKER.format(seconds=1)), cwd=tmp_path)
    _, err = late.communicate(timeout=60)
    assert late.returncode == 2 and "the world is full" in err
    # a seated brick that goes away before the start frees its robot
    first.close()
    served.wait_for("robot 2 is free again")
    again = FakeJoin(served.address).join()
    assert again[0] == "seat" and again[1]["number"] == 2


def test_a_brick_that_stalls_mid_run_is_dropped_as_hung_and_the_run_goes_on(serve, tmp_path):
    served = serve("--maze", "line-shared", "--robots", "2", "--time", "30", "--hang-after", "1",
                   "--summary", "served.json")  # fmt: skip
    stalled = FakeJoin(served.address)
    seat = stalled.join(robot=1)
    assert seat[0] == "seat" and seat[1]["robot"] == "robot1" and seat[1]["tick_us"] == 10_000
    stalled.send(["hello", {"protocol": PROTOCOL, "sandbox": {}}])
    ender = _join(served.address, _program(tmp_path, "ender.py", TALKER.format(seconds=5)), cwd=tmp_path)
    assert stalled.receive()[0] == "snap"  # the run started; this brick now says nothing at all
    out, err = ender.communicate(timeout=120)
    assert ender.returncode == 0 and "] done" in out, err
    served.finish()
    summary = _summary(tmp_path / "served.json")
    assert summary["status"] == "hung" and "the program on the other computer ran" in summary["reason"]
    assert summary["sim_time_s"] == pytest.approx(5, abs=0.05)  # the other program still ran to its end
    stalled.close()


def test_nonsense_from_a_seated_brick_mid_run_drops_only_that_robot(serve, tmp_path):
    served = serve("--maze", "line-shared", "--robots", "2", "--time", "30", "--summary", "served.json")
    rogue = FakeJoin(served.address)
    assert rogue.join(robot=2)[0] == "seat"
    rogue.send(["hello", {"protocol": PROTOCOL, "sandbox": {}}])
    ender = _join(served.address, _program(tmp_path, "ender.py", TALKER.format(seconds=3)), cwd=tmp_path)
    assert rogue.receive()[0] == "snap"
    rogue.sock.sendall(b'["ops", [["w", 999, "x"]]]\n{not json\n')
    stop = rogue.receive()
    assert stop[0] == "stop" and "protocol" in stop[1]
    out, err = ender.communicate(timeout=120)
    assert ender.returncode == 0 and "] done" in out, err
    served.finish()
    summary = _summary(tmp_path / "served.json")
    assert summary["sim_time_s"] == pytest.approx(3, abs=0.05)


def test_join_says_clearly_when_no_world_is_there(tmp_path):
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]  # free once closed: nothing listens there
    program = _program(tmp_path, "t.py", TALKER.format(seconds=1))
    for address, message in (
        (f"127.0.0.1:{port}", "no world is served at"),
        ("127.0.0.1", "give the world's address as HOST:PORT"),
    ):
        done = subprocess.run(
            _command("join", address, str(program)), capture_output=True, text=True, env=_env(), cwd=tmp_path
        )
        assert done.returncode == 2 and message in done.stderr


def test_a_student_who_joins_before_the_world_is_served_waits_for_it(tmp_path):
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    early = _join(f"127.0.0.1:{port}", _program(tmp_path, "t.py", TALKER.format(seconds=1)), "--wait", "60",
                  cwd=tmp_path)  # fmt: skip
    time.sleep(1.0)  # the teacher is late
    assert early.poll() is None, "join gave up at once"
    served = Served(tmp_path, "--maze", "line-shared", "--robots", "1", "--time", "3", "--port", str(port))
    try:
        out, err = early.communicate(timeout=120)
        assert early.returncode == 0 and "] done" in out, err
        assert served.finish() == 0
    finally:
        served.stop()


class SlowLink:
    """A TCP proxy that holds every chunk back a while, both ways: a distant or slow network."""

    def __init__(self, target: str, delay_s: float) -> None:
        import threading

        host, port = target.rsplit(":", 1)
        self.target = (host, int(port))
        self.delay_s = delay_s
        self.listener = socket.create_server(("127.0.0.1", 0))
        self.address = f"127.0.0.1:{self.listener.getsockname()[1]}"
        self.threads = [threading.Thread(target=self._accept, daemon=True)]
        self.threads[0].start()

    def _accept(self) -> None:
        import threading

        while True:
            try:
                near, _ = self.listener.accept()
            except OSError:
                return
            far = socket.create_connection(self.target)
            for a, b in ((near, far), (far, near)):
                threading.Thread(target=self._pipe, args=(a, b), daemon=True).start()

    def _pipe(self, source: socket.socket, sink: socket.socket) -> None:
        try:
            while data := source.recv(65536):
                time.sleep(self.delay_s)
                sink.sendall(data)
            sink.shutdown(socket.SHUT_WR)
        except OSError:
            pass

    def close(self) -> None:
        self.listener.close()


def test_a_slow_distant_brick_changes_the_wall_time_only(serve, tmp_path):
    spinner = _program(tmp_path, "spinner.py", SPINNER)
    subprocess.run(
        _command("run", str(LINE_FOLLOWER), str(spinner), "--maze", "line-shared", "--time", "3", "--quiet",
                 "--summary", "run.json"),
        cwd=tmp_path, env=_env(), check=True, capture_output=True,
    )  # fmt: skip
    served = serve("--maze", "line-shared", "--robots", "2", "--time", "3", "--summary", "served.json")
    link = SlowLink(served.address, delay_s=0.003)  # 3 ms more each way, for every chunk
    try:
        far = _join(link.address, spinner, "--robot", "2", cwd=tmp_path)
        near = _join(served.address, LINE_FOLLOWER, "--robot", "1", cwd=tmp_path)
        for join in (far, near):
            _, err = join.communicate(timeout=300)
            assert join.returncode == 0, err
    finally:
        link.close()
    assert served.finish() == 0
    ran, joined = _summary(tmp_path / "run.json"), _summary(tmp_path / "served.json")
    assert joined["fingerprint"] == ran["fingerprint"]
    assert joined["wall_time_s"] > ran["wall_time_s"]
