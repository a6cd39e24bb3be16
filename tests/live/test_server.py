"""The live page's API (ev3sim2d/live/server.py) over real HTTP, against a real live run."""

from __future__ import annotations

import http.client
import json
import textwrap
import threading
import time
from pathlib import Path

import pytest

from ev3sim2d.editor.page_guard import TOKEN_HEADER
from ev3sim2d.live.engine import LiveRun
from ev3sim2d.live.server import LiveServer, LiveWorldFile
from ev3sim2d.world.maze_file import load_maze

DRIVE = """
    from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
    import time
    tank = MoveTank(OUTPUT_B, OUTPUT_C)
    tank.on(30, 30)
    time.sleep(30)
"""

ARENA = """\
# a walled arena for the live server's tests
title: test arena
cell_cm: 12
grid: |
{rows}
start:
  x_cm: 60
  y_cm: 120
  heading_deg: 0
"""


def arena_text(width: int = 20, height: int = 20) -> str:
    rows = ["#" * width] + ["#" + "." * (width - 2) + "#"] * (height - 2) + ["#" * width]
    return ARENA.format(rows="\n".join("  " + r for r in rows))


class Client:
    """Requests to a live server as its page makes them (with the page token), answers as (status, JSON)."""

    def __init__(self, port: int, token: str) -> None:
        self.port = port
        self.token = token

    def request(self, method: str, path: str, body: object = None, headers: dict | None = None):
        conn = http.client.HTTPConnection("127.0.0.1", self.port, timeout=60)
        data = None if body is None else json.dumps(body).encode()
        sent = {"Content-Type": "application/json"} if data is not None else {}
        sent[TOKEN_HEADER] = self.token
        sent.update(headers or {})
        conn.request(method, path, body=data, headers=sent)
        response = conn.getresponse()
        raw = response.read()
        conn.close()
        return response.status, json.loads(raw) if raw else None

    def get(self, path: str):
        return self.request("GET", path)

    def post(self, path: str, body: object = None, **headers):
        return self.request("POST", path, body, headers)

    def state(self) -> dict:
        status, state = self.get("/api/state")
        assert status == 200
        return state

    def wait_for(self, predicate, timeout_s: float = 60.0) -> dict:
        end = time.monotonic() + timeout_s
        while time.monotonic() < end:
            state = self.state()
            if predicate(state):
                return state
            time.sleep(0.03)
        raise AssertionError(f"not reached: {self.state()}")


@pytest.fixture
def live_server(tmp_path):
    """live_server(program_text, speed=..., paused=...) -> (client, LiveRun, world path)."""
    started: list[tuple[LiveServer, LiveRun]] = []

    def start(program: str = DRIVE, speed: float | None = None, paused: bool = True, world_file: bool = True):
        path = tmp_path / "prog.py"
        path.write_text(textwrap.dedent(program))
        world_path = tmp_path / "arena.yaml"
        world_path.write_text(arena_text())
        live = LiveRun([path], load_maze(world_path), speed=speed)
        files = LiveWorldFile(world_path) if world_file else LiveWorldFile(None, "empty")
        server = LiveServer(live, files)
        threading.Thread(target=server.serve_forever, daemon=True).start()
        live.start(paused=paused)
        started.append((server, live))
        client = Client(server.server_address[1], server.token)
        client.wait_for(lambda s: s["robots"] and s["status"] in ("paused", "running"))
        return client, live, world_path

    yield start
    for server, live in started:
        server.shutdown()
        server.server_close()
        live.close()


