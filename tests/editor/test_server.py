"""The editor's server keeps the file safe: only its own endpoints, only its one file, atomic saves."""

import http.client
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from ev3sim2d.editor.page_guard import TOKEN_HEADER
from ev3sim2d.results.output_files import replace_keeping_backup
from ev3sim2d.world.maze_file import load_maze

ROOT = Path(__file__).resolve().parents[2]


def request(editor, method, path, body=None, headers=None, token=True):
    """A request as the editor's own page makes it: with the page token (unless token=False)."""
    connection = http.client.HTTPConnection("127.0.0.1", editor.port, timeout=10)
    sent = {TOKEN_HEADER: editor.server.token} if token else {}
    sent.update(headers or {})
    try:
        connection.request(method, path, body=body, headers=sent)
        response = connection.getresponse()
        data = response.read()
        return response.status, response.getheader("Content-Type", ""), data
    finally:
        connection.close()


def post(editor, payload, headers=None):
    body = payload if isinstance(payload, bytes) else json.dumps(payload).encode()
    return request(editor, "POST", "/api/save", body, {"Content-Type": "application/json", **(headers or {})})


def unchanged_payload(editor):
    status, _, data = request(editor, "GET", "/api/world")
    assert status == 200
    world = json.loads(data)
    return {
        "cell_cm": world["cell_cm"],
        "cells": [
            [{k: c[k] for k in ("wall", "shade", "color", "char")} for c in row] for row in world["cells"]
        ],
        "starts": world["starts"],
        "regions": world["regions"],
    }


def test_it_listens_on_127_0_0_1_only(editor_on):
    editor = editor_on("maze")
    assert editor.server.server_address[0] == "127.0.0.1"
    assert editor.url.startswith("http://127.0.0.1:")


def test_the_page_and_its_files_are_served(editor_on):
    editor = editor_on("maze")
    for path, kind in [("/", "text/html"), ("/editor.js", "javascript"), ("/editor.css", "text/css")]:
        status, content_type, body = request(editor, "GET", path)
        assert status == 200 and kind in content_type and body
    html = request(editor, "GET", "/")[2].decode()
    assert "http://" not in html and "https://" not in html  # no assets from the network


@pytest.mark.parametrize(
    "path",
    [
        "/../mazes/maze.yaml",
        "/static/editor.js",
        "/server.py",
        "/%2e%2e/server.py",
        "/api/world/../../etc/passwd",
        "/maze.yaml",
        "/editor.js/../server.py",
        "//etc/passwd",
    ],
)
def test_other_paths_are_refused(editor_on, path):
    editor = editor_on("maze")
    status, content_type, body = request(editor, "GET", path)
    assert status == 404 and "json" in content_type and "error" in json.loads(body)


def test_a_request_for_another_host_is_refused(editor_on):
    editor = editor_on("maze")
    status, _, body = request(editor, "GET", "/api/world", headers={"Host": "evil.example:80"})
    assert status == 403 and "Host" in json.loads(body)["error"]


def test_saving_unchanged_writes_nothing(editor_on):
    editor = editor_on("line")
    before = editor.path.read_bytes()
    status, _, body = post(editor, unchanged_payload(editor))
    assert status == 200 and json.loads(body)["changed"] is False
    assert editor.path.read_bytes() == before
    assert not editor.path.with_name("line.yaml.bak").exists()


def test_a_save_writes_the_file_and_keeps_the_old_one_as_bak(editor_on):
    editor = editor_on("maze")
    before = editor.path.read_text()
    payload = unchanged_payload(editor)
    payload["cells"][5][5] = {"wall": True, "shade": None, "color": None, "char": None}
    payload["starts"][0]["heading_deg"] = 0
    status, _, body = post(editor, payload)
    assert status == 200, body
    assert editor.path.with_name("maze.yaml.bak").read_text() == before
    world = load_maze(editor.path)
    assert world.grid.is_wall(5, 5) and world.start.heading_deg == 0
    assert sorted(p.name for p in editor.path.parent.iterdir()) == ["maze.yaml", "maze.yaml.bak"]


@pytest.mark.parametrize(
    "body, headers, status",
    [
        (b"{not json", {}, 400),
        (b"\xff\xfe", {}, 400),
        (b"[1, 2]", {}, 400),
        (json.dumps({"path": "/etc/passwd"}).encode(), {}, 400),
        (b"{}", {"Content-Type": "text/plain"}, 415),
        (b"{}", {"Content-Type": "application/x-www-form-urlencoded"}, 415),
        (b"{}", {"Origin": "http://evil.example"}, 403),
    ],
)
def test_malformed_requests_change_nothing(editor_on, body, headers, status):
    editor = editor_on("maze")
    before = editor.path.read_bytes()
    got, content_type, answer = post(editor, body, headers)
    assert got == status and "json" in content_type and json.loads(answer)["error"]
    assert editor.path.read_bytes() == before
    assert sorted(p.name for p in editor.path.parent.iterdir()) == ["maze.yaml"]


def test_a_too_large_body_is_refused_unread(editor_on):
    editor = editor_on("maze")
    status, _, answer = request(
        editor, "POST", "/api/save", b"{}", {"Content-Type": "application/json", "Content-Length": str(10**9)}
    )
    assert status == 413 and json.loads(answer)["error"]


