"""The live page's server (`ev3sim2d live`, docs/live.md): the page, and an HTTP API on 127.0.0.1 only.

The API is what the page uses and what a teacher may script: GET /api/state (a snapshot), GET
/api/events (Server-Sent Events: the state up to ~30 times a second, only when it changed; a slow or
closed page misses states, the simulation never waits for it), GET /api/world (the world with its
edits, as the editor's page reads it), and POSTs that pause, resume, step, change the speed, reload,
reset, move a robot, change a cell and save the world.  The same safety rules as the editor's server
(ev3sim2d/editor/server.py, whose answers and checks this reuses): only our own Host, no other site's
page, the page token on every API request (ev3sim2d/editor/page_guard.py), never framed, JSON bodies of
limited size and depth, errors as JSON with a message, a cap on connections.
"""

from __future__ import annotations

import json
import math
import re
import struct
import threading
import time
import zlib
from http import HTTPStatus
from pathlib import Path
from urllib.parse import parse_qs

from ..devices import registry
from ..editor.page_guard import PageServer
from ..editor.server import STATIC_DIR as EDITOR_STATIC_DIR
from ..editor.server import BadBody, EditorHandler, WorldFile
from ..results.output_files import replace_keeping_backup
from ..world.cell import Cell
from ..world.robot_spec import SENSOR_PORTS, robot_yaml
from ..world.source_error import WorldFileError
from ..world.world_json import BadEdit, MazeSource
from .engine import LiveError, LiveRun

STATIC_DIR = Path(__file__).with_name("static")
STATIC_FILES = {
    "/": (STATIC_DIR, "index.html", "text/html; charset=utf-8"),
    "/index.html": (STATIC_DIR, "index.html", "text/html; charset=utf-8"),
    "/live.js": (STATIC_DIR, "live.js", "text/javascript; charset=utf-8"),
    "/live.css": (STATIC_DIR, "live.css", "text/css; charset=utf-8"),
    "/world_canvas.js": (EDITOR_STATIC_DIR, "world_canvas.js", "text/javascript; charset=utf-8"),
    "/page_token.js": (EDITOR_STATIC_DIR, "page_token.js", "text/javascript; charset=utf-8"),
}
MAX_BODY_BYTES = 64 * 1024  # the commands are small; the world is saved from the server's own copy
EVENTS_EVERY_S = 1 / 30
KEEP_ALIVE_S = 15.0


class LiveWorldFile:
    """The world file a live run was started with: saving writes the run's cells into it with the
    editor's writer (comments and layout kept, the old file as .bak); a shipped world is not written."""

    def __init__(self, path: str | Path | None, shipped_name: str | None = None) -> None:
        self.path = None if path is None else Path(path).resolve()
        self.shipped_name = shipped_name

    def save(self, live: LiveRun) -> dict:
        if self.path is None:
            raise LiveError(
                f"the world is the shipped world '{self.shipped_name}', not a file of yours, so there is no "
                "file to save to (and 'save as' is not offered: the page cannot choose a file on your "
                "computer safely); copy it first (ev3sim2d mazes --copy, or cp) and start live with "
                "--maze yourfile.yaml"
            )
        world_file = WorldFile(self.path)  # the file as it is on disk now
        current = MazeSource(live.world_text(), str(self.path)).to_json()
        on_disk = world_file.world_json()
        if (current["width"], current["height"]) != (on_disk["width"], on_disk["height"]):
            raise LiveError(f"{self.path} changed size on disk since the run started; not saved")
        cells = []
        for new_row, old_row in zip(current["cells"], on_disk["cells"], strict=True):
            row = []
            for new, old in zip(new_row, old_row, strict=True):
                same = (new["wall"], new["shade"], new["color"]) == (old["wall"], old["shade"], old["color"])
                row.append({"wall": new["wall"], "shade": new["shade"], "color": new["color"],
                            "char": old["char"] if same else None})  # fmt: skip
            cells.append(row)
        payload = {
            "cell_cm": on_disk["cell_cm"],
            "cells": cells,
            "starts": on_disk["starts"],
            "regions": on_disk["regions"],
        }
        result = world_file.save(payload)
        return {"saved": result["saved"], "changed": result["changed"]}


