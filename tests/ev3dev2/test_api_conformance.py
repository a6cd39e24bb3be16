"""
The shim's public API is python-ev3dev2 2.1.0's: every module, class, function, method
signature (parameter names, kinds and defaults), property (and whether it has a setter),
constant and value in conformance/api_2.1.0.json (read from the real source by
conformance/snapshot_api.py) is in the shim the same, and the shim adds nothing public;
the differences left are in conformance/api_allowlist.yaml, each with its reason.

The share matched shows in pytest's summary, and from
``python tests/ev3dev2/conformance/snapshot_api.py --compare``.
"""

import json
import os
import textwrap

import pytest

from .conformance import snapshot_api
from .conftest import API_SHARE

UPSTREAM = os.environ.get("EV3DEV2_UPSTREAM", "/tmp/ev3src/python-ev3dev2-2.1.0")


@pytest.fixture(scope="module")
def report():
    return snapshot_api.Report()


def test_shim_api_matches_python_ev3dev2(report, request):
    request.config.stash[API_SHARE] = report.summary()
    print(report.summary())
    assert not report.unexpected, report.details()


def test_every_allowed_difference_is_still_a_difference_and_says_why(report):
    assert not report.stale, report.details()
    assert all(reason.strip() for reason in report.allowlist.values())


@pytest.mark.skipif(
    not os.path.isfile(os.path.join(UPSTREAM, "ev3dev2", "motor.py")),
    reason="the python-ev3dev2 2.1.0 source is not here (set EV3DEV2_UPSTREAM to its folder)",
)
def test_the_snapshot_is_what_the_script_makes_of_the_real_source(tmp_path):
    written = snapshot_api.write_snapshot(UPSTREAM, str(tmp_path / "api.json"))
    with open(snapshot_api.SNAPSHOT, encoding="utf-8") as file:
        assert json.load(file) == json.loads(json.dumps(written))


# -- the extraction and the comparison, on small packages ---------------------------------


def describe(tmp_path, files):
    for path, text in files.items():
        target = tmp_path / "ev3dev2" / path
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(textwrap.dedent(text))
    return snapshot_api.describe_package(str(tmp_path))


def differences(tmp_path, upstream, shim):
    _, found, _ = snapshot_api.compare(describe(tmp_path / "up", upstream), describe(tmp_path / "shim", shim))
    return {key: (theirs, ours) for key, theirs, ours in found}


def test_a_changed_default_or_a_missing_setter_is_a_difference(tmp_path):
    upstream = {
        "__init__.py": """
            class Motor:
                def on(self, speed, brake=True, block=False): pass
                @property
                def speed_sp(self): pass
                @speed_sp.setter
                def speed_sp(self, value): pass
        """
    }
    shim = {
        "__init__.py": """
            class Motor:
                def on(self, speed, brake=True, block=True): pass
                speed_sp = _attribute("speed_sp", "doc", writable=False)
        """
    }
    assert differences(tmp_path, upstream, shim) == {
        "ev3dev2:Motor.on": (
            "method (self, speed, brake=True, block=False)",
            "method (self, speed, brake=True, block=True)",
        ),
        "ev3dev2:Motor.speed_sp": ("property (read-write)", "property (read-only)"),
    }


def test_a_method_inherited_from_a_private_base_is_the_class_own_and_extras_count(tmp_path):
    upstream = {
        "__init__.py": """
            class SpeedValue: pass
            class SpeedRPM(SpeedValue):
                def to_native_units(self, motor): pass
        """
    }
    shim = {
        "__init__.py": """
            class SpeedValue: pass
            class _Scaled(SpeedValue):
                LIMIT = 'max_rpm'
                def to_native_units(self, motor): pass
            class SpeedRPM(_Scaled): pass
        """
    }
    assert differences(tmp_path, upstream, shim) == {"ev3dev2:SpeedRPM.LIMIT": (None, "constant = 'max_rpm'")}


def test_module_ifs_are_read_as_on_an_ev3_and_imports_name_what_they_import(tmp_path):
    upstream = {
        "__init__.py": "def get_current_platform(): pass\n",
        "_platform/ev3.py": "OUTPUT_A = 'ev3-ports:outA'\n",
        "_platform/evb.py": "OUTPUT_A = 'outA'\n",
        "motor.py": """
            from ev3dev2 import get_current_platform
            platform = get_current_platform()
            if platform == 'ev3':
                from ev3dev2._platform.ev3 import OUTPUT_A
            elif platform == 'evb':
                from ev3dev2._platform.evb import OUTPUT_A
        """,
    }
    description = describe(tmp_path, upstream)["modules"]["ev3dev2.motor"]["names"]
    assert description["OUTPUT_A"] == {"kind": "import", "target": "ev3dev2._platform.ev3.OUTPUT_A"}
    assert description["platform"] == {"kind": "constant", "value": "'ev3'"}
