"""`ev3sim2d edit`: draw a world file in the browser - walls, shades, colours, the start, regions."""

from __future__ import annotations

import argparse
import re
import threading
import webbrowser
from pathlib import Path

from ..editor.server import EditorServer, WorldFile
from ..world.source_error import WorldFileError
from .exit_codes import EXIT_OK, fail

NAME = "edit"
HELP = "edit a world file in the browser (a page served on 127.0.0.1 only)"
MAX_NEW_CELLS = 200


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", metavar="FILE", help="the world file (.yaml) to edit; the only file written")
    parser.add_argument(
        "--new", metavar="WxH", help="make FILE a new walled arena of W x H cells (10 cm) first, e.g. 20x20"
    )
    parser.add_argument("--port", type=int, default=0, help="port on 127.0.0.1 (default: a free one)")
    parser.add_argument(
        "--no-browser", action="store_true", help="only print the address; do not open a browser"
    )


def new_arena_text(width: int, height: int) -> str:
    """A walled arena of white floor, cells of 10 cm, the robot in the middle facing +x."""
    rows = ["#" * width] + ["#" + "." * (width - 2) + "#" for _ in range(height - 2)] + ["#" * width]
    grid = "".join(f"  {row}\n" for row in rows)
    return (
        f"# A walled arena of {width} x {height} cells of 10 cm; the robot starts in the middle facing right.\n"
        "title: New arena\n"
        "cell_cm: 10\n"
        f"grid: |\n{grid}"
        "start:\n"
        f"  x_cm: {width * 5}\n"
        f"  y_cm: {height * 5}\n"
        "  heading_deg: 0\n"
    )


def main(args) -> int:
    path = Path(args.file)
    if args.new is not None:
        match = re.fullmatch(r"(\d+)[xX](\d+)", args.new.strip())
        if not match:
            return fail(f"--new takes the size as WxH cells, e.g. --new 20x20, got {args.new!r}")
        width, height = int(match.group(1)), int(match.group(2))
        if not (3 <= width <= MAX_NEW_CELLS and 3 <= height <= MAX_NEW_CELLS):
            return fail(f"--new: a world is 3 to {MAX_NEW_CELLS} cells each way, got {width}x{height}")
        if path.exists():
            return fail(f"{path} exists; --new never overwrites a file: give a new name, or leave out --new")
        if path.suffix not in (".yaml", ".yml"):
            return fail(f"{path}: a world file's name ends in .yaml")
        try:
            with open(path, "x", encoding="utf-8") as handle:
                handle.write(new_arena_text(width, height))
        except OSError as err:
            return fail(f"cannot write {path}: {err.strerror}")
    elif not path.is_file():
        return fail(f"{path}: no such file; to make a new world write: ev3sim2d edit --new 20x20 {path}")
    if not 0 <= args.port <= 65535:
        return fail("--port must be 0 to 65535")
    try:
        world_file = WorldFile(path)
    except WorldFileError as err:
        return fail(f"{err}; fix it in a text editor first")
    try:
        server = EditorServer(world_file, args.port)
    except OSError as err:
        return fail(f"cannot listen on 127.0.0.1:{args.port}: {err.strerror}")
    print(f"ev3sim2d edit: editing {world_file.path} at {server.url} (Ctrl+C to stop)", flush=True)
    print(
        "ev3sim2d edit: the address's #token=... is this start's key; only a page opened with it can read or "
        "change anything, so keep it to yourself (docs/editor.md)",
        flush=True,
    )
    if not args.no_browser:
        threading.Thread(target=webbrowser.open, args=(server.url,), daemon=True).start()
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        print("ev3sim2d edit: stopped", flush=True)
    finally:
        server.server_close()
    return EXIT_OK