LCD_WIDTH, LCD_HEIGHT = 178, 128
ROBOT_FILE_NAME = re.compile(r"[A-Za-z0-9_][A-Za-z0-9_ .-]*\.yaml")


def grey_png(pixels: bytes, width: int = LCD_WIDTH, height: int = LCD_HEIGHT) -> bytes:
    """8-bit grey pixels, row by row, as a PNG file (what the page shows an LCD frame with)."""

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    rows = b"".join(b"\x00" + pixels[y * width : (y + 1) * width] for y in range(height))
    header = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    return (
        b"\x89PNG\r\n\x1a\n"
        + chunk(b"IHDR", header)
        + chunk(b"IDAT", zlib.compress(rows))
        + chunk(b"IEND", b"")
    )


def robot_json(live: LiveRun, index: int) -> dict:
    """GET /api/robot: a robot as its file's text and mapping, its own file, and what the page may choose
    from (the registry's sensor kinds, each with its facings and options; the sensor ports)."""
    import yaml

    spec = live.robot_spec(index)
    own = live.robot_file(index)
    return {
        "robot": index + 1,
        "text": live.robot_text(index),
        "mapping": yaml.safe_load(robot_yaml(spec)),
        "file": None if own is None else str(own),
        "kinds": {
            kind: {
                "facings": list(registry.sensor_class(kind).FACINGS),
                "options": {
                    name: default
                    for name, (default, _unit, _m) in registry.sensor_class(kind).OPTIONS.items()
                },
            }
            for kind in registry.sensor_kinds()
        },
        "ports": list(SENSOR_PORTS),
    }


def _plain(value: object) -> object:
    """numpy numbers and the like, as JSON numbers."""
    if hasattr(value, "item"):
        return value.item()
    if isinstance(value, (tuple, set)):
        return list(value)
    raise TypeError(f"{type(value).__name__} is not JSON")


def state_json(state: dict) -> bytes:
    """The state as JSON (a NaN or an infinity becomes null: JSON has neither)."""
    text = json.dumps(state, default=_plain, allow_nan=True)
    if "NaN" in text or "Infinity" in text:
        text = json.dumps(_finite(json.loads(text)))
    return text.encode("utf-8")


def _finite(value: object) -> object:
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, list):
        return [_finite(v) for v in value]
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    return value


