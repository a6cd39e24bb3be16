"""`ev3sim2d live` and `ev3sim2d edit` answer only their own user's page (issue 27, classes 1, 2, 4a).

Each attack runs against the real commands, started as a student starts them, and as the one who
would try it: another account on the same computer (no token; or the token but another uid), a web
page the student visits (another origin's page in real Chromium: fetch, POST, <img> and <script>
probes, an overlay that frames the page and clicks), a rebinding host name (Chromium's
--host-resolver-rules maps evil.test to 127.0.0.1), and hundreds of idle connections.  The honest
outcome in each: nothing read, nothing written (the world file, the robot file, their .bak), the run
not paused, the server still answering its own page within seconds, its open files bounded.
"""

from __future__ import annotations

import hashlib
import http.client
import http.server
import json
import os
import re
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from ev3sim2d.editor.page_guard import MAX_CONNECTIONS, MAX_JSON_DEPTH, TOKEN_HEADER
from tests import headless_chromium
from tests.live.test_server import arena_text

ROOT = Path(__file__).resolve().parents[2]
SECRET = "SECRET-PRINTED-LINE"
PROGRAM = f"""
from ev3dev2.display import Display
import time
print("{SECRET}")
lcd = Display()
lcd.draw.rectangle((0, 0, 177, 127), fill="black")
lcd.update()
time.sleep(600)
"""
NO_CONTENT = {"Content-Type": "application/json"}


class Started:
    """A real `ev3sim2d live` or `ev3sim2d edit` process: its address, token, folder and files."""

    def __init__(self, kind: str, folder: Path) -> None:
        self.kind, self.folder = kind, folder
        world = folder / "arena.yaml"
        world.write_text(arena_text())
        if kind == "live":
            (folder / "prog.py").write_text(PROGRAM)
            args = ["live", "prog.py", "--maze", "arena.yaml", "--no-browser"]
        else:
            args = ["edit", "arena.yaml", "--no-browser"]
        self.process = subprocess.Popen(
            [sys.executable, "-m", "ev3sim2d", *args],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, cwd=folder,
        )  # fmt: skip
        line = self.process.stdout.readline()
        found = re.search(r"http://127\.0\.0\.1:(\d+)/#token=([A-Za-z0-9_-]+)", line)
        assert found, f"no address with a token in {line!r}"
        self.port, self.token = int(found.group(1)), found.group(2)
        self.url = f"http://127.0.0.1:{self.port}/"
        if kind == "live":
            deadline = time.monotonic() + 60
            state = self.state()  # on: the program has printed its line and drawn on its screen
            while not (state["robots"] and state["robots"][0]["lcd_frame"] is not None and state["printed"]):
                assert time.monotonic() < deadline, state
                time.sleep(0.1)
                state = self.state()

    def request(self, method: str, path: str, body: bytes | None = None, headers: dict | None = None):
        connection = http.client.HTTPConnection("127.0.0.1", self.port, timeout=30)
        try:
            connection.request(method, path, body=body, headers=headers or {})
            response = connection.getresponse()
            return response.status, dict(response.getheaders()), response.read()
        finally:
            connection.close()

    def own(self, method: str, path: str, body: object = None):
        """A request as the student's page makes it."""
        data = None if body is None else json.dumps(body).encode()
        return self.request(method, path, data, {TOKEN_HEADER: self.token, **NO_CONTENT})

    def state(self) -> dict:
        status, _, body = self.own("GET", "/api/state")
        assert status == 200, body
        return json.loads(body)

    def files(self) -> dict[str, str]:
        """Every file in the folder, by name, as a hash of its bytes (what an attack must leave alone)."""
        return {
            p.name: hashlib.sha256(p.read_bytes()).hexdigest() for p in self.folder.iterdir() if p.is_file()
        }

    def open_files(self) -> int | None:
        fd_folder = Path(f"/proc/{self.process.pid}/fd")
        return len(os.listdir(fd_folder)) if fd_folder.is_dir() else None

    def stop(self) -> None:
        self.process.kill()
        self.process.wait()


@pytest.fixture(scope="module")
def servers(tmp_path_factory):
    started = {kind: Started(kind, tmp_path_factory.mktemp(kind)) for kind in ("live", "edit")}
    yield started
    for server in started.values():
        server.stop()


