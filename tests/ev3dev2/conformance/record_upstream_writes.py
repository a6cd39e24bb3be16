"""
Records what the REAL python-ev3dev2 2.1.0 does in every scenario of scenarios.py, into
upstream_writes.json, which is committed: tests/ev3dev2/test_behaviour_conformance.py runs the
same scenarios through our shim and compares, without needing the real library.

    python tests/ev3dev2/conformance/record_upstream_writes.py [SOURCE]

SOURCE is the unpacked python-ev3dev2 2.1.0 sdist (the folder that holds ``ev3dev2/``) or the
sdist itself; without it, pip downloads the sdist into a temporary folder.

The library runs in a child Python started with ``-I`` from SOURCE, so this repository's shim
cannot be imported by mistake.  It finds its devices in a temporary sysfs-like folder (its
``DEVICE_ROOT_PATH``), and the attribute files it opens are objects that read and write a
FakeBrick, which logs every access; ``time.time``/``time.sleep``, ``select.poll`` and the
StopWatch's clock follow the FakeBrick's virtual clock, as they would inside a simulated run,
and the library believes it runs on an EV3.

Per scenario the fixture holds the ordered attribute writes ``[device, attribute, value]``,
the exception the script let out (``None`` if it ended normally), what the script recorded,
the whole access log (reads, writes and polls in order), and a digest of the scenario, so a
scenario changed without recording again fails its test.
"""

import _thread
import hashlib
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
FIXTURE = os.path.join(HERE, "upstream_writes.json")

PRELUDE = """
def attempt(action):
    try:
        record(action())
    except Exception as error:
        record(type(error).__name__ + ': ' + str(error))
"""


class _Enough(Exception):
    """Ends a thread that run_threads_briefly runs."""


def run_threads_briefly(sleeps):
    """From now on, a thread the library starts runs at once, here, until it has slept ``sleeps`` times."""

    def start_new_thread(function, args, kwargs=None):
        real_sleep, count = time.sleep, [0]

        def sleep(seconds):
            real_sleep(seconds)
            count[0] += 1
            if count[0] >= sleeps:
                raise _Enough()

        time.sleep = sleep
        try:
            function(*args, **(kwargs or {}))
        except _Enough:
            pass
        finally:
            time.sleep = real_sleep
        return 1

    _thread.start_new_thread = start_new_thread


def describe_exception(error):
    """'ev3dev2.motor.SpeedInvalid: message', with ' (from OSError)' when raised from another."""
    kind = type(error)
    name = kind.__name__ if kind.__module__ == "builtins" else f"{kind.__module__}.{kind.__name__}"
    cause = f" (from {type(error.__cause__).__name__})" if error.__cause__ is not None else ""
    return f"{name}: {error}{cause}"


def run_script(script):
    """Runs a scenario's script; returns (what it recorded, the exception it let out as text or None)."""
    records = []
    start_new_thread = _thread.start_new_thread
    names = {"record": records.append, "run_threads_briefly": run_threads_briefly, "__name__": "scenario"}
    try:
        exec(PRELUDE + script, names)
    except Exception as error:
        return records, describe_exception(error)
    finally:
        _thread.start_new_thread = start_new_thread
    return records, None


def digest(devices, script):
    """A short fingerprint of a scenario."""
    text = json.dumps([devices, script], sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def outcome(log, records, exception):
    """A scenario's entry in the fixture (and what the shim's run is compared with)."""
    return {
        "writes": [entry[1:] for entry in log if entry[0] == "write"],
        "exception": exception,
        "records": json.loads(json.dumps(records)),
        "log": log,
    }


# -- the real library's side: attribute files and select.poll on the FakeBrick ----------


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


def child_main(upstream_dir):
    """In the isolated child: run the jobs on stdin through the real library, print the outcomes."""
    sys.path[:0] = [upstream_dir, os.path.dirname(HERE)]

    from fake_brick import FakeBrick

    state = {"brick": FakeBrick()}
    time.time = lambda: state["brick"].time()
    time.sleep = lambda seconds: state["brick"].sleep(seconds)

    import ev3dev2

    ev3dev2.get_current_platform = lambda: "ev3"  # ports and LEDs of an EV3, as the shim has them
    import ev3dev2.motor
    import ev3dev2.stopwatch

    expected = os.path.join(upstream_dir, "ev3dev2")
    assert os.path.dirname(os.path.abspath(ev3dev2.__file__)) == expected, ev3dev2.__file__
    ev3dev2.Device._attribute_file_open = lambda device, name: FakeAttribute(
        state["brick"], device._path, name
    )
    ev3dev2.motor.select = FakeSelect
    ev3dev2.stopwatch.get_ticks_ms = lambda: int(time.time() * 1000)

    jobs = json.load(sys.stdin)
    results = {}
    for name, job in jobs.items():
        brick = state["brick"] = FakeBrick(job["devices"])
        with tempfile.TemporaryDirectory() as root:
            build_sysfs(root, job["devices"])
            ev3dev2.Device.DEVICE_ROOT_PATH = root
            records, exception = run_script(job["script"])
        results[name] = outcome(brick.log, records, exception)
    json.dump(results, sys.stdout)


# -- recording ----------------------------------------------------------------------------


def record(source):
    """Run every scenario through the real library in ``source``; write the fixture."""
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(HERE))))
    from tests.ev3dev2.conformance.scenarios import SCENARIOS

    jobs = {name: {"devices": devices, "script": script} for name, (devices, script) in SCENARIOS.items()}
    result = subprocess.run(
        [sys.executable, "-I", os.path.abspath(__file__), "--child", os.path.abspath(source)],
        input=json.dumps(jobs),
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )
    if result.returncode != 0:
        sys.exit(result.stderr)
    results = json.loads(result.stdout)
    fixture = {
        name: {"digest": digest(job["devices"], job["script"]), **results[name]} for name, job in jobs.items()
    }
    with open(FIXTURE, "w", encoding="utf-8") as file:
        file.write(format_fixture(fixture))
    return fixture


def format_fixture(fixture):
    """JSON with one write, record or log entry a line, so a change shows as a small diff."""
    lines = ["{"]
    for index, name in enumerate(sorted(fixture)):
        entry = fixture[name]
        lines.append(f"  {json.dumps(name)}: {{")
        fields = []
        for key in ("digest", "exception", "writes", "records", "log"):
            value = entry[key]
            if isinstance(value, list) and value:
                items = ",\n".join("      " + json.dumps(item) for item in value)
                fields.append(f"    {json.dumps(key)}: [\n{items}\n    ]")
            else:
                fields.append(f"    {json.dumps(key)}: {json.dumps(value)}")
        lines.append(",\n".join(fields))
        lines.append("  }" + ("," if index < len(fixture) - 1 else ""))
    lines.append("}")
    return "\n".join(lines) + "\n"


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["--child"]:
        child_main(argv[1])
        return 0
    source = argv[0] if argv else None
    with tempfile.TemporaryDirectory() as folder:
        sys.path.insert(0, HERE)
        from snapshot_api import download_source, unpack

        if source is None:
            source = download_source(folder)
        elif os.path.isfile(source):
            source = unpack(source, folder)
        fixture = record(source)
    print(f"wrote {os.path.relpath(FIXTURE)}: {len(fixture)} scenarios")
    return 0


if __name__ == "__main__":
    sys.exit(main())