class LiveHandler(EditorHandler):
    """Serves the live page and its API (module docstring); refuses everything else."""

    server: LiveServer
    server_version = "ev3sim2d-live"
    program_name = "ev3sim2d live"

    # -- GET ---------------------------------------------------------------------------
    def do_GET(self) -> None:  # noqa: N802 - http.server's name
        if not self._page_request_ok():
            return
        path = self.path.split("?", 1)[0]
        if path in STATIC_FILES:  # the page's own files hold no data: no token needed
            folder, name, content_type = STATIC_FILES[path]
            self._send(HTTPStatus.OK, (folder / name).read_bytes(), content_type)
            return
        if not self._token_ok():
            return
        live = self.server.live
        if path == "/api/state":
            self._send(HTTPStatus.OK, state_json(live.state()), "application/json; charset=utf-8")
        elif path == "/api/events":
            self._events()
        elif path == "/api/world":
            self._world()
        elif path == "/api/lcd":
            self._lcd()
        elif path == "/api/robot":
            self._robot()
        else:
            self._error(HTTPStatus.NOT_FOUND, f"no such page {path!r}; the API is described in docs/live.md")

    do_HEAD = do_GET

    def _query_int(self, name: str, default: int | None = None) -> int | None:
        """?name=N as an int (default if absent); BadRequest if not a whole number."""
        query = parse_qs(self.path.split("?", 1)[1]) if "?" in self.path else {}
        if name not in query:
            return default
        try:
            return int(query[name][-1])
        except ValueError:
            raise BadRequest(f"{name}={query[name][-1]!r} is not a whole number") from None

    def _robot_number(self) -> int:
        number = self._query_int("robot", 1)
        count = len(self.server.live.programs)
        if not 1 <= number <= count:
            raise BadRequest(f"there is no robot {number}: robots are 1 to {count}")
        return number

    def _lcd(self) -> None:
        """GET /api/lcd?robot=N[&frame=F]: an LCD frame as a PNG (the robot's current one without frame)."""
        live = self.server.live
        try:
            number = self._robot_number()
            frame = self._query_int("frame")
        except BadRequest as err:
            self._error(HTTPStatus.BAD_REQUEST, str(err))
            return
        if frame is None:
            robots = live.state()["robots"]
            frame = robots[number - 1]["lcd_frame"] if number <= len(robots) else None
        pixels = None if frame is None else live.lcd_frame(frame)
        if pixels is None:
            self._error(HTTPStatus.NOT_FOUND, "no such LCD frame in this run (the program has not drawn it)")
            return
        self._send(HTTPStatus.OK, grey_png(pixels), "image/png")

    def _robot(self) -> None:
        try:
            answer = robot_json(self.server.live, self._robot_number() - 1)
        except BadRequest as err:
            self._error(HTTPStatus.BAD_REQUEST, str(err))
            return
        self._json(HTTPStatus.OK, answer)

    def _world(self) -> None:
        live = self.server.live
        version = live.state()["world_version"]  # read first: a newer text only makes the page fetch again
        try:
            text = live.world_text()
        except LiveError as err:
            self._error(HTTPStatus.SERVICE_UNAVAILABLE, str(err))
            return
        data = MazeSource(text, self.server.world_label).to_json()
        data["world_version"] = version
        self._json(HTTPStatus.OK, data)

    def _events(self) -> None:
        """Server-Sent Events: each new state as `data: {...}`; ends when the page goes or we close."""
        self.send_response(HTTPStatus.OK)
        self.send_header("Content-Type", "text/event-stream; charset=utf-8")
        self.end_headers()
        self.close_connection = True
        if self.command == "HEAD":
            return
        live, closing = self.server.live, self.server.closing
        last = None
        quiet_since = time.monotonic()
        try:
            while not closing.is_set():
                state = live.state()
                if state is not last:  # the engine publishes a new dict for each change
                    last = state
                    self.wfile.write(b"data: " + state_json(state) + b"\n\n")
                    self.wfile.flush()
                    quiet_since = time.monotonic()
                elif time.monotonic() - quiet_since > KEEP_ALIVE_S:
                    self.wfile.write(b": still here\n\n")
                    self.wfile.flush()
                    quiet_since = time.monotonic()
                closing.wait(EVENTS_EVERY_S)
        except (BrokenPipeError, ConnectionResetError, TimeoutError, OSError):
            return

    # -- POST --------------------------------------------------------------------------
    def do_POST(self) -> None:  # noqa: N802
        if not self._page_request_ok() or not self._token_ok():
            return
        path = self.path.split("?", 1)[0]
        command = COMMANDS.get(path)
        if command is None:
            self._error(
                HTTPStatus.NOT_FOUND,
                f"no such endpoint {path!r}; the commands are {', '.join(sorted(COMMANDS))} (docs/live.md)",
            )
            return
        if not self._origin_ok():
            return
        data = self._body()
        if data is None:
            return
        try:
            answer = command(self.server, data)
        except BadRequest as err:
            self._error(HTTPStatus.BAD_REQUEST, str(err))
        except RecursionError:
            self._error(HTTPStatus.BAD_REQUEST, "the request nests too deeply; nothing was changed")
        except (LiveError, BadEdit, WorldFileError) as err:
            self._error(HTTPStatus.CONFLICT, str(err))
        except OSError as err:
            self._error(HTTPStatus.INTERNAL_SERVER_ERROR, f"could not write the file: {err}")
        else:
            self._send(HTTPStatus.OK, state_json(answer), "application/json; charset=utf-8")

    def _body(self) -> dict | None:
        """The request's JSON object ({} for an empty body), or None after answering with the error."""
        try:
            length = int(self.headers.get("Content-Length", "0") or "0")
        except ValueError:
            self._error(HTTPStatus.LENGTH_REQUIRED, "the Content-Length header is not a number")
            return None
        if length < 0 or length > MAX_BODY_BYTES:
            self._error(HTTPStatus.REQUEST_ENTITY_TOO_LARGE, f"the request is over {MAX_BODY_BYTES} bytes")
            self.close_connection = True
            return None
        if length == 0:
            return {}
        content_type = self.headers.get("Content-Type", "").split(";")[0].strip().lower()
        if content_type != "application/json":
            self._error(
                HTTPStatus.UNSUPPORTED_MEDIA_TYPE, "send the request as JSON (Content-Type: application/json)"
            )
            return None
        try:
            data = self._json_body(length)
        except BadBody as err:
            self._error(HTTPStatus.BAD_REQUEST, str(err))
            return None
        if not isinstance(data, dict):
            self._error(HTTPStatus.BAD_REQUEST, "the request must be a JSON object")
            return None
        return data