def test_pause_stops_time_and_step_moves_it_on(live_server):
    client, _, _ = live_server(speed=4.0, paused=False)
    client.wait_for(lambda s: s["t_s"] > 0.3)
    status, paused = client.post("/api/pause")
    assert status == 200 and paused["status"] == "paused"
    time.sleep(0.3)
    assert client.state()["t_s"] == paused["t_s"]
    status, stepped = client.post("/api/step", {"ms": 100})
    assert status == 200 and stepped["t_s"] == pytest.approx(paused["t_s"] + 0.1, abs=1e-6)
    status, stepped = client.post("/api/step", {"ticks": 1})
    assert status == 200 and stepped["t_s"] > paused["t_s"] + 0.1
    status, state = client.post("/api/speed", {"speed": None})
    assert status == 200 and state["speed"] is None
    status, state = client.post("/api/resume")
    assert status == 200
    client.wait_for(lambda s: s["t_s"] > stepped["t_s"] + 0.3)


def test_move_puts_the_robot_there_and_the_trace_counts_it(live_server):
    client, _, _ = live_server()
    status, state = client.post("/api/move", {"robot": 1, "x_cm": 100, "y_cm": 100, "heading_deg": 90})
    assert status == 200
    robot = state["robots"][0]
    assert (robot["x_cm"], robot["y_cm"], robot["heading_deg"]) == pytest.approx((100, 100, 90), abs=0.01)
    assert state["interventions"] == 1
    status, answer = client.post("/api/move", {"robot": 1, "x_cm": 2, "y_cm": 2, "heading_deg": 0})
    assert status == 409 and "wall" in answer["error"]
    status, answer = client.post("/api/move", {"robot": 2, "x_cm": 100, "y_cm": 100, "heading_deg": 0})
    assert status == 400 and "robot 2" in answer["error"]


def test_a_cell_made_a_wall_is_in_the_world_and_saved_to_the_file_with_a_backup(live_server):
    client, _, world_path = live_server()
    before = world_path.read_text()
    status, state = client.post("/api/cell", {"col": 10, "row": 10, "wall": True})
    assert status == 200 and state["world_version"] == 1
    status, world = client.get("/api/world")
    assert status == 200 and world["cells"][10][10]["wall"] and world["world_version"] == 1
    status, state = client.post("/api/cell", {"col": 5, "row": 5, "wall": False, "shade": 30})
    assert status == 200
    status, answer = client.post("/api/save-world")
    assert status == 200 and answer["saved"]["changed"]
    saved = load_maze(world_path)
    assert saved.grid.cell(10, 10).wall and saved.grid.cell(5, 5).shade == 30
    assert Path(str(world_path) + ".bak").read_text() == before
    assert world_path.read_text().startswith("# a walled arena")  # the file's comment is kept


def test_a_shipped_world_is_not_saved_and_the_page_is_told_why(live_server):
    client, _, _ = live_server(world_file=False)
    status, answer = client.post("/api/save-world")
    assert status == 409 and "save as" in answer["error"]


@pytest.mark.parametrize(
    ("path", "body", "status", "words"),
    [
        ("/api/step", {"ms": "fast"}, 400, "'ms'"),
        ("/api/step", {"ms": 10, "ticks": 1}, 400, "not both"),
        ("/api/step", {"ms": -5}, 409, "a step is"),
        ("/api/speed", {"speed": 500}, 409, "0.1 to 50"),
        ("/api/speed", {}, 400, "'speed' is missing"),
        ("/api/move", {"robot": 1, "x_cm": 50}, 400, "'y_cm' is missing"),
        ("/api/cell", {"col": 0, "row": 3, "wall": False, "shade": 100}, 400, "border"),
        ("/api/cell", {"col": 99, "row": 3, "wall": True}, 400, "outside"),
        ("/api/cell", {"col": 3, "row": 3, "wall": False, "color": "purple"}, 400, "unknown colour"),
        ("/api/pause", {"now": True}, 400, "unknown field"),
        ("/api/jump", {}, 404, "no such endpoint"),
        ("/api/pause", [1, 2], 400, "JSON object"),
    ],
)
def test_bad_requests_are_refused_with_a_message(live_server, path, body, status, words):
    client, _, _ = live_server()
    got, answer = client.post(path, body)
    assert got == status and words in answer["error"]


