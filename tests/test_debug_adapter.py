"""The Debug Adapter Protocol server VS Code attaches to (`ev3sim2d run --debug-adapter`), driven by a
scripted client speaking raw DAP over its socket, as VS Code's debugpy attach configuration does: it sets
a breakpoint, stops there, reads the threads, the stack, a variable, evaluates, steps and continues.
While it is stopped the world's time does not advance, and the run ends with the plain run's
fingerprint.  A client without the run's token is turned away.
"""

from __future__ import annotations

import json
import re
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

PROGRAM = """\
from ev3dev2.motor import LargeMotor, MoveTank, OUTPUT_B, OUTPUT_C
tank = MoveTank(OUTPUT_B, OUTPUT_C)
left = LargeMotor(OUTPUT_B)
tank.on(30, 30)
for lap in range(3):
    speed = 10 * (lap + 1)
    tank.on_for_seconds(speed, speed, 0.5)
print("done", left.position)
"""


class Client:
    """A DAP client: requests out, responses and events in, over one socket."""

    def __init__(self, port: int) -> None:
        self.socket = socket.create_connection(("127.0.0.1", port), timeout=60)
        self.buffer = b""
        self.seq = 0
        self.events: list[dict] = []

    def request(self, command: str, **arguments) -> dict:
        self.seq += 1
        data = json.dumps(
            {"seq": self.seq, "type": "request", "command": command, "arguments": arguments}
        ).encode()
        self.socket.sendall(b"Content-Length: %d\r\n\r\n" % len(data) + data)
        while True:
            message = self.receive()
            if message["type"] == "response" and message["request_seq"] == self.seq:
                return message
            self.events.append(message)

    def event(self, name: str) -> dict:
        for i, event in enumerate(self.events):
            if event.get("event") == name:
                return self.events.pop(i)
        while True:
            message = self.receive()
            if message.get("event") == name:
                return message
            self.events.append(message)

    def receive(self) -> dict:
        while b"\r\n\r\n" not in self.buffer:
            self._read()
        header, self.buffer = self.buffer.split(b"\r\n\r\n", 1)
        length = int(re.search(rb"Content-Length: (\d+)", header).group(1))
        while len(self.buffer) < length:
            self._read()
        body, self.buffer = self.buffer[:length], self.buffer[length:]
        return json.loads(body)

    def _read(self) -> None:
        chunk = self.socket.recv(65536)
        if not chunk:
            raise ConnectionError("the adapter closed the connection")
        self.buffer += chunk


def _start(folder: Path, *options) -> tuple[subprocess.Popen, int, str]:
    run = subprocess.Popen(
        [sys.executable, "-m", "ev3sim2d", "run", "prog.py", "--maze", "empty", "--time", "5",
         "--debug-adapter", "0", *options],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=folder,
    )  # fmt: skip
    line = run.stderr.readline()
    found = re.search(r"on 127\.0\.0\.1:(\d+) \(token (\S+)\)", line)
    assert found, line
    return run, int(found.group(1)), found.group(2)


@pytest.fixture
def folder(tmp_path) -> Path:
    (tmp_path / "prog.py").write_text(PROGRAM)
    return tmp_path


