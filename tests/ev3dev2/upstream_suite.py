"""
Runs python-ev3dev2 2.1.0's own test suite, unmodified, against our shim, from a checkout of it
named at run time: none of upstream's files is in this repository.

    EV3SIM2D_UPSTREAM_EV3DEV2=CHECKOUT python -m tests.ev3dev2.upstream_suite RESULTS.json
                                                                   (from the repository's root)

CHECKOUT is https://github.com/ev3dev/ev3dev-lang-python at tag ev3dev-stretch/2.1.0, the release
the shim mirrors, with its tests/fake-sys submodule (https://github.com/ddemidov/ev3dev-lang-fake-sys
at the commit 2.1.0 records) checked out:

    git clone --branch ev3dev-stretch/2.1.0 --recurse-submodules \\
        https://github.com/ev3dev/ev3dev-lang-python CHECKOUT

What it uses of the checkout: ``tests/api_tests.py`` (the suite: upstream's CI, .travis.yml, runs
only that file), and of fake-sys the helpers it imports (``populate_arena.py``, ``clean_arena.py``,
``micropython_patch.py``) and the devices it puts in its arena (``devices/board-info``,
``infrared_sensor``, ``large_motor``, ``medium_motor``); not fake-sys's ``touch_sensor``, which no
test asks for.  Each of those files must have the sha256 that upstream_files.sha256 (ours) gives
it, or the checkout is refused with the files that differ named, so that another version of
upstream never passes for 2.1.0.  A checkout made with Windows line endings (Git's core.autocrlf)
is taken when turning them back gives exactly those bytes, which are then what runs.

How it runs, as upstream's ``python3 tests/api_tests.py`` does: those files are copied into a
temporary folder (the tests write their arena of fake devices into fake-sys/ and point
``ev3dev2.Device.DEVICE_ROOT_PATH`` at it; and beside the checkout's tests/ is the real
python-ev3dev2, which must not be imported), the shim is connected to a ``FakeSysfs``
(fake_sysfs.py) that serves the arena's files, and the suite runs in this process, what it prints
kept out of the way.  It is a process of its own because api_tests.py patches the shim's classes
and sys.path for good.  RESULTS.json gets ``{test id: {"outcome": ..., "details": ...}}``, outcome
one of passed, failed, error, skipped; test_upstream_suite.py judges them.

Not run: python-ev3dev2's tests/motor/ (motor_unittest.py, motor_param_unittest.py,
motor_motion_unittest.py, motor_run_direct_unittest.py).  None can run on a fake sysfs, nor against
python-ev3dev2 2.1.0 itself: they import ``ev3dev.ev3``, python-ev3dev 1.x's module, which 2.1.0
does not have; at import they open a real motor (``ev3.Motor('outA')``, and for other boards
'evb-ports:outA', 'ttyAMA0:MA', 'pistorms:BAM1'); and what they check is the tacho-motor
driver on a brick: that it refuses values out of range with an IOError, that ``command = 'reset'``
restores its defaults, that a run to a position stops within a tolerance while they busy-wait on
``state`` in real time, and (run-direct) only that the motor runs.  Fake-sys's attributes are plain
files with no driver behind them, so they would check nothing of the library.

Refreshing, for another upstream release: set the tag and commits below and in
upstream_files.sha256's header, make a checkout of it as above, and from the checkout write the
digests again under that header:

    find tests/api_tests.py tests/fake-sys/clean_arena.py tests/fake-sys/populate_arena.py \\
         tests/fake-sys/micropython_patch.py tests/fake-sys/devices/board-info \\
         tests/fake-sys/devices/infrared_sensor tests/fake-sys/devices/large_motor \\
         tests/fake-sys/devices/medium_motor -type f | LC_ALL=C sort | xargs sha256sum

then update TEST_IDS (test_upstream_suite.py compares it with the checkout's api_tests.py).
"""

import contextlib
import hashlib
import importlib.util
import io
import json
import os
import sys
import tempfile
import unittest
from collections.abc import Mapping

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DIGESTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "upstream_files.sha256")

CHECKOUT_VARIABLE = "EV3SIM2D_UPSTREAM_EV3DEV2"
REQUIRE_VARIABLE = "EV3SIM2D_REQUIRE_UPSTREAM_EV3DEV2"
UPSTREAM_REPOSITORY = "https://github.com/ev3dev/ev3dev-lang-python"
UPSTREAM_TAG = "ev3dev-stretch/2.1.0"
UPSTREAM_COMMIT = "ccbcbdb9cfdf1758f93d01924725f565b7542c9d"
FAKE_SYS_REPOSITORY = "https://github.com/ddemidov/ev3dev-lang-fake-sys"
FAKE_SYS_COMMIT = "64c4af7a029aca4da07f3de7d85e9f7e8d407219"
FAKE_SYS = "tests/fake-sys"
SUITE_FILES = ["tests/api_tests.py"]