class BadRequest(ValueError):
    """A request with a missing or wrong field; the message names it."""


def _field(data: dict, name: str, kinds: tuple, required: bool = True, allow_none: bool = False):
    if name not in data:
        if required:
            raise BadRequest(f"the field {name!r} is missing")
        return None
    value = data[name]
    if value is None and allow_none:
        return None
    if isinstance(value, bool) and bool not in kinds:
        raise BadRequest(f"{name!r} must be a number, not true/false")
    if not isinstance(value, kinds) or (isinstance(value, float) and not math.isfinite(value)):
        raise BadRequest(f"{name!r} has the wrong type: {value!r}")
    return value


def _only(data: dict, allowed: set[str]) -> None:
    unknown = sorted(set(data) - allowed)
    if unknown:
        raise BadRequest(
            f"unknown field(s) {', '.join(unknown)}; this command takes {', '.join(sorted(allowed)) or 'none'}"
        )


NUMBER = (int, float)


def _pause(server: LiveServer, data: dict) -> dict:
    _only(data, set())
    return server.live.pause()


def _resume(server: LiveServer, data: dict) -> dict:
    _only(data, set())
    return server.live.resume()


def _step(server: LiveServer, data: dict) -> dict:
    _only(data, {"ms", "ticks"})
    ms = _field(data, "ms", NUMBER, required=False, allow_none=True)
    ticks = _field(data, "ticks", (int,), required=False, allow_none=True)
    if ms is not None and ticks is not None:
        raise BadRequest("give ms or ticks, not both")
    return server.live.step(ms=ms, ticks=ticks)


def _speed(server: LiveServer, data: dict) -> dict:
    _only(data, {"speed"})
    return server.live.set_speed(_field(data, "speed", NUMBER, allow_none=True))


def _reload(server: LiveServer, data: dict) -> dict:
    _only(data, set())
    return server.live.reload()


def _reset(server: LiveServer, data: dict) -> dict:
    _only(data, set())
    return server.live.reset()


def _move(server: LiveServer, data: dict) -> dict:
    _only(data, {"robot", "x_cm", "y_cm", "heading_deg"})
    robot = _field(data, "robot", (int,))
    x, y = _field(data, "x_cm", NUMBER), _field(data, "y_cm", NUMBER)
    heading = _field(data, "heading_deg", NUMBER)
    if not 1 <= robot <= len(server.live.programs):
        raise BadRequest(f"there is no robot {robot}: robots are 1 to {len(server.live.programs)}")
    return server.live.move_robot(robot - 1, x, y, heading)


def _cell(server: LiveServer, data: dict) -> dict:
    _only(data, {"col", "row", "wall", "shade", "color"})
    col, row = _field(data, "col", (int,)), _field(data, "row", (int,))
    wall = _field(data, "wall", (bool,))
    shade = _field(data, "shade", NUMBER, required=False, allow_none=True)
    color = _field(data, "color", (str,), required=False, allow_none=True)
    grid = server.live.world.grid
    if not (0 <= col < grid.width and 0 <= row < grid.height):
        raise BadRequest(
            f"cell ({col}, {row}) is outside the {grid.width}x{grid.height} grid (columns 0..{grid.width - 1}, "
            f"rows 0..{grid.height - 1}, from the bottom-left)"
        )
    border = col in (0, grid.width - 1) or row in (0, grid.height - 1)
    if border and not wall:
        raise BadRequest(
            "border cells stay walls, so the robot cannot leave the world; their colour can change"
        )
    try:
        cell = Cell(wall=wall, shade=None if shade is None else float(shade), color=color)
    except ValueError as err:
        raise BadRequest(str(err)) from None
    return server.live.set_cell(col, row, cell)