def test_a_scripted_client_stops_at_a_breakpoint_looks_steps_and_continues(folder):
    run, port, token = _start(folder, "--summary", "debugged.json")
    try:
        client = Client(port)
        assert client.request("initialize", adapterID="ev3sim2d")["success"]
        attached = client.request("attach", ev3sim2dToken=token, connect={"host": "127.0.0.1", "port": port})
        assert attached["success"]
        client.event("initialized")
        source = str(folder / "prog.py")
        set_ = client.request("setBreakpoints", source={"path": source}, breakpoints=[{"line": 7}])
        assert set_["body"]["breakpoints"] == [{"verified": True, "line": 7}]
        assert client.request("configurationDone")["success"]

        stopped = client.event("stopped")["body"]
        assert stopped["reason"] == "breakpoint"
        threads = client.request("threads")["body"]["threads"]
        assert [t["name"] for t in threads] == ["MainThread"] and threads[0]["id"] == stopped["threadId"]
        frames = client.request("stackTrace", threadId=stopped["threadId"])["body"]["stackFrames"]
        assert (frames[0]["line"], frames[0]["name"], frames[0]["source"]["path"]) == (
            7,
            "<module>",
            source,
        )
        scopes = client.request("scopes", frameId=frames[0]["id"])["body"]["scopes"]
        assert [s["name"] for s in scopes] == ["Locals", "Globals"]
        names = client.request("variables", variablesReference=scopes[0]["variablesReference"])["body"]
        values = {v["name"]: v["value"] for v in names["variables"]}
        assert values["lap"] == "0" and values["speed"] == "10" and "tank" in values
        first = client.request("evaluate", expression="left.position", context="watch")["body"]["result"]
        time.sleep(1.0)  # the student looks away: the world waits
        again = client.request("evaluate", expression="left.position", context="watch")["body"]["result"]
        assert first == again
        refused = client.request("evaluate", expression="left.on(80)", context="repl")
        assert not refused["success"] and "writing to the robot is refused" in refused["message"]

        assert client.request("next", threadId=stopped["threadId"])["success"]
        assert client.event("stopped")["body"]["reason"] == "step"
        frames = client.request("stackTrace", threadId=stopped["threadId"])["body"]["stackFrames"]
        assert frames[0]["line"] == 5  # the loop's next round
        client.request("setBreakpoints", source={"path": source}, breakpoints=[])  # no more stops
        assert client.request("continue", threadId=stopped["threadId"])["success"]
        assert client.event("exited")["body"]["exitCode"] == 0
        client.event("terminated")
        out, err = run.communicate(timeout=120)
    finally:
        run.kill()
    assert "] done " in out, err
    plain = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "run", "prog.py", "--maze", "empty", "--time", "5", "--summary", "plain.json"],
        capture_output=True, text=True, cwd=folder, timeout=120,
    )  # fmt: skip
    assert plain.stdout.split("] done")[1] == out.split("] done")[1]
    fingerprint = [
        json.loads((folder / name).read_text())["fingerprint"] for name in ("debugged.json", "plain.json")
    ]
    assert fingerprint[0] == fingerprint[1]


def test_a_client_without_the_runs_token_is_turned_away(folder):
    run, port, token = _start(folder)
    try:
        client = Client(port)
        client.request("initialize", adapterID="someone else")
        refused = client.request("attach", ev3sim2dToken="guess")
        assert not refused["success"] and "token" in refused["message"]
        with pytest.raises((ConnectionError, OSError)):
            client.request("configurationDone")
        _, err = run.communicate(timeout=60)
    finally:
        run.kill()
    assert run.returncode == 2 and "token" in err


def test_stop_on_entry_stops_at_the_first_line(folder):
    run, port, token = _start(folder)
    try:
        client = Client(port)
        client.request("initialize")
        client.request("attach", ev3sim2dToken=token, stopOnEntry=True)
        client.request("configurationDone")
        stopped = client.event("stopped")["body"]
        assert stopped["reason"] == "entry"
        frames = client.request("stackTrace", threadId=stopped["threadId"])["body"]["stackFrames"]
        assert frames[0]["line"] == 1
        client.request("continue", threadId=stopped["threadId"])
        client.event("terminated")
        run.communicate(timeout=120)
    finally:
        run.kill()
    assert run.returncode == 0


def test_every_thread_of_the_program_is_listed_with_its_own_stack(tmp_path):
    (tmp_path / "prog.py").write_text(
        "import threading, time\n"
        "def blink():\n"
        "    while True:\n"
        "        time.sleep(0.25)\n"
        "threading.Thread(target=blink, name='blinker', daemon=True).start()\n"
        "time.sleep(1)\n"
        "total = 3\n"
    )
    run, port, token = _start(tmp_path)
    try:
        client = Client(port)
        client.request("initialize")
        client.request("attach", ev3sim2dToken=token)
        client.request(
            "setBreakpoints", source={"path": str(tmp_path / "prog.py")}, breakpoints=[{"line": 7}]
        )
        client.request("configurationDone")
        stopped = client.event("stopped")["body"]
        threads = {t["name"]: t["id"] for t in client.request("threads")["body"]["threads"]}
        assert set(threads) == {"MainThread", "blinker"} and threads["MainThread"] == stopped["threadId"]
        main = client.request("stackTrace", threadId=threads["MainThread"])["body"]["stackFrames"]
        blinker = client.request("stackTrace", threadId=threads["blinker"])["body"]["stackFrames"]
        assert main[0]["line"] == 7
        assert (blinker[0]["name"], blinker[0]["line"]) == ("blink", 4)  # waiting in its sleep
        client.request("continue", threadId=stopped["threadId"])
        client.event("terminated")
        run.communicate(timeout=120)
    finally:
        run.kill()
    assert run.returncode == 0
