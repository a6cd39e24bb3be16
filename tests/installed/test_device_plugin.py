"""A new kind of sensor, the way docs/devices.md tells a user to add one: the page's laser-ev3 package
written out from the page, `pip install -e laser-ev3` into the venv that has the installed ev3sim2d, and
the page's command run with the page's robot file and program.  (tests/devices/test_new_device_kind.py
checks the same files in-tree, with a hand-made dist-info.)

The command is the page's: pip builds the package in an isolated environment with setuptools from the
same sources the fixture installed ev3sim2d's dependencies from (with `--no-build-isolation` the venv's
setuptools 65 fails without the `wheel` package), and finds its one dependency, ev3sim2d, installed.
It is uninstalled afterwards: the venv is shared with the other tests."""

import re

import pytest

from tests.devices.test_new_device_kind import PAGE, page_blocks


@pytest.fixture
def laser_ev3_installed(installed, user_folder):
    package = user_folder / "laser-ev3"
    package.mkdir()
    (package / "laser_ev3.py").write_text(page_blocks("python")[0])
    (package / "pyproject.toml").write_text(page_blocks("toml")[0])
    done = installed.run("pip", "install", "-q", "-e", "laser-ev3", cwd=user_folder)
    assert done.returncode == 0, done.stdout + done.stderr
    yield package
    removed = installed.run("pip", "uninstall", "-q", "-y", "laser-ev3", cwd=user_folder)
    assert removed.returncode == 0, removed.stderr


def test_the_pages_package_installed_with_pip_gives_run_its_kind(installed, user_folder, laser_ev3_installed):
    (user_folder / "laser-robot.yaml").write_text(page_blocks("yaml")[0])
    (user_folder / "laser.py").write_text(page_blocks("python")[1])
    (command,) = re.findall(r"^(ev3sim2d run .*)$", PAGE.read_text(), flags=re.MULTILINE)
    done = installed.run(f"{command} --time 1", cwd=user_folder, shell=True)
    assert done.returncode == 0, done.stderr
    [reading] = [line for line in done.stdout.splitlines() if "laser-ev3-range" in line]
    assert reading.split()[-4:] == ["laser-ev3-range", "DIST-MM", "mm", reading.split()[-1]]
    assert 0 < int(reading.split()[-1]) <= 2000  # mm, up to the robot file's max_cm: 200
    assert (user_folder / "laser.png").read_bytes().startswith(b"\x89PNG")


def test_without_the_package_the_robot_file_names_the_unknown_kind(installed, user_folder):
    (user_folder / "laser-robot.yaml").write_text(page_blocks("yaml")[0])
    (user_folder / "laser.py").write_text(page_blocks("python")[1])
    done = installed.run("ev3sim2d", "run", "laser.py", "--robot", "laser-robot.yaml", cwd=user_folder)
    assert done.returncode == 2, done.stdout + done.stderr
    assert "laser-robot.yaml" in done.stderr and "unknown kind 'laser-range'" in done.stderr
    assert "Traceback" not in done.stderr and "KeyError" not in done.stderr