def test_posting_anywhere_else_is_refused(editor_on):
    editor = editor_on("maze")
    for path in ["/api/save/../../x", "/api/world", "/", "/api/save?file=/etc/passwd"]:
        status, _, _ = request(editor, "POST", path, b"{}", {"Content-Type": "application/json"})
        assert status == 404
    assert request(editor, "PUT", "/api/save", b"{}")[0] == 405


@pytest.mark.parametrize(
    "edit, words",
    [
        (
            lambda p: p["cells"][0].__setitem__(
                3, {"wall": False, "shade": 100, "color": None, "char": None}
            ),
            "border",
        ),
        (
            lambda p: p["cells"][2].__setitem__(
                2, {"wall": True, "shade": None, "color": None, "char": None}
            ),
            "wall",
        ),
        (
            lambda p: p["cells"][2].__setitem__(
                2, {"wall": False, "shade": 500, "color": None, "char": None}
            ),
            "shade",
        ),
        (
            lambda p: p["cells"][2].__setitem__(
                2, {"wall": False, "shade": None, "color": "pink", "char": None}
            ),
            "color",
        ),
        (lambda p: p.__setitem__("cell_cm", -1), "cell_cm"),
        (lambda p: p.__setitem__("cell_cm", "10"), "cell_cm"),
        (lambda p: p["starts"].clear(), "starts"),
        (lambda p: p["regions"].append({"name": "x", "rects": [[0, 0, 5000, 10]]}), "outside"),
        (lambda p: p["regions"].append({"name": "", "rects": [[0, 0, 10, 10]]}), "name"),
        (lambda p: p["cells"].pop(), "border"),
        (lambda p: p["cells"][3].pop(), "same length"),
    ],
)
def test_a_broken_world_is_refused_with_the_reason_and_nothing_written(editor_on, edit, words):
    editor = editor_on("maze")
    before = editor.path.read_bytes()
    payload = unchanged_payload(editor)
    edit(payload)
    status, _, answer = post(editor, payload)
    assert status == 400
    assert words in json.loads(answer)["error"]
    assert editor.path.read_bytes() == before
    assert sorted(p.name for p in editor.path.parent.iterdir()) == ["maze.yaml"]


def test_saving_leaves_the_old_file_when_writing_fails(tmp_path, monkeypatch):
    path = tmp_path / "w.yaml"
    path.write_text("old")

    def broken_replace(src, dst):
        raise OSError("disk full")

    monkeypatch.setattr(os, "replace", broken_replace)
    with pytest.raises(OSError):
        replace_keeping_backup(path, "new")
    assert path.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["w.yaml"]


def test_saving_renames_into_place_and_keeps_the_old_one(tmp_path):
    path = tmp_path / "w.yaml"
    path.write_text("old")
    replace_keeping_backup(path, "new")
    assert path.read_text() == "new" and (tmp_path / "w.yaml.bak").read_text() == "old"


# -- the command ------------------------------------------------------------------------------------


def cli(*args, cwd=None):
    return subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "edit", *map(str, args)],
        capture_output=True,
        text=True,
        timeout=60,
        cwd=cwd or ROOT,
    )


def test_new_refuses_to_overwrite_and_checks_the_size(tmp_path):
    existing = tmp_path / "x.yaml"
    existing.write_text("keep me")
    result = cli("--new", "20x20", "--no-browser", existing)
    assert result.returncode == 2 and "never overwrites" in result.stderr
    assert existing.read_text() == "keep me"
    result = cli("--new", "2x20", "--no-browser", tmp_path / "y.yaml")
    assert result.returncode == 2 and not (tmp_path / "y.yaml").exists()
    result = cli("--no-browser", tmp_path / "missing.yaml")
    assert result.returncode == 2 and "--new" in result.stderr


def test_new_makes_a_walled_arena_and_serves_it(tmp_path):
    path = tmp_path / "new.yaml"
    process = subprocess.Popen(
        [sys.executable, "-m", "ev3sim2d", "edit", "--new", "12x8", "--no-browser", str(path)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=ROOT,
    )
    try:
        line = process.stdout.readline()
        assert "http://127.0.0.1:" in line and "/#token=" in line
        port = int(line.split("http://127.0.0.1:")[1].split("/")[0])
        token = line.split("#token=")[1].split()[0]
        connection = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
        connection.request("GET", "/api/world")
        refused = connection.getresponse()
        assert refused.status == 403 and "#token=" in json.loads(refused.read())["error"]
        connection = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
        connection.request("GET", "/api/world", headers={TOKEN_HEADER: token})
        world = json.loads(connection.getresponse().read())
        assert (world["width"], world["height"], world["cell_cm"]) == (12, 8, 10)
    finally:
        process.terminate()
        process.wait(timeout=10)
    world = load_maze(path)
    assert (world.grid.width, world.grid.height, world.grid.cell_cm) == (12, 8, 10)
    assert (world.start.x_cm, world.start.y_cm, world.start.heading_deg) == (60, 40, 0)
    assert all(world.grid.is_wall(c, r) for c, r, _ in world.grid.cells() if c in (0, 11) or r in (0, 7))
    assert sum(not cell.wall for _, _, cell in world.grid.cells()) == 10 * 6


def test_a_broken_world_file_is_not_opened(tmp_path):
    path = tmp_path / "broken.yaml"
    path.write_text("grid: |\n  ###\n  #.x\n  ###\nstart: {cell: [1, 1]}\n")
    started = time.monotonic()
    result = cli("--no-browser", path)
    assert result.returncode == 2 and "broken.yaml:3" in result.stderr and time.monotonic() - started < 60