@pytest.fixture(params=["live", "edit"])
def server(request, servers):
    """Each server, with a check afterwards that nothing in its folder changed and the run goes on."""
    chosen = servers[request.param]
    before = chosen.files()
    yield chosen
    assert chosen.process.poll() is None, "the server died"
    assert chosen.files() == before, "an attack changed a file"
    if chosen.kind == "live":
        assert chosen.state()["status"] == "running", "an attack paused the run"


def reads(kind: str) -> list[str]:
    if kind == "live":
        return ["/api/state", "/api/events", "/api/world", "/api/lcd?robot=1", "/api/lcd?robot=1&frame=0",
                "/api/robot?robot=1", "/api/nothing-here"]  # fmt: skip
    return ["/api/world", "/api/nothing-here"]


def writes(kind: str) -> list[tuple[str, dict]]:
    if kind == "live":
        return [
            ("/api/pause", {}),
            ("/api/cell", {"col": 3, "row": 3, "wall": True}),
            ("/api/save-world", {}),
            ("/api/save-robot", {"robot": 1, "file": "arena.yaml", "replace": True}),
            ("/api/save-robot", {"robot": 1, "file": "stolen.yaml"}),
            ("/api/move", {"robot": 1, "x_cm": 30, "y_cm": 30, "heading_deg": 0}),
            ("/api/reset", {}),
        ]
    return [("/api/save", {"cell_cm": 12, "cells": [], "starts": [], "regions": []})]


# -- class 1: no proof of who is asking ------------------------------------------------------------------
@pytest.mark.parametrize("key", [None, "wrong", "same-length", "in-the-query"])
def test_without_the_token_nothing_is_read_and_nothing_is_written(server, key):
    """Another account on the computer (or any program) without the printed address's key: every read,
    the event stream and the LCD image included, and every write is refused alike, learning nothing."""
    headers = {} if key in (None, "in-the-query") else {TOKEN_HEADER: "x" * len(server.token)}
    if key == "wrong":
        headers[TOKEN_HEADER] = server.token[:-1]
    query = f"?token={server.token}" if key == "in-the-query" else ""
    answers = set()
    for path in reads(server.kind):
        joined = path + (query.replace("?", "&") if "?" in path else query)
        for method in ("GET", "HEAD"):
            status, _, body = server.request(method, joined, headers=headers)
            assert status == 403, (method, path, status)
            assert SECRET.encode() not in body and b"arena" not in body
            answers.add(body)
    for path, body in writes(server.kind) * 2:  # twice: a second `replace: true` would reach the .bak
        status, _, answer = server.request(
            "POST", path + query, json.dumps(body).encode(), {**headers, **NO_CONTENT}
        )
        assert status == 403, (path, status, answer)
        answers.add(answer)
    assert len(answers - {b""}) == 1, "the refusals differ, so they tell the endpoints apart"
    assert "#token=" in json.loads((answers - {b""}).pop())["error"]  # and tell the student what to do


def test_the_page_files_hold_no_data_and_need_no_token(server):
    """Only the page's own files (HTML, JS, CSS) are served without the key, and none holds a secret."""
    for path in ("/", "/page_token.js", "/world_canvas.js"):
        status, headers, body = server.request("GET", path)
        assert status == 200 and SECRET.encode() not in body and server.token.encode() not in body


@pytest.mark.needs_linux("proc")
def test_another_account_is_turned_away_even_with_the_token(server):
    """Where the system says who holds the other end (Linux: /proc/net/tcp), another uid is closed on
    at once, though it sends the right key; this account with the same request is answered."""
    if os.geteuid() != 0:
        pytest.skip("needs root to connect as another account (nobody)")
    ask = (
        "import http.client, sys\n"
        f"c = http.client.HTTPConnection('127.0.0.1', {server.port}, timeout=10)\n"
        f"c.request('GET', '/api/world', headers={{'{TOKEN_HEADER}': '{server.token}'}})\n"
        "try:\n    r = c.getresponse(); print(r.status, r.read()[:40])\n"
        "except (OSError, http.client.HTTPException) as err:\n    print('refused', type(err).__name__)\n"
    )
    python = next((p for p in ("/usr/bin/python3", "/usr/local/bin/python3") if os.access(p, os.X_OK)), None)
    if python is None:
        pytest.skip("no system Python another account may run")
    as_nobody = subprocess.run(
        [python, "-c", ask], capture_output=True, text=True, timeout=60, user=65534, group=65534, cwd="/"
    )
    assert as_nobody.stdout.startswith("refused"), as_nobody.stdout + as_nobody.stderr
    as_us = subprocess.run([sys.executable, "-c", ask], capture_output=True, text=True, timeout=60)
    assert as_us.stdout.startswith("200"), as_us.stdout + as_us.stderr


