"""Outside a simulated run every module of the Pybricks shim imports cleanly, each on its own in a fresh
interpreter (an editor, a documentation tool or a test may import any of them first), and using a device
says how to run the program."""

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
MODULES = sorted(
    ".".join(path.relative_to(ROOT).with_suffix("").parts).removesuffix(".__init__")
    for path in (ROOT / "pybricks").rglob("*.py")
    if "_micropython" not in path.parts and path.name != "ev3brick.py"
)


@pytest.mark.parametrize("module", MODULES)
def test_each_module_imports_alone_in_a_fresh_interpreter(module):
    done = subprocess.run(
        [sys.executable, "-c", f"import {module}"], capture_output=True, text=True, cwd=ROOT, timeout=60
    )
    assert done.returncode == 0, done.stderr


def test_using_a_device_outside_a_run_says_how_to_run_the_program():
    """pybricks.ev3brick makes an EV3Brick as it is imported, as on the firmware: outside a run that is the
    first use of a device."""
    code = (
        "from pybricks.ev3devices import Motor\nfrom pybricks.parameters import Port\n"
        "try:\n    Motor(Port.B)\nexcept RuntimeError as err:\n    print(err)\n"
        "try:\n    import pybricks.ev3brick\nexcept RuntimeError as err:\n    print(err)\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=60)
    lines = done.stdout.splitlines()
    assert len(lines) == 2 and all("must run inside the simulator: ev3sim2d run" in line for line in lines)
