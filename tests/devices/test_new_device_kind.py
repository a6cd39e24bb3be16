"""A new kind of sensor added as a user would (docs/devices.md): a package of one's own with one class
and an `ev3sim2d.devices` entry point, a robot file that uses the kind, a real program that reads it
by its driver name in a real brick, and a picture of the run.  The files are the page's own."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from ev3sim2d.devices import registry
from ev3sim2d.devices.sensor import LegoSensor, Mode
from ev3sim2d.render.frame import write_png
from ev3sim2d.simulator.run import run_programs
from ev3sim2d.world.robot_spec import load_robot, parse_robot
from ev3sim2d.world.source_error import WorldFileError
from tests.inline_world import arena, two_wheel_robot

PAGE = Path(__file__).resolve().parents[2] / "docs" / "devices.md"
START = "x_cm: 60\n  y_cm: 120\n  heading_deg: 0"  # the laser 8 cm ahead, at x 68; the wall's face at x 228


def page_blocks(language: str) -> list[str]:
    """The page's fenced code blocks in `language`, in order."""
    return re.findall(rf"^```{language}\n(.*?)^```", PAGE.read_text(), flags=re.DOTALL | re.MULTILINE)


@pytest.fixture
def kinds_as_they_were():
    """Whatever a test registers is forgotten after it, and so is the user's package."""
    saved = dict(registry.SENSORS)
    modules = set(sys.modules)
    yield
    registry.SENSORS.clear()
    registry.SENSORS.update(saved)
    for name in set(sys.modules) - modules:
        if name.startswith(("laser_ev3", "light_gate")):
            del sys.modules[name]


@pytest.fixture
def laser_installed(tmp_path, monkeypatch, kinds_as_they_were) -> Path:
    """The page's laser-ev3 package, installed as pip would: its module and a dist-info with the entry
    points of its pyproject.toml, in a site folder on the path."""
    tomllib = pytest.importorskip("tomllib", reason="reading TOML needs Python 3.11")
    device, *_ = page_blocks("python")
    project = tomllib.loads(page_blocks("toml")[0])["project"]
    site = tmp_path / "site"
    site.mkdir()
    (site / "laser_ev3.py").write_text(device)
    info = site / f"laser_ev3-{project['version']}.dist-info"
    info.mkdir()
    (info / "METADATA").write_text(
        f"Metadata-Version: 2.1\nName: {project['name']}\nVersion: {project['version']}\n"
    )
    groups = "".join(
        f"[{group}]\n" + "".join(f"{name} = {value}\n" for name, value in points.items())
        for group, points in project["entry-points"].items()
    )
    (info / "entry_points.txt").write_text(groups)
    monkeypatch.syspath_prepend(str(site))
    return site


def test_a_plugin_kind_is_read_by_a_real_program_and_drawn(tmp_path, laser_installed):
    robot_file = tmp_path / "laser-robot.yaml"
    robot_file.write_text(page_blocks("yaml")[0])
    program = tmp_path / "laser.py"
    program.write_text(page_blocks("python")[1])

    robot = load_robot(robot_file)  # the kind comes from the entry point: no import, no register()
    assert robot.sensor("1").kind == "laser-range"
    assert robot.sensor("1").options == {"max_cm": 200.0}
    result = run_programs([program], arena(start=START), robot, 1.0, 0, 5.0, None)

    assert result.ok, result.reason
    printed = [line.text for line in result.trace.output if line.stream == "stdout"]
    assert printed == ["laser-ev3-range DIST-MM mm 1600"]  # 228 - 68 cm, in mm
    picture = tmp_path / "laser.png"
    write_png(result.trace, picture, (480, 270))
    assert picture.stat().st_size > 1000


def test_the_page_s_command_runs_the_plugin_kind(tmp_path, laser_installed):
    """`ev3sim2d run` with the package installed finds the kind itself (the page's command, as written)."""
    (tmp_path / "laser-robot.yaml").write_text(page_blocks("yaml")[0])
    (tmp_path / "laser.py").write_text(page_blocks("python")[1])
    (command,) = re.findall(r"^(ev3sim2d run .*)$", PAGE.read_text(), flags=re.MULTILINE)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(laser_installed), *sys.path]))
    done = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", *command.split()[1:], "--time", "1"],
        cwd=tmp_path,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    assert "laser-ev3-range DIST-MM mm" in done.stdout
    assert (tmp_path / "laser.png").stat().st_size > 1000


def test_the_panel_shows_a_plugin_reading_with_its_unit_and_label(laser_installed):
    from ev3sim2d.render.panel import sensor_value_text
    from ev3sim2d.render.robot_layer import sensor_device

    assert sensor_device("laser-range").LABEL == "laser"
    assert sensor_value_text("laser-range", "DIST-MM", [1600]) == "1600 mm"