# -- class 2: framing, other sites' pages, rebinding --------------------------------------------------------
def test_every_answer_forbids_framing_and_referrers(server):
    for method, path, headers in [
        ("GET", "/", {}),
        ("GET", "/api/world", {TOKEN_HEADER: server.token}),
        ("GET", "/api/world", {}),
        ("GET", "/nothing", {TOKEN_HEADER: server.token}),
        ("OPTIONS", "/api/world", {}),
        ("GET", "/", {"Host": "evil.test"}),
        ("GET", "/", {"Sec-Fetch-Site": "cross-site"}),
    ]:
        _, answer, _ = server.request(method, path, headers=headers)
        assert "frame-ancestors 'none'" in answer["Content-Security-Policy"], (method, path)
        assert "default-src 'self'" in answer["Content-Security-Policy"]
        assert answer["X-Frame-Options"] == "DENY" and answer["Referrer-Policy"] == "no-referrer"


@pytest.mark.parametrize(
    "foreign",
    [
        {"Sec-Fetch-Site": "cross-site"},
        {"Sec-Fetch-Site": "same-site"},  # another port of 127.0.0.1: another program's page
        {"Origin": "http://evil.test"},
        {"Origin": "null"},
        {"Origin": "http://127.0.0.1:1"},
        {"Referer": "http://evil.test/page.html"},
    ],
)
def test_another_pages_request_is_refused_even_with_the_token(server, foreign):
    """A request another page made (the browser says so) is refused on every path, the page's files too."""
    for path in ["/", "/page_token.js", *reads(server.kind)]:
        status, _, body = server.request("GET", path, headers={TOKEN_HEADER: server.token, **foreign})
        assert status == 403 and b"other pages" in body, (path, foreign)
    path, body = writes(server.kind)[0]
    status, _, _ = server.request(
        "POST", path, json.dumps(body).encode(), {TOKEN_HEADER: server.token, **foreign, **NO_CONTENT}
    )
    assert status == 403
    status, _, _ = server.request("GET", reads(server.kind)[0], headers={TOKEN_HEADER: server.token,
                                  "Sec-Fetch-Site": "same-origin", "Origin": server.url.rstrip("/")})  # fmt: skip
    assert status == 200  # what our own page sends


ATTACKER_PAGE = """<!doctype html><meta charset="utf-8"><title>free robot games</title>
<body style="margin:0">
<iframe id="frame" src="{target}" style="position:absolute;left:0;top:0;width:1200px;height:800px;opacity:0.5"></iframe>
<script>
window.results = {{}};
function probe(kind, name, url) {{
  return new Promise((done) => {{
    const el = document.createElement(kind);
    const started = performance.now();
    el.onload = () => done([name, "load"]);
    el.onerror = () => done([name, "error"]);
    el.src = url;
    document.body.append(el);
  }});
}}
async function attack() {{
  const base = "{base}";
  const probes = [];
  for (const [name, path] of {paths}) {{
    probes.push(probe("img", "img " + name, base + path));
    probes.push(probe("script", "script " + name, base + path));
  }}
  probes.push(probe("img", "img closed port", "http://127.0.0.1:{closed}/api/state"));
  probes.push(probe("script", "script closed port", "http://127.0.0.1:{closed}/page_token.js"));
  for (const [name, outcome] of await Promise.all(probes)) window.results[name] = outcome;
  const read = [];
  for (const path of ["api/state", "api/world", "api/events"]) {{
    try {{
      const r = await fetch(base + path, {{ headers: {{ "{header}": "guess" }} }});
      read.push(await r.text());
    }} catch (err) {{ read.push("failed"); }}
    try {{
      const r = await fetch(base + path, {{ mode: "no-cors" }});
      read.push(r.type + ":" + (await r.text()));
    }} catch (err) {{ read.push("failed"); }}
  }}
  for (const [path, body] of {writes}) {{
    try {{ await fetch(base + path, {{ method: "POST", mode: "no-cors", body: JSON.stringify(body),
                                       headers: {{ "Content-Type": "text/plain" }} }}); }} catch (err) {{}}
    try {{ await fetch(base + path, {{ method: "POST", body: JSON.stringify(body),
                                       headers: {{ "Content-Type": "application/json", "{header}": "guess" }} }}); }}
    catch (err) {{}}
  }}
  window.results.read = read;
  window.results.done = true;
}}
attack();
</script>"""