# The tests of SUITE_FILES, as unittest names them (module.Class.method): pytest knows them
# without a checkout, and test_upstream_suite.py checks them against the checkout's api_tests.py.
TEST_IDS = [
    "api_tests.TestAPI.test_device",
    "api_tests.TestAPI.test_infrared_sensor",
    "api_tests.TestAPI.test_joystick",
    "api_tests.TestAPI.test_medium_motor",
    "api_tests.TestAPI.test_medium_motor_write",
    "api_tests.TestAPI.test_motor_on_for_degrees",
    "api_tests.TestAPI.test_motor_on_for_rotations",
    "api_tests.TestAPI.test_move_tank_relative_distance",
    "api_tests.TestAPI.test_steering_large_value",
    "api_tests.TestAPI.test_steering_units",
    "api_tests.TestAPI.test_stopwatch",
    "api_tests.TestAPI.test_tank_units",
    "api_tests.TestAPI.test_units",
]


class UpstreamCheckoutError(Exception):
    """The checkout named in EV3SIM2D_UPSTREAM_EV3DEV2 is missing, or is not python-ev3dev2 2.1.0."""


def how_to_run() -> str:
    """How to make a checkout and name it, in one line (for a skip's reason as for an error)."""
    return (
        f"make a checkout with `git clone --branch {UPSTREAM_TAG} --recurse-submodules "
        f"{UPSTREAM_REPOSITORY} CHECKOUT` and name it in {CHECKOUT_VARIABLE}, e.g. "
        f"`{CHECKOUT_VARIABLE}=CHECKOUT python -m pytest tests/ev3dev2/test_upstream_suite.py`"
    )


def not_named() -> str:
    """Why the suite cannot run when EV3SIM2D_UPSTREAM_EV3DEV2 is unset, and what to do."""
    return (
        f"{CHECKOUT_VARIABLE} is not set: python-ev3dev2 2.1.0's own tests run from a checkout of it, "
        f"which this repository does not hold; {how_to_run()}"
    )


def expected_digests(path: str = DIGESTS) -> dict[str, str]:
    """{path in the checkout: sha256} from a ``sha256sum`` file ('#' lines are comments)."""
    digests = {}
    with open(path, encoding="utf-8") as file:
        for number, line in enumerate(file, 1):
            if not line.strip() or line.startswith("#"):
                continue
            digest, separator, name = line.rstrip("\r\n").partition("  ")
            if not separator or len(digest) != 64 or not name:
                raise ValueError(f"{path}, line {number}: not 'SHA256  PATH': {line!r}")
            digests[name] = digest
    return digests


def verified_files(checkout: str, digests: Mapping[str, str] | None = None) -> dict[str, bytes]:
    """{path: bytes} of every file the digests list, read from the checkout and each checked against
    its digest; UpstreamCheckoutError naming every file that is missing or differs."""
    digests = expected_digests() if digests is None else digests
    where = f"{CHECKOUT_VARIABLE}={checkout}"
    if not os.path.isdir(checkout):
        raise UpstreamCheckoutError(f"{where}: there is no such folder; {how_to_run()}")
    files, missing, different = {}, [], []
    for name, digest in sorted(digests.items()):
        try:
            with open(os.path.join(checkout, *name.split("/")), "rb") as file:
                data = file.read()
        except OSError:  # not there, or not a file
            missing.append(name)
            continue
        actual = hashlib.sha256(data).hexdigest()
        if actual != digest and b"\r\n" in data:  # Git's core.autocrlf turns LF into CRLF on checkout
            as_committed = data.replace(b"\r\n", b"\n")
            if hashlib.sha256(as_committed).hexdigest() == digest:
                data, actual = as_committed, digest
        if actual != digest:
            different.append(f"{name} (sha256 {actual}, not {digest})")
            continue
        files[name] = data
    if missing or different:
        raise UpstreamCheckoutError(_refusal(checkout, where, missing, different))
    return files


