"""`ev3sim2d live` from the wheel: it serves its page (all of it: the shared world drawing too) and its API
on 127.0.0.1, runs the program live, and Ctrl+C leaves the run's trace for `render`."""

import json
import re
import signal
import subprocess
import time
import urllib.request

import pytest


def _get(url: str, token: str = "") -> bytes:
    request = urllib.request.Request(url, headers={"X-Ev3sim2d-Token": token} if token else {})
    with urllib.request.urlopen(request, timeout=10) as answer:
        return answer.read()


@pytest.mark.needs_linux("signals")  # Ctrl+C, played as SIGINT
def test_live_serves_its_page_and_api_and_leaves_a_trace(installed, user_folder):
    installed.run("ev3sim2d", "examples", cwd=user_folder)
    live = subprocess.Popen(
        ["ev3sim2d", "live", "examples/line_follower.py", "--maze", "line", "--no-browser", "--max-speed",
         "--time", "5", "--trace", "run.npz"],
        cwd=user_folder, env=installed.environment(), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    try:
        line = live.stdout.readline()
        found = re.search(r"(http://127\.0\.0\.1:\d+)/#token=([A-Za-z0-9_-]+)", line)
        url, token = found.group(1), found.group(2)  # the page's address carries this run's key
        page = _get(url + "/").decode()
        for script in re.findall(r'src="/?([^"]+\.js)"', page):
            assert _get(f"{url}/{script}"), script  # every file the page loads is in the wheel
        deadline = time.monotonic() + 60
        while json.loads(_get(url + "/api/state", token))["status"] != "ended":
            assert time.monotonic() < deadline, "the 5 s run did not end"
            time.sleep(0.1)
    finally:
        live.send_signal(signal.SIGINT)
        out, err = live.communicate(timeout=60)
    assert (user_folder / "run.npz").exists(), out + err
    done = installed.run("ev3sim2d", "render", "run.npz", "--png", "end.png", cwd=user_folder)
    assert done.returncode == 0 and (user_folder / "end.png").exists(), done.stderr