def _save_world(server: LiveServer, data: dict) -> dict:
    _only(data, set())
    saved = server.world_file.save(server.live)
    return {**server.live.state(), "saved": saved}


def _set_robot(server: LiveServer, data: dict) -> dict:
    _only(data, {"robot", "text", "mapping"})
    number = _robot(server, data)
    text = _field(data, "text", (str,), required=False)
    mapping = _field(data, "mapping", (dict,), required=False)
    if (text is None) == (mapping is None):
        raise BadRequest("give the robot as 'text' (a robot file's YAML) or as 'mapping', one of them")
    try:
        return server.live.set_robot(number - 1, text if text is not None else mapping)
    except WorldFileError as err:
        raise BadRequest(str(err)) from None


def _robot(server: LiveServer, data: dict) -> int:
    number = _field(data, "robot", (int,))
    if not 1 <= number <= len(server.live.programs):
        raise BadRequest(f"there is no robot {number}: robots are 1 to {len(server.live.programs)}")
    return number


def _save_robot(server: LiveServer, data: dict) -> dict:
    """Write a robot to its own robot file (the old one kept as .bak), or to a new file `file` in the
    folder of the world file (or of the first program, for a shipped world); never over another file
    without replace: true."""
    _only(data, {"robot", "file", "replace"})
    number = _robot(server, data)
    name = _field(data, "file", (str,), required=False, allow_none=True)
    replace = bool(_field(data, "replace", (bool,), required=False))
    live = server.live
    if name is None:
        path = live.robot_file(number - 1)
        if path is None:
            spec = live.robot_spec(number - 1)
            raise LiveError(
                f"robot {number} ({spec.name}) did not come from a robot file of yours (a shipped robot, one "
                "written inside the world file, or changed here), so there is no file to write it to; give a "
                "new file name (e.g. my-robot.yaml) to save it in the folder of your world or program"
            )
        replace = True
    else:
        if not ROBOT_FILE_NAME.fullmatch(name) or ".." in name:
            raise BadRequest(
                f"{name!r} is not a plain file name ending in .yaml (letters, digits, _ - . and spaces, no "
                "folders); the robot is saved in the folder of your world or program"
            )
        folder = (
            server.world_file.path.parent if server.world_file.path else live.programs[0].resolve().parent
        )
        path = folder / name
    text = live.robot_text(number - 1)
    if path.exists() and not replace:
        raise LiveError(
            f"{path} already exists; send replace: true to write over it (the old one is kept as .bak)"
        )
    replace_keeping_backup(path, text)
    live.adopt_robot_file(number - 1, path)
    return {**live.state(), "saved": {"saved": str(path), "robot": number}}


COMMANDS = {
    "/api/pause": _pause,
    "/api/resume": _resume,
    "/api/step": _step,
    "/api/speed": _speed,
    "/api/reload": _reload,
    "/api/reset": _reset,
    "/api/move": _move,
    "/api/cell": _cell,
    "/api/save-world": _save_world,
    "/api/robot": _set_robot,
    "/api/save-robot": _save_robot,
}


class LiveServer(PageServer):
    """The live page's server on 127.0.0.1 for one live run (page token and limits: page_guard.py)."""

    def __init__(
        self, live: LiveRun, world_file: LiveWorldFile, port: int = 0, verbose: bool = False
    ) -> None:
        self.live = live
        self.world_file = world_file
        self.world_label = str(world_file.path) if world_file.path else str(world_file.shipped_name)
        self.verbose = verbose
        self.closing = threading.Event()
        super().__init__(port, LiveHandler)

    def server_close(self) -> None:
        self.closing.set()  # the event streams end
        super().server_close()