def test_a_kind_nobody_installed_is_drawn_as_any_sensor():
    from ev3sim2d.render.panel import sensor_value_text
    from ev3sim2d.render.robot_layer import SensorLook, beam_distance_cm, sensor_device

    assert sensor_device("sonar-9000") is LegoSensor
    assert sensor_value_text("sonar-9000", "RANGE", [12, 7]) == "12 7"
    assert beam_distance_cm(SensorLook("in1", "sonar-9000", 0, 8, "forward"), ("RANGE", [12])) is None


# -- register(), from Python, and what it refuses --------------------------------------------------------


class LightGate(LegoSensor):
    """Whether a robot's body crosses the line the sensor looks along, within 30 cm (1) or not (0)."""

    KIND = "light-gate"
    DRIVER = "demo-light-gate"
    MODES = {"GATE": Mode(1, 0, "", "s8", 0, 1, noisy=False)}
    FACINGS = ("forward",)

    def measure(self, mode):
        x, y, facing = self.position()
        return (0 if self.around.ray(x, y, facing, 30.0) is None else 1,)


def test_register_makes_a_kind_usable_in_robot_files(kinds_as_they_were):
    assert registry.register(LightGate) is LightGate
    robot = parse_robot(two_wheel_robot("gate", "{port: 2, kind: light-gate, radius_cm: 8}"))
    assert robot.sensor("2").facing == "forward"  # its first facing is its default
    assert "light-gate" in registry.sensor_kinds()


def test_a_facing_the_kind_does_not_model_is_refused_with_the_reason(kinds_as_they_were):
    registry.register(LightGate)
    with pytest.raises(WorldFileError) as caught:
        parse_robot(two_wheel_robot("gate", "{port: 2, kind: light-gate, facing: down}"))
    message = str(caught.value)
    assert "light-gate sensor cannot face down" in message and "write `facing: forward`" in message


def test_an_unknown_kind_lists_the_kinds_there_are():
    with pytest.raises(WorldFileError) as caught:
        parse_robot(two_wheel_robot("r", "{port: 2, kind: laser}"), "my-robot.yaml")
    message = str(caught.value)
    assert "my-robot.yaml" in message and "unknown kind 'laser'" in message
    assert "touch, gyro, color, ultrasonic, infrared, nxt-light, nxt-sound" in message


@pytest.mark.parametrize(
    ("attributes", "says"),
    [
        ({"KIND": "", "DRIVER": "x", "MODES": {"A": Mode(1)}}, "needs its own KIND, the lower-case name"),
        ({"KIND": "Big", "DRIVER": "x", "MODES": {"A": Mode(1)}}, 'add e.g. `KIND = "light-gate"`'),
        ({"KIND": "gate", "MODES": {"A": Mode(1)}}, "has no DRIVER"),
        ({"KIND": "gate", "DRIVER": "x"}, "has no MODES"),
        ({"KIND": "gate", "DRIVER": "x", "MODES": {"A": Mode(1)}, "FACINGS": ("up",)}, "FACINGS must list"),
        ({"KIND": "color", "DRIVER": "x", "MODES": {"A": Mode(1)}}, "which is ColorSensor's"),
    ],
)
def test_register_says_what_to_fix_in_which_file(attributes, says, kinds_as_they_were):
    cls = type("Broken", (LegoSensor,), attributes)
    cls.__module__ = __name__
    with pytest.raises(registry.DeviceKindError) as caught:
        registry.register(cls)
    assert says in str(caught.value)
    assert str(caught.value).startswith(__file__)


def test_a_subclass_must_name_its_own_kind(kinds_as_they_were):
    class LongRangeUltrasonic(registry.UltrasonicSensor):
        DRIVER = "demo-long-us"

    with pytest.raises(registry.DeviceKindError, match="inherits 'ultrasonic'"):
        registry.register(LongRangeUltrasonic)


def test_a_plugin_that_does_not_load_is_named_at_the_robot_files_line(
    tmp_path, monkeypatch, kinds_as_they_were
):
    site = tmp_path / "site"
    info = site / "light_gate-1.0.dist-info"
    info.mkdir(parents=True)
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: light-gate\nVersion: 1.0\n")
    (info / "entry_points.txt").write_text("[ev3sim2d.devices]\nlight-gate = light_gate_missing:LightGate\n")
    monkeypatch.syspath_prepend(str(site))
    text = two_wheel_robot("r", "{port: 2, kind: light-gate}")
    with pytest.raises(WorldFileError) as caught:
        parse_robot(text, "gate-robot.yaml")
    message = str(caught.value)
    assert "gate-robot.yaml" in message
    assert "light-gate = light_gate_missing:LightGate (package light-gate) does not load" in message
    assert "No module named 'light_gate_missing'" in textwrap.dedent(message)