def test_other_hosts_and_origins_are_refused_and_big_bodies_too(live_server):
    client, _, _ = live_server()
    status, answer = client.request("GET", "/api/state", headers={"Host": "evil.example:80"})
    assert status == 403 and "Host" in answer["error"]
    status, answer = client.post("/api/pause", Origin="http://evil.example")
    assert status == 403
    status, answer = client.post("/api/step", {"ms": 1, "pad": "x" * 100_000})
    assert status == 413
    conn = http.client.HTTPConnection("127.0.0.1", client.port, timeout=10)
    conn.request(
        "POST",
        "/api/step",
        body=b"ms=5",
        headers={"Content-Type": "application/x-www-form-urlencoded", TOKEN_HEADER: client.token},
    )
    assert conn.getresponse().status == 415


def test_events_stream_the_state_when_it_changes(live_server):
    client, _, _ = live_server(speed=2.0, paused=False)
    conn = http.client.HTTPConnection("127.0.0.1", client.port, timeout=10)
    conn.request("GET", "/api/events", headers={TOKEN_HEADER: client.token})
    response = conn.getresponse()
    assert response.status == 200 and response.getheader("Content-Type").startswith("text/event-stream")
    times = []
    while len(times) < 5:
        line = response.fp.readline().decode()
        if line.startswith("data: "):
            times.append(json.loads(line[6:])["t_s"])
    conn.close()
    assert times == sorted(times) and times[-1] > times[0]


def test_the_page_and_the_shared_world_drawing_are_served(live_server):
    client, _, _ = live_server()
    for path in ("/", "/live.js", "/live.css", "/world_canvas.js"):
        conn = http.client.HTTPConnection("127.0.0.1", client.port, timeout=10)
        conn.request("GET", path)
        assert conn.getresponse().status == 200, path


DRAW = """
    from ev3dev2.display import Display
    import time
    lcd = Display()
    lcd.draw.rectangle((0, 0, 177, 127), outline="black")
    lcd.draw.ellipse((120, 60, 160, 100), fill="black")
    lcd.update()
    time.sleep(30)
"""


def _get_bytes(client: Client, path: str) -> tuple[int, str, bytes]:
    conn = http.client.HTTPConnection("127.0.0.1", client.port, timeout=10)
    conn.request("GET", path, headers={TOKEN_HEADER: client.token})
    response = conn.getresponse()
    body = response.read()
    conn.close()
    return response.status, response.getheader("Content-Type"), body


def test_the_lcd_frame_is_in_the_state_by_number_and_served_as_a_png(live_server):
    client, _, _ = live_server(DRAW)
    status, state = client.post("/api/step", {"ms": 500})
    frame = state["robots"][0]["lcd_frame"]
    assert status == 200 and frame is not None
    status, kind, png = _get_bytes(client, f"/api/lcd?robot=1&frame={frame}")
    assert status == 200 and kind == "image/png" and png.startswith(b"\x89PNG")
    import zlib

    rows = zlib.decompress(png[png.index(b"IDAT") + 4 :])  # one IDAT chunk: 128 rows of a filter byte + 178
    assert len(rows) == 128 * 179 and rows[1:179] == bytes([0] * 178)  # the black rectangle's top edge
    assert _get_bytes(client, "/api/lcd?robot=1")[2] == png  # the robot's current frame
    assert _get_bytes(client, "/api/lcd?robot=1&frame=999")[0] == 404


def _colour_sensor(mapping: dict) -> dict:
    return next(s for s in mapping["sensors"] if s["kind"] == "color")


