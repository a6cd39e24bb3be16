"""An editor server on a temporary copy of a maze, in a thread, for the server and browser tests."""

import shutil
import threading
from pathlib import Path

import pytest

from ev3sim2d.editor.server import EditorServer, WorldFile

MAZES = Path(__file__).resolve().parents[2] / "mazes"


class RunningEditor:
    """A started editor: its file, its address, and a way to stop it."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.server = EditorServer(WorldFile(path))
        self.thread = threading.Thread(target=self.server.serve_forever, daemon=True)
        self.thread.start()

    @property
    def url(self) -> str:
        return self.server.url

    @property
    def port(self) -> int:
        return self.server.server_address[1]

    def stop(self) -> None:
        self.server.shutdown()
        self.server.server_close()


@pytest.fixture
def editor_on(tmp_path):
    """editor_on('maze') starts an editor on a copy of mazes/maze.yaml in a temporary folder."""
    started = []

    def start(name: str) -> RunningEditor:
        folder = tmp_path / "work"
        folder.mkdir(exist_ok=True)
        path = folder / f"{name}.yaml"
        shutil.copy(MAZES / f"{name}.yaml", path)
        editor = RunningEditor(path)
        started.append(editor)
        return editor

    yield start
    for editor in started:
        editor.stop()
