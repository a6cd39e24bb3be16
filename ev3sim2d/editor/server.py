"""The editor's web server: one page and a small JSON API, on 127.0.0.1, for one world file.

GET /api/world gives the world as JSON; POST /api/save takes the edited world,
writes it into the file's text (see maze_writer), reads that text back with the
world loader and only then replaces the file - atomically, keeping the previous
version as FILE.bak.  Anything else is refused with a JSON error: other paths,
large or non-JSON bodies, other hosts or origins.  Nothing but the one file
(and its .bak) is ever written.  Who may ask (the page token, no other site's page, never framed) and
how many at once: ev3sim2d/editor/page_guard.py.
"""

from __future__ import annotations

import json
import math
import threading
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler
from pathlib import Path

from ..results.output_files import replace_keeping_backup
from ..world.maze_writer import write_maze_text
from ..world.source_error import WorldFileError
from ..world.world_json import BadEdit, MazeSource, edited_from_json
from ..world.yaml_source import read_text_file
from .page_guard import (
    MAX_JSON_DEPTH,
    REQUEST_TIMEOUT_S,
    SECURITY_HEADERS,
    TOKEN_HEADER,
    PageServer,
    json_depth_ok,
    token_matches,
)

STATIC_DIR = Path(__file__).with_name("static")
STATIC_FILES = {
    "/": ("index.html", "text/html; charset=utf-8"),
    "/index.html": ("index.html", "text/html; charset=utf-8"),
    "/editor.js": ("editor.js", "text/javascript; charset=utf-8"),
    "/world_canvas.js": ("world_canvas.js", "text/javascript; charset=utf-8"),  # shared with the live page
    "/page_token.js": ("page_token.js", "text/javascript; charset=utf-8"),  # shared with the live page
    "/editor.css": ("editor.css", "text/css; charset=utf-8"),
}
MAX_BODY_BYTES = 4 * 1024 * 1024


