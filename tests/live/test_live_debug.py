"""`ev3sim2d live --debug`: the program stops at its first line in the debugger, its prompt in the terminal
that started live; the page's state says where it is stopped, and the world waits until the prompt lets
the program go on.  breakpoint() in a live program stops the same way."""

from __future__ import annotations

import json
import re
import subprocess
import sys
import time
import urllib.request

import pytest


def _state(url: str) -> dict:
    """GET api/state with the page token the printed address carries (http://127.0.0.1:PORT/#token=...)."""
    base, token = url.split("#token=")
    request = urllib.request.Request(base + "api/state", headers={"X-Ev3sim2d-Token": token})
    with urllib.request.urlopen(request, timeout=30) as answer:
        return json.loads(answer.read())


def _until(url: str, check, what: str) -> dict:
    deadline = time.monotonic() + 60
    while True:
        state = _state(url)
        if check(state):
            return state
        assert time.monotonic() < deadline, f"{what}: {state.get('status')}, {state.get('debugging')}"
        time.sleep(0.1)


@pytest.fixture
def live(tmp_path):
    (tmp_path / "prog.py").write_text(
        "from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C\n"
        "tank = MoveTank(OUTPUT_B, OUTPUT_C)\n"
        "tank.on(30, 30)\n"
        "breakpoint()\n"
        "tank.on_for_seconds(20, 20, 1)\n"
    )
    process = subprocess.Popen(
        [sys.executable, "-m", "ev3sim2d", "live", "prog.py", "--no-browser", "--debug", "--max-speed", "--time", "5"],
        stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, cwd=tmp_path,
    )  # fmt: skip
    try:
        url = None
        while url is None:
            line = process.stdout.readline()
            assert line, "live ended before it gave its address"
            found = re.search(r"at (http://127\.0\.0\.1:\d+/\S*)", line)
            url = found.group(1) if found else None
        yield process, url
    finally:
        process.kill()
        process.wait()


def test_the_page_says_where_the_program_is_stopped_and_the_world_waits(live):
    process, url = live
    first = _until(url, lambda s: s.get("debugging") == "prog.py:1", "stopped at the first line")
    time.sleep(1.0)
    assert _state(url)["t_s"] == first["t_s"] == 0.0  # (max speed, and not a tick in a second)
    process.stdin.write("c\n")
    process.stdin.flush()
    at_breakpoint = _until(url, lambda s: s.get("debugging") == "prog.py:5", "stopped after breakpoint()")
    time.sleep(0.5)
    assert _state(url)["t_s"] == at_breakpoint["t_s"] > 0
    process.stdin.write("c\n")
    process.stdin.flush()
    ended = _until(url, lambda s: s["status"] == "ended", "the run ends")
    assert ended["debugging"] is None and ended["t_s"] >= 1.0
