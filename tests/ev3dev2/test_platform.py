"""
get_current_platform() and the port names it picks, as python-ev3dev2 2.1.0: 'ev3', or 'fake'
when the environment sets FAKE_SYS (its own tests do, to run on a fake sysfs), where motors are
on 'outA'... and sensors on 'in1'..., and there are no LEDs.  Each case imports the shim afresh
in a Python of its own, since the names are chosen when the modules are imported.
"""

import json
import os
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

REPORT = """
import json
import ev3dev2, ev3dev2.auto as auto, ev3dev2.led as led, ev3dev2.motor as motor, ev3dev2.sensor as sensor
print(json.dumps({
    "platform": ev3dev2.get_current_platform(),
    "motor": [motor.platform, motor.OUTPUT_A, motor.OUTPUT_D],
    "sensor": [sensor.platform, sensor.INPUT_1, sensor.INPUT_4],
    "led": [led.platform, len(led.LEDS), len(led.LED_GROUPS), led.LED_DEFAULT_COLOR],
    "auto": [auto.platform, auto.OUTPUT_A, auto.INPUT_1, len(auto.LEDS)],
}))
"""


def shim_in_a_fresh_python(fake_sys):
    env = {k: v for k, v in os.environ.items() if k not in ("FAKE_SYS", "PYTHONSAFEPATH")}
    if fake_sys is not None:
        env["FAKE_SYS"] = fake_sys
    run = subprocess.run(
        [sys.executable, "-c", REPORT], cwd=ROOT, env=env, capture_output=True, text=True, timeout=60
    )
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout)


@pytest.mark.parametrize("fake_sys", [None, ""])
def test_the_simulated_brick_is_an_ev3(fake_sys):
    assert shim_in_a_fresh_python(fake_sys) == {
        "platform": "ev3",
        "motor": ["ev3", "ev3-ports:outA", "ev3-ports:outD"],
        "sensor": ["ev3", "ev3-ports:in1", "ev3-ports:in4"],
        "led": ["ev3", 4, 2, "GREEN"],
        "auto": ["ev3", "ev3-ports:outA", "ev3-ports:in1", 4],
    }


def test_fake_sys_in_the_environment_makes_it_the_fake_platform_as_upstream():
    assert shim_in_a_fresh_python("1") == {
        "platform": "fake",
        "motor": ["fake", "outA", "outD"],
        "sensor": ["fake", "in1", "in4"],
        "led": ["fake", 0, 0, ""],
        "auto": ["fake", "outA", "in1", 0],
    }