def _serve_folder(folder: Path) -> http.server.ThreadingHTTPServer:
    """The attacker's site: a plain file server on another port of 127.0.0.1."""

    class Quiet(http.server.SimpleHTTPRequestHandler):
        def __init__(self, *args, **kwargs):
            super().__init__(*args, directory=str(folder), **kwargs)

        def log_message(self, *args) -> None:
            pass

    site = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Quiet)
    threading.Thread(target=site.serve_forever, daemon=True).start()
    return site


def _closed_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


@pytest.fixture(scope="module")
def browser():
    with headless_chromium.chromium() as launched:
        yield launched


def test_another_sites_page_reads_nothing_writes_nothing_and_cannot_frame_it(server, browser, tmp_path):
    """A page on another origin, in real Chromium: its <img> and <script> probes cannot tell our
    endpoints (or our page's files) from a port where nothing listens, its fetches read nothing, its
    POSTs write nothing, and the page it frames (even with the right key in the address) never renders,
    so the clicks of an overlay land nowhere."""
    paths = [[p, p.lstrip("/")] for p in reads(server.kind)] + [["page", ""], ["js", "page_token.js"]]
    (tmp_path / "attack.html").write_text(
        ATTACKER_PAGE.format(
            target=server.url + f"#token={server.token}",
            base=server.url,
            paths=json.dumps(paths),
            writes=json.dumps([[p.lstrip("/"), b] for p, b in writes(server.kind)]),
            closed=_closed_port(),
            header=TOKEN_HEADER,
        )
    )
    site = _serve_folder(tmp_path)
    page = browser.new_page(viewport={"width": 1280, "height": 900})
    try:
        page.goto(f"http://127.0.0.1:{site.server_address[1]}/attack.html")
        page.wait_for_function("window.results && window.results.done", timeout=30_000)
        results = page.evaluate("window.results")
        probes = {name: outcome for name, outcome in results.items() if name.startswith(("img", "script"))}
        assert set(probes.values()) == {"error"}, probes  # the same as the closed port's, for every path
        assert all(SECRET not in text and "arena" not in text for text in results["read"]), results["read"]
        frame = next(f for f in page.frames if f != page.main_frame)
        assert frame.evaluate("typeof window.ev3live + typeof window.ev3edit") == "undefinedundefined"
        for x, y in [(300, 300), (500, 400), (640, 450), (200, 600)]:
            page.mouse.click(x, y)  # the overlay's "click the dots"
        page.keyboard.press("Space")
        time.sleep(0.5)
    finally:
        page.close()
        site.shutdown()
        site.server_close()


def test_a_rebinding_host_name_gets_nothing(server, browser):
    """DNS rebinding: evil.test resolves to 127.0.0.1 (Chromium's --host-resolver-rules); its page, even
    with the key, and its API requests are refused by the Host check."""
    args = [*headless_chromium.ARGS, "--host-resolver-rules=MAP evil.test 127.0.0.1"]
    rebound = browser.browser_type.launch(executable_path=headless_chromium.executable(), args=args)
    try:
        page = rebound.new_page()
        response = page.goto(f"http://evil.test:{server.port}/#token={server.token}")
        assert response.status == 403 and "wrong Host" in response.text()
        for api in reads(server.kind)[:3]:
            answer = page.evaluate(
                "async ([url, header, token]) => { const r = await fetch(url, {headers: {[header]: token}});"
                " return [r.status, await r.text()]; }",
                [f"http://evil.test:{server.port}{api}", TOKEN_HEADER, server.token],
            )
            assert answer[0] == 403 and SECRET not in answer[1], (api, answer)
    finally:
        rebound.close()


