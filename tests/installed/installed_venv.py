"""ev3sim2d as a user installs it: a wheel built by pip from a copy of the sources, installed into a
fresh virtual environment of its own (no system site-packages; the dependencies come from pip's usual
sources and cache), then its `plot` extra (matplotlib: a test of a user without it hides it), and
commands run in a folder that is not the checkout.

`.ci/run` makes one with `python -m tests.installed.installed_venv DIR` and hands it to the tests in
EV3SIM2D_INSTALLED_VENV; without that variable the tests' fixture makes one the same way, once a session.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SOURCES = (
    "setup.py",
    "setup.cfg",
    "pyproject.toml",
    "README.md",
    "ev3sim2d",
    "ev3dev2",
    "pybricks",
    "mazes",
    "lessons",
    "examples",
)
ENV_VAR = "EV3SIM2D_INSTALLED_VENV"


@dataclass(frozen=True)
class InstalledVenv:
    """A virtual environment with the wheel installed, and the wheel itself."""

    venv: Path
    wheel: Path

    @property
    def bin(self) -> Path:
        """Where the venv's commands are: bin/, or Scripts\\ on Windows."""
        return scripts_folder(self.venv)

    def environment(self) -> dict[str, str]:
        """The user's environment with this venv activated, as `source .venv/bin/activate` would."""
        environment = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
        environment["VIRTUAL_ENV"] = str(self.venv)
        environment["PATH"] = f"{self.bin}{os.pathsep}{environment.get('PATH', '/usr/bin:/bin')}"
        return environment

    def run(
        self, *command: str, cwd: Path, timeout: float = 300, shell: bool = False, env: dict | None = None
    ):
        """Run a command (the installed `ev3sim2d`, `python`, ...) in `cwd`, as a user would type it
        (`env`: variables the user sets besides)."""
        environment = {**self.environment(), **(env or {})}
        if not shell:  # found on the venv's PATH, as a shell finds it (Windows looks in the caller's own)
            command = (shutil.which(command[0], path=environment["PATH"]) or command[0], *command[1:])
        return subprocess.run(
            command[0] if shell else list(command),
            shell=shell,
            cwd=cwd,
            env=environment,
            capture_output=True,
            text=True,
            timeout=timeout,
            stdin=subprocess.DEVNULL,
        )


def build_wheel(folder: Path) -> Path:
    """`pip wheel --no-deps` of a copy of the sources (an in-tree build would leave build/ behind)."""
    source = folder / "source"
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc", "*.egg-info")
    source.mkdir(parents=True)
    for name in SOURCES:
        path = ROOT / name
        if path.is_dir():
            shutil.copytree(path, source / name, ignore=ignore)
        else:
            shutil.copy2(path, source / name)
    _check([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(folder / "dist"), str(source)])
    shutil.rmtree(source)
    [wheel] = (folder / "dist").glob("ev3sim2d-*.whl")
    return wheel


def make(folder: Path) -> InstalledVenv:
    """Build the wheel into folder/dist and install it into a fresh folder/venv."""
    folder.mkdir(parents=True, exist_ok=True)
    wheel = build_wheel(folder)
    venv = folder / "venv"
    _check([sys.executable, "-m", "venv", str(venv)])
    pip = [str(scripts_folder(venv) / "python"), "-m", "pip", "install", "-q"]
    _check([*pip, str(wheel)])  # the README's install
    _check([*pip, f"{wheel}[plot]"])  # then the `plot` extra docs/python-api.ipynb asks for
    return InstalledVenv(venv, wheel)


def scripts_folder(venv: Path) -> Path:
    """A venv's folder of commands: `Scripts` where Python makes that one (Windows), else `bin`."""
    scripts = venv / "Scripts"
    return scripts if scripts.is_dir() and not (venv / "bin").is_dir() else venv / "bin"


def from_environment() -> InstalledVenv | None:
    """The venv .ci/run made, if it made one."""
    venv = os.environ.get(ENV_VAR)
    if not venv:
        return None
    [wheel] = (Path(venv).parent / "dist").glob("ev3sim2d-*.whl")
    return InstalledVenv(Path(venv), wheel)


def _check(command: list[str]) -> None:
    done = subprocess.run(command, capture_output=True, text=True, timeout=900)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed ({done.returncode}):\n{done.stdout}\n{done.stderr}")


if __name__ == "__main__":
    started = time.monotonic()
    made = make(Path(sys.argv[1]).resolve())
    print(made.venv)
    print(
        f"built {made.wheel.name} and installed it in a fresh venv in {time.monotonic() - started:.0f} s",
        file=sys.stderr,
    )
