"""
Runs scripts against the REAL python-ev3dev2 and prints what it read and wrote.

Usage: python -I upstream_runner.py UPSTREAM_SOURCE_DIR < jobs.json

``jobs.json`` maps scenario names to {'devices': [specs], 'script': code}.
Each script runs with a fresh FakeBrick behind the real library: the library
finds devices in a temporary sysfs-like folder (its ``DEVICE_ROOT_PATH``), and
its attribute files are replaced by objects that read and write the FakeBrick,
which logs every access.  ``time.time``/``time.sleep``, ``select.poll`` and the
StopWatch's clock follow the FakeBrick's virtual clock, as they would inside a
simulated run, and the library believes it runs on an EV3.  Prints {name: {'log': [...], 'records': [...]}} as JSON.

Run isolated (-I) so that this repository's own ev3dev2 shim is not importable.
"""

import json
import os
import sys
import tempfile
import time

PRELUDE = """
def attempt(action):
    try:
        record(action())
    except Exception as error:
        record(type(error).__name__ + ': ' + str(error))
"""


def run_script(script, records):
    """Run a scenario's script; an exception it lets out ends it, and is recorded."""
    try:
        exec(PRELUDE + script, {"record": records.append, "__name__": "scenario"})
    except Exception as error:
        records.append(["uncaught", type(error).__name__, str(error)])


class FakeAttribute:
    """An open sysfs attribute file of the real library, read and written through the FakeBrick."""

    def __init__(self, brick, device_path, name):
        self.brick = brick
        self.class_name = os.path.basename(os.path.dirname(device_path))
        self.device_name = os.path.basename(device_path)
        self.name = name

    def seek(self, position):
        pass

    def flush(self):
        pass

    def read(self, size=-1):
        data = self.brick.read(self.class_name, self.device_name, self.name).encode("latin-1")
        return data if size is None or size < 0 else data[:size]

    def write(self, data):
        self.brick.write(self.class_name, self.device_name, self.name, bytes(data).decode("latin-1"))
        return len(data)


class FakePoll:
    """select.poll() on a motor's state file: waits on the FakeBrick's virtual clock."""

    def __init__(self):
        self.files = []

    def register(self, file, mask=None):
        self.files.append(file)

    def poll(self, timeout_ms):
        for file in self.files:
            file.brick.poll(file.class_name, file.device_name, file.name, timeout_ms)
        return []


class FakeSelect:
    POLLPRI = 2

    @staticmethod
    def poll():
        return FakePoll()


def build_sysfs(root, devices):
    """Folders and attribute files, so the real library can find and match the devices."""
    for spec in devices:
        folder = os.path.join(root, spec["class"], spec["name"])
        for attribute, value in spec["attrs"].items():
            path = os.path.join(folder, attribute)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            value = value[0] if isinstance(value, list) else value
            with open(path, "w", encoding="latin-1") as file:
                file.write(value + "\n")
            os.chmod(path, 0o664)


def main():
    upstream_dir = os.path.abspath(sys.argv[1])
    here = os.path.dirname(os.path.abspath(__file__))
    sys.path[:0] = [upstream_dir, here]

    from fake_brick import FakeBrick

    state = {"brick": FakeBrick()}
    time.time = lambda: state["brick"].time()
    time.sleep = lambda seconds: state["brick"].sleep(seconds)

    import ev3dev2

    ev3dev2.get_current_platform = lambda: "ev3"  # ports and LEDs of an EV3, as the shim has them
    import ev3dev2.motor
    import ev3dev2.stopwatch

    assert os.path.dirname(os.path.abspath(ev3dev2.__file__)) == os.path.join(upstream_dir, "ev3dev2"), (
        ev3dev2.__file__
    )
    ev3dev2.Device._attribute_file_open = lambda device, name: FakeAttribute(
        state["brick"], device._path, name
    )
    ev3dev2.motor.select = FakeSelect
    ev3dev2.stopwatch.get_ticks_ms = lambda: int(time.time() * 1000)

    jobs = json.load(sys.stdin)
    results = {}
    for name, job in jobs.items():
        brick = state["brick"] = FakeBrick(job["devices"])
        records = []
        with tempfile.TemporaryDirectory() as root:
            build_sysfs(root, job["devices"])
            ev3dev2.Device.DEVICE_ROOT_PATH = root
            run_script(job["script"], records)
        results[name] = {"log": brick.log, "records": records}

    json.dump(results, sys.stdout)


if __name__ == "__main__":
    main()