class WorldFile:
    """The one file this editor may write, with its current text; saving is one at a time."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path).resolve()
        self._lock = threading.Lock()
        self.source = MazeSource(read_text_file(self.path), str(self.path))

    def world_json(self) -> dict:
        with self._lock:
            return self.source.to_json()

    def save(self, data: object) -> dict:
        """Write the edited world; BadEdit or WorldFileError (and nothing written) when it is not a valid world."""
        edited = edited_from_json(data)
        with self._lock:
            try:
                text = write_maze_text(self.source, edited)
            except ValueError as err:
                raise BadEdit(str(err)) from None
            new_source = MazeSource(text, str(self.path))  # raises WorldFileError when the world is broken
            _check_reflects(new_source, edited)
            changed = text != self.source.text
            if changed:
                replace_keeping_backup(self.path, text)
            self.source = new_source
            return {"saved": str(self.path), "changed": changed, "world": new_source.to_json()}


def _check_reflects(source: MazeSource, edited) -> None:
    """The text read back is the edited world (a mismatch is our bug, so it stays loud)."""
    grid = source.grid
    cells = [[grid.cell(col, row) for col in range(grid.width)] for row in range(grid.height)]
    same_starts = len(source.starts) == len(edited.starts) and all(
        math.isclose(a, b, abs_tol=1e-5)
        for got, want in zip(source.starts, edited.starts, strict=True)
        for a, b in zip(got.as_dict().values(), want.as_dict().values(), strict=True)
    )
    if cells != [[item.cell for item in row] for row in edited.cells] or not same_starts:
        raise RuntimeError("the written world does not read back as edited; nothing was saved")


class EditorHandler(BaseHTTPRequestHandler):
    """Serves the page, GET /api/world and POST /api/save; refuses everything else."""

    server: EditorServer
    server_version = "ev3sim2d-editor"
    sys_version = ""
    timeout = REQUEST_TIMEOUT_S  # a request must arrive (and a stream's reader keep reading) within this
    program_name = "ev3sim2d edit"

    def log_message(self, format: str, *args) -> None:  # noqa: A002 - the base class's name
        if self.server.verbose:
            super().log_message(format, *args)

    # -- the connection: waiting for a request (it may be closed for room) or serving one -----------
    def handle_one_request(self) -> None:
        self.server.mark(waiting=True)
        super().handle_one_request()

    def parse_request(self) -> bool:
        ok = super().parse_request()
        if ok:
            self.server.mark(waiting=False)
        return ok

    # -- answers ---------------------------------------------------------------------
    def end_headers(self) -> None:
        for name, value in SECURITY_HEADERS:  # every answer, errors and the event stream included
            self.send_header(name, value)
        super().end_headers()

    def _send(self, status: int, body: bytes, content_type: str) -> None:
        self.send_response(status)
        self.send_header("Content-Type", content_type)
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        if self.command != "HEAD":
            self.wfile.write(body)

    def _json(self, status: int, payload: dict) -> None:
        self._send(status, json.dumps(payload).encode("utf-8"), "application/json; charset=utf-8")

    def _error(self, status: int, message: str) -> None:
        self._json(status, {"error": message})

    # -- who is asking -----------------------------------------------------------------
    def _page_request_ok(self) -> bool:
        """Our own Host (no DNS rebinding), and not another site's page: the same answer for every path,
        so a page elsewhere learns nothing from what it asks for."""
        if not self._host_ok():
            return False
        own = f"http://{self.headers.get('Host', '')}"
        site = self.headers.get("Sec-Fetch-Site")
        origin = self.headers.get("Origin")
        referer = self.headers.get("Referer")
        # Our page only ever asks its own origin ("same-origin"); the student opening the address is
        # "none".  "same-site" is another port of 127.0.0.1 - another program's page - so it is refused.
        if (
            (site is not None and site not in ("same-origin", "none"))
            or (origin is not None and origin != own)
            or (referer is not None and referer != own and not referer.startswith(own + "/"))
        ):
            self.close_connection = True
            self._error(HTTPStatus.FORBIDDEN, "requests from other pages than this server's own are refused")
            return False
        return True

    def _token_ok(self) -> bool:
        """The request carries this server start's page token (X-Ev3sim2d-Token)."""
        if token_matches(self.headers.get(TOKEN_HEADER), self.server.token):
            return True
        self.close_connection = True
        self._error(
            HTTPStatus.FORBIDDEN,
            f"this request does not carry the page's key: open the address {self.program_name} printed (it "
            f"ends in #token=...); a script sends the key as the header {TOKEN_HEADER}",
        )
        return False

    def _origin_ok(self) -> bool:
        """A POST comes from our own page, not from another site's page in the same browser."""
        origin = self.headers.get("Origin")
        port = self.server.server_address[1]
        if origin is not None and origin not in (f"http://127.0.0.1:{port}", f"http://localhost:{port}"):
            self._error(HTTPStatus.FORBIDDEN, f"requests from {origin} are refused")
            return False
        return True

    def _host_ok(self) -> bool:
        """Only our own address (a web page elsewhere cannot reach us through DNS rebinding)."""
        port = self.server.server_address[1]
        host = self.headers.get("Host", "")
        if host not in (f"127.0.0.1:{port}", f"localhost:{port}"):
            self.close_connection = True
            self._error(HTTPStatus.FORBIDDEN, f"wrong Host {host!r}; open http://127.0.0.1:{port}/")
            return False
        return True

    def _json_body(self, length: int) -> object:
        """The body's JSON, or a BadBody naming what is wrong with it."""
        try:
            data = json.loads(self.rfile.read(length).decode("utf-8"))
        except (UnicodeDecodeError, json.JSONDecodeError) as err:
            raise BadBody(f"the request is not JSON: {err}") from None
        except RecursionError:
            raise BadBody(f"the request's JSON nests too deeply (at most {MAX_JSON_DEPTH} levels)") from None
        if not json_depth_ok(data):
            raise BadBody(f"the request's JSON nests too deeply (at most {MAX_JSON_DEPTH} levels)")
        return data

    # -- requests --------------------------------------------------------------------
    def do_GET(self) -> None:  # noqa: N802 - http.server's name
        if not self._page_request_ok():
            return
        path = self.path.split("?", 1)[0]
        static = STATIC_FILES.get(path)
        if static is not None:  # the page's own files hold no data: no token needed
            name, content_type = static
            self._send(HTTPStatus.OK, (STATIC_DIR / name).read_bytes(), content_type)
            return
        if not self._token_ok():
            return
        if path == "/api/world":
            self._json(HTTPStatus.OK, self.server.world_file.world_json())
            return
        self._error(HTTPStatus.NOT_FOUND, f"no such page {path!r}")

    do_HEAD = do_GET

    def do_POST(self) -> None:  # noqa: N802
        if not self._page_request_ok() or not self._token_ok():
            return
        if self.path != "/api/save":
            self._error(
                HTTPStatus.NOT_FOUND, f"no such endpoint {self.path!r}; the editor saves with POST /api/save"
            )
            return
        if not self._origin_ok():
            return
        content_type = self.headers.get("Content-Type", "").split(";")[0].strip().lower()
        if content_type != "application/json":
            self._error(
                HTTPStatus.UNSUPPORTED_MEDIA_TYPE, "send the world as JSON (Content-Type: application/json)"
            )
            return
        try:
            length = int(self.headers.get("Content-Length", ""))
        except ValueError:
            self._error(HTTPStatus.LENGTH_REQUIRED, "a Content-Length header is needed")
            return
        if length < 0 or length > MAX_BODY_BYTES:
            self._error(HTTPStatus.REQUEST_ENTITY_TOO_LARGE, f"the request is over {MAX_BODY_BYTES} bytes")
            self.close_connection = True
            return
        try:
            data = self._json_body(length)
        except BadBody as err:
            self._error(HTTPStatus.BAD_REQUEST, str(err))
            return
        try:
            result = self.server.world_file.save(data)
        except RecursionError:
            self._error(HTTPStatus.BAD_REQUEST, "the world sent nests too deeply; nothing was saved")
        except BadEdit as err:
            self._error(HTTPStatus.BAD_REQUEST, str(err))
        except WorldFileError as err:
            self._error(HTTPStatus.BAD_REQUEST, f"not saved: {err}")
        except OSError as err:
            self._error(HTTPStatus.INTERNAL_SERVER_ERROR, f"could not write the file: {err}")
        except RuntimeError as err:
            self._error(HTTPStatus.INTERNAL_SERVER_ERROR, str(err))
        else:
            self._json(HTTPStatus.OK, result)

    def _refuse(self) -> None:
        if self._page_request_ok():
            self._error(HTTPStatus.METHOD_NOT_ALLOWED, f"{self.command} is not supported")

    do_PUT = do_DELETE = do_PATCH = do_OPTIONS = _refuse


class BadBody(ValueError):
    """A request body that is not the JSON asked for; the message says why."""


class EditorServer(PageServer):
    """The editor's server on 127.0.0.1 for one world file (page token and limits: page_guard.py)."""

    def __init__(self, world_file: WorldFile, port: int = 0, verbose: bool = False) -> None:
        self.world_file = world_file
        self.verbose = verbose
        super().__init__(port, EditorHandler)