def test_the_honest_page_works_with_its_policy_and_hides_its_key(server, browser):
    """The student's own page, under the servers' real policy (no bypass), loads its data with the key,
    takes the key out of the address bar, and keeps working after a reload (sessionStorage)."""
    page = browser.new_page(viewport={"width": 1280, "height": 800})
    errors: list[str] = []
    page.on("pageerror", lambda err: errors.append(str(err)))
    try:
        page.goto(server.url + f"#token={server.token}")
        ready = "() => !!(window.ev3live || window.ev3edit) && (window.ev3live || window.ev3edit).ready()"
        _until(page, ready)  # (polled from here: the policy forbids the eval that wait_for_function uses)
        assert server.token not in page.url
        page.reload()
        _until(page, ready)
        if server.kind == "live":  # the LCD image, fetched with the key, drawn (the program's black screen)
            _until(
                page,
                "() => { const c = document.querySelector('#bricks canvas');"
                " return !!c && c.getContext('2d').getImageData(89, 64, 1, 1).data[0] < 40; }",
            )
        assert errors == []
    finally:
        page.close()


def _until(page, predicate: str, timeout_s: float = 30.0) -> None:
    deadline = time.monotonic() + timeout_s
    while not page.evaluate(predicate):
        assert time.monotonic() < deadline, f"not reached: {predicate}"
        time.sleep(0.1)


# -- class 4a: unbounded work ---------------------------------------------------------------------------
def test_hundreds_of_idle_connections_do_not_lock_the_page_out(server):
    """300 sockets that send nothing: the page and the API still answer within seconds, and the server's
    open files stay bounded (the cap closes the oldest idle connection to make room)."""
    before = server.open_files()
    idle = []
    try:
        for _ in range(300):
            idle.append(socket.create_connection(("127.0.0.1", server.port), timeout=10))
        time.sleep(1.0)
        started = time.monotonic()
        status, _, _ = server.request("GET", "/")
        assert status == 200
        status, _, body = server.own("GET", reads(server.kind)[0])
        took = time.monotonic() - started
        assert status == 200 and took < 5, (status, took)
        during = server.open_files()
        if during is not None:
            print(f"{server.kind}: open files {before} before, {during} with 300 idle connections")
            assert during <= before + MAX_CONNECTIONS + 8, (before, during)
    finally:
        for sock in idle:
            sock.close()


def test_past_the_cap_of_busy_connections_the_answer_is_503_at_once(server):
    """When every connection is busy (event streams with the key), a newcomer is answered 503 at once
    and closed; when they end, the server answers again."""
    if server.kind != "live":
        pytest.skip("only the live server has long requests (the event stream)")
    streams = []
    try:
        while len(streams) < MAX_CONNECTIONS:
            connection = http.client.HTTPConnection("127.0.0.1", server.port, timeout=10)
            connection.request("GET", "/api/events", headers={TOKEN_HEADER: server.token})
            response = connection.getresponse()  # (kept: dropping it would close the stream)
            streams.append((connection, response))
            if response.status == 503:  # (a slot still held by an earlier test's stream)
                break
        started = time.monotonic()
        status, headers, body = server.own("GET", "/api/state")
        assert status == 503 and time.monotonic() - started < 3 and b"busy" in body
        assert headers["X-Frame-Options"] == "DENY"
    finally:
        for connection, response in streams:
            response.close()
            connection.close()
    deadline = time.monotonic() + 20
    while server.request("GET", "/")[0] != 200:
        assert time.monotonic() < deadline, "the server did not come back after the streams ended"
        time.sleep(0.2)


@pytest.mark.parametrize("body", [b"[" * 200_000, b"{\"a\":" * 30_000, json.dumps(
    {"robot": 1, "x": [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]}).encode()])  # fmt: skip
def test_deep_json_is_a_clear_400_never_a_traceback(server, body):
    path = "/api/save" if server.kind == "edit" else "/api/robot"
    if len(body) > 60_000 and server.kind == "live":
        body = body[:60_000]  # the live server's bodies are at most 64 KiB
    status, _, answer = server.request("POST", path, body, {TOKEN_HEADER: server.token, **NO_CONTENT})
    assert status == 400 and "nests too deeply" in json.loads(answer)["error"], answer
    assert f"at most {MAX_JSON_DEPTH}" in json.loads(answer)["error"]