def _refusal(checkout, where, missing, different) -> str:
    fake_sys = os.path.join(checkout, *FAKE_SYS.split("/"))
    if missing and all(n.startswith(FAKE_SYS + "/") for n in missing) and not _has_files(fake_sys):
        return (
            f"{where}: {FAKE_SYS}/ is empty: its submodule ({FAKE_SYS_REPOSITORY}) is not checked out.\n"
            f"Check it out with: git -C {checkout} submodule update --init {FAKE_SYS}"
        )
    lines = [f"{where} is not python-ev3dev2 2.1.0 as tests/ev3dev2/upstream_files.sha256 pins it:"]
    lines += [f"  missing: {name}" for name in missing[:10]]
    lines += [f"  differs: {name}" for name in different[:10]]
    more = max(len(missing) - 10, 0) + max(len(different) - 10, 0)
    if more:
        lines.append(f"  and {more} more")
    lines.append(
        f"It must be {UPSTREAM_REPOSITORY} at tag {UPSTREAM_TAG} (commit {UPSTREAM_COMMIT}), its "
        f"{FAKE_SYS} at {FAKE_SYS_REPOSITORY} commit {FAKE_SYS_COMMIT}, with no file changed:\n"
        f"    git -C {checkout} checkout {UPSTREAM_TAG} && git -C {checkout} submodule update --init"
    )
    return "\n".join(lines)


def _has_files(folder: str) -> bool:
    return os.path.isdir(folder) and any(not n.startswith(".") for n in os.listdir(folder))


def checkout_from(environ: Mapping[str, str]) -> str | None:
    """The checkout EV3SIM2D_UPSTREAM_EV3DEV2 names, made absolute; None when it is unset or empty."""
    checkout = environ.get(CHECKOUT_VARIABLE, "").strip()
    return os.path.abspath(checkout) if checkout else None


def required(environ: Mapping[str, str]) -> bool:
    """EV3SIM2D_REQUIRE_UPSTREAM_EV3DEV2=1: no checkout is a failure, not a reason to skip (CI)."""
    return environ.get(REQUIRE_VARIABLE, "").strip() not in ("", "0")


def copy_suite(files: Mapping[str, bytes], scratch: str) -> str:
    """Writes the files into scratch by their paths in the checkout; the folder holding the suite."""
    for name, data in files.items():
        path = os.path.join(scratch, *name.split("/"))
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "wb") as file:
            file.write(data)
    return os.path.join(scratch, "tests")


class _Recorder(unittest.TestResult):
    def __init__(self):
        super().__init__()
        self.outcomes = {}

    def addSuccess(self, test):
        self.outcomes[test.id()] = {"outcome": "passed", "details": ""}

    def addFailure(self, test, err):
        super().addFailure(test, err)
        self.outcomes[test.id()] = {"outcome": "failed", "details": self.failures[-1][1]}

    def addError(self, test, err):
        super().addError(test, err)
        self.outcomes[test.id()] = {"outcome": "error", "details": self.errors[-1][1]}

    def addSkip(self, test, reason):
        self.outcomes[test.id()] = {"outcome": "skipped", "details": reason}


def run_suite(folder: str) -> dict:
    """Runs every test of the suite files in ``folder`` (copy_suite's) against the shim."""
    sys.path.insert(0, ROOT)
    import ev3dev2
    from ev3dev2 import _link
    from tests.ev3dev2.fake_sysfs import FakeSysfs

    if os.path.dirname(os.path.abspath(ev3dev2.__file__)) != os.path.join(ROOT, "ev3dev2"):
        raise RuntimeError(f"imported {ev3dev2.__file__}, not this repository's shim")
    _link.connect(FakeSysfs())

    recorder = _Recorder()
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed), contextlib.redirect_stderr(printed):
        for name in SUITE_FILES:
            path = os.path.join(folder, os.path.basename(name))
            module_name = os.path.splitext(os.path.basename(name))[0]
            spec = importlib.util.spec_from_file_location(module_name, path)
            module = importlib.util.module_from_spec(spec)
            sys.modules[module_name] = module
            spec.loader.exec_module(module)
            unittest.defaultTestLoader.loadTestsFromModule(module).run(recorder)
    return recorder.outcomes


def main(argv):
    (results_path,) = argv
    checkout = checkout_from(os.environ)
    try:
        if checkout is None:
            raise UpstreamCheckoutError(not_named())
        files = verified_files(checkout)
    except UpstreamCheckoutError as error:
        print(error, file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory(prefix="ev3dev2-upstream-") as scratch:
        outcomes = run_suite(copy_suite(files, scratch))
    with open(results_path, "w", encoding="utf-8") as file:
        json.dump(outcomes, file, indent=1, sort_keys=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