def test_a_sensor_moved_on_the_page_runs_from_0_s_paused_with_its_new_place(live_server):
    client, live, _ = live_server()
    client.post("/api/step", {"ms": 300})
    status, robot = client.get("/api/robot?robot=1")
    assert status == 200 and robot["file"] is None and "facings" in robot["kinds"]["color"]
    mapping = robot["mapping"]
    _colour_sensor(mapping)["angle_deg"] = 90
    _colour_sensor(mapping)["radius_cm"] = 5
    status, state = client.post("/api/robot", {"robot": 1, "mapping": mapping})
    assert status == 200 and state["t_s"] == 0 and state["status"] == "paused"
    sensor = next(s for s in state["robots"][0]["sensors"] if s["kind"] == "color")
    assert (sensor["angle_deg"], sensor["radius_cm"]) == (90, 5)
    assert "angle_deg: 90" in client.get("/api/robot?robot=1")[1]["text"]
    status, state = client.post("/api/reload")  # a reload keeps the changed robot
    sensor = next(s for s in state["robots"][0]["sensors"] if s["kind"] == "color")
    assert sensor["angle_deg"] == 90
    status, state = client.post("/api/reset")  # a reset forgets it
    assert next(s for s in state["robots"][0]["sensors"] if s["kind"] == "color")["angle_deg"] == 0


def test_a_robot_the_robot_files_refuse_is_refused_with_the_files_error(live_server):
    client, _, _ = live_server()
    mapping = client.get("/api/robot?robot=1")[1]["mapping"]
    _colour_sensor(mapping)["kind"] = "colour"
    status, answer = client.post("/api/robot", {"robot": 1, "mapping": mapping})
    assert status == 400 and "did you mean 'color'" in answer["error"]
    text = client.get("/api/robot?robot=1")[1]["text"]
    line = next(n for n, row in enumerate(text.splitlines(), 1) if "kind: ultrasonic" in row)
    text = text.replace("facing: forward, cone_deg", "facing: down, cone_deg")
    status, answer = client.post("/api/robot", {"robot": 1, "text": text})
    assert status == 400 and answer["error"].startswith(f"the page's robot:{line}:")
    assert "write `facing: forward`" in answer["error"]
    client.post("/api/resume")
    status, answer = client.post(
        "/api/robot", {"robot": 1, "text": client.get("/api/robot?robot=1")[1]["text"]}
    )
    assert status == 409 and "pause" in answer["error"]


def test_a_robot_is_saved_to_a_new_file_that_reads_back_equal_and_then_to_that_file(live_server, tmp_path):
    client, live, _ = live_server()
    status, answer = client.post("/api/save-robot", {"robot": 1})
    assert status == 409 and "new file name" in answer["error"]  # the shipped driving base is not ours
    mapping = client.get("/api/robot?robot=1")[1]["mapping"]
    _colour_sensor(mapping)["radius_cm"] = 8.5
    client.post("/api/robot", {"robot": 1, "mapping": mapping})
    for bad in ("../mine.yaml", "sub/mine.yaml", "mine.txt", ".yaml"):
        status, answer = client.post("/api/save-robot", {"robot": 1, "file": bad})
        assert status == 400 and "plain file name" in answer["error"], bad
    status, answer = client.post("/api/save-robot", {"robot": 1, "file": "mine.yaml"})
    assert status == 200 and answer["saved"]["saved"] == str(tmp_path / "mine.yaml")
    from dataclasses import replace

    from ev3sim2d.world.robot_spec import load_robot

    saved = load_robot(tmp_path / "mine.yaml")
    assert replace(saved, source=None) == replace(live.robot_spec(0), source=None)
    assert saved.sensor("in3").radius_cm == 8.5
    status, answer = client.post("/api/save-robot", {"robot": 1, "file": "mine.yaml"})
    assert status == 409 and "replace: true" in answer["error"]
    assert client.get("/api/robot?robot=1")[1]["file"] == str(tmp_path / "mine.yaml")
    status, answer = client.post("/api/save-robot", {"robot": 1})  # its own file now
    assert status == 200 and (tmp_path / "mine.yaml.bak").is_file()
