"""docs/fidelity.md says how faithful the simulated devices are, and stays true.

The page is written by docs/make_fidelity.py from docs/fidelity/drivers.json (what lego-linux-drivers
documents, extracted by docs/fidelity/extract_drivers.py) and docs/fidelity/differences.yaml (why each
difference is there).  These tests: the page is what the generator writes now; every difference a row
links to has an entry, and every entry a row that still needs it; each sensor mode the page marks ✓ has
the driver's table (an independent comparison here, of every field, for every mode); and the checks
behind the page catch a wrong bin_data_format, num_values, decimals or units in any mode (the touch
sensor's TOUCH was s8 where the driver says LEGO_SENSOR_DATA_S32 until a fix; nothing had noticed).
"""

from __future__ import annotations

import importlib.util
import json
import re
import sys
from pathlib import Path

import pytest
import yaml

from ev3sim2d.devices.registry import BUILT_IN
from ev3sim2d.devices.sensor import Mode

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
PAGE = DOCS / "fidelity.md"
DRIVERS = json.loads((DOCS / "fidelity" / "drivers.json").read_text(encoding="utf-8"))
DIFFERENCES = yaml.safe_load((DOCS / "fidelity" / "differences.yaml").read_text(encoding="utf-8"))
DRIVER_MODES = [
    (cls, sensor, mode) for cls in BUILT_IN for sensor in DRIVERS["sensors"] if sensor["driver"] == cls.DRIVER
    for mode in sensor["modes"]
]  # fmt: skip


def load(name: str, path: Path):
    if name not in sys.modules:
        spec = importlib.util.spec_from_file_location(name, path)
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        spec.loader.exec_module(module)
    return sys.modules[name]


@pytest.fixture(scope="module")
def generated():
    """(the page as the generator writes it now, its rows)."""
    make = load("ev3sim2d_docs_make_fidelity", DOCS / "make_fidelity.py")
    text, rows, _differences = make.generate()
    return text, rows


@pytest.fixture(scope="module")
def probes():
    load("ev3sim2d_docs_make_fidelity", DOCS / "make_fidelity.py")
    return sys.modules["ev3sim2d_docs_fidelity_probes"]


def page_status(driver: str, mode: str) -> str:
    """✓ or ✗, as docs/fidelity.md shows it for a sensor mode of a driver."""
    text = PAGE.read_text(encoding="utf-8")
    section = text.split(f"`{driver}`, ", 1)[1].split("\n## ", 1)[0]
    line = next(line for line in section.splitlines() if line.startswith(f"| `{mode}` |"))
    return line.rsplit("|", 2)[-2].strip()[0]


def test_the_page_is_what_the_generator_writes_now(generated):
    text, _ = generated
    assert PAGE.read_text(encoding="utf-8") == text, (
        "docs/fidelity.md is out of date: run .venv/bin/python docs/make_fidelity.py"
    )


def test_every_difference_a_row_links_to_has_an_entry_that_says_why(generated):
    _, rows = generated
    linked = {key for row in rows for key in row.keys()}
    assert linked - set(DIFFERENCES) == set(), "add these to docs/fidelity/differences.yaml"
    for key, entry in DIFFERENCES.items():
        assert re.fullmatch(r"[a-z0-9]+(-[a-z0-9]+)*", key), key
        for field in ("title", "why", "student_sees"):
            assert str(entry.get(field, "")).strip(), f"{key}: no {field}"


def test_every_entry_is_still_needed_by_a_row(generated):
    """No stale entries: a difference fixed makes its check pass, and its entry must go."""
    _, rows = generated
    ids = {row.id for row in rows}
    linked = {key for row in rows for key in row.keys()}
    assert set(DIFFERENCES) - linked == set(), "these entries name no row that still fails or has the caveat"
    for key, entry in DIFFERENCES.items():
        for row_id in entry.get("rows", []):
            assert row_id in ids, f"{key}: no row {row_id}"


def test_every_x_row_has_a_reason(generated):
    _, rows = generated
    for row in rows:
        if not row.ok:
            assert row.failures and all(DIFFERENCES.get(key) for key, _ in row.failures), row.id


def test_the_page_counts_its_rows(generated):
    text, rows = generated
    simulated = [row for row in rows if not row.id.startswith("not-simulated:")]
    good = sum(row.ok for row in simulated)
    assert f"**{len(simulated)} rows: {good} ✓" in text
    assert f"{len(simulated) - good} ✗;**" in text
    assert text.count("| ✓") + text.count("| ✗") == len(rows)


@pytest.mark.parametrize(
    "cls, sensor, mode", DRIVER_MODES, ids=[f"{s['driver']}-{m['name']}" for _, s, m in DRIVER_MODES]
)
def test_a_mode_marked_ok_has_the_drivers_table(cls, sensor, mode):
    """Compared here, field by field, without the generator: where they differ, the page says ✗."""
    ours: Mode | None = cls.MODES.get(mode["name"])
    ranges = [value["range"] for value in mode["values"]]
    documented = (
        None if not ranges or None in ranges else (min(r[0] for r in ranges), max(r[1] for r in ranges))
    )
    scaled = (mode["raw_min"], mode["raw_max"]) != (mode["si_min"], mode["si_max"])
    same = ours is not None and (
        list(cls.MODES).index(mode["name"]) == mode["index"]
        and ours.num_values == mode["num_values"]
        and ours.decimals == mode["decimals"]
        and ours.units == mode["units"]
        and ours.data_format == mode["bin_data_format"]
        and (documented is None or (ours.low, ours.high) == documented)
        and (ours.raw is not None if mode["scale"] else ours.raw == (
            (mode["raw_min"], mode["raw_max"], mode["si_min"], mode["si_max"]) if scaled else None))
    )  # fmt: skip
    if not same:
        assert page_status(sensor["driver"], mode["name"]) == "✗", (
            f"{cls.__name__}.MODES[{mode['name']!r}] is {ours} but {sensor['file']}:{mode['line']} documents "
            f"num_values {mode['num_values']}, decimals {mode['decimals']}, units {mode['units']!r}, "
            f"bin_data_format {mode['bin_data_format']!r}, range {documented}; docs/fidelity.md marks it ✓"
        )


def test_every_mode_of_every_simulated_sensor_is_on_the_page():
    for cls in BUILT_IN:
        sensor = next(s for s in DRIVERS["sensors"] if s["driver"] == cls.DRIVER)
        assert [m["name"] for m in sensor["modes"]] == list(cls.MODES), cls.__name__
        for mode in sensor["modes"]:
            assert page_status(sensor["driver"], mode["name"]) in "✓✗"


WRONG = {
    "bin_data_format": lambda mode: {"data_format": "s16" if mode.data_format != "s16" else "s8"},
    "num_values": lambda mode: {"num_values": mode.num_values + 1},
    "decimals": lambda mode: {"decimals": mode.decimals + 1},
    "units": lambda mode: {"units": mode.units + "x"},
}


@pytest.mark.parametrize("what", WRONG)
def test_the_checks_catch_a_wrong_field_in_any_mode(probes, monkeypatch, what):
    """Each mode of each sensor, given a wrong value of one field, fails its row (and is ✓ as it is)."""
    missed = []
    for cls in BUILT_IN:
        sensor = next(s for s in DRIVERS["sensors"] if s["driver"] == cls.DRIVER)
        for mode in sensor["modes"]:
            ours = cls.MODES[mode["name"]]
            wrong = Mode(**{**ours.__dict__, **WRONG[what](ours)})
            monkeypatch.setitem(cls.MODES, mode["name"], wrong)
            bench = probes.Bench(probes.SCENE_X.get(cls.KIND, probes.OPEN_X), probes.sensor_entry(cls))
            row = probes.mode_row(cls, sensor, mode, DRIVERS, bench)
            if not any(what in failure for _, failure in row.failures):
                missed.append(f"{sensor['driver']} {mode['name']}")
            monkeypatch.setitem(cls.MODES, mode["name"], ours)
    assert not missed, f"a wrong {what} passed in: {missed}"


def test_the_extractor_reads_a_defs_table_as_the_drivers_document_it(tmp_path):
    """extract_drivers.py on a small table written the way sensors/ev3_analog_sensor_defs.c is."""
    extract = load("ev3sim2d_docs_fidelity_extract", DOCS / "fidelity" / "extract_drivers.py")
    defs = """
const struct ev3_analog_sensor_info ev3_analog_sensor_defs[] = {
    [LEGO_EV3_TOUCH_SENSOR] = {
        /**
         * @vendor_name: LEGO
         * @vendor_part_number: 45507
         * @vendor_part_name: EV3 Touch Sensor
         */
        .name = LEGO_EV3_TOUCH_SENSOR_NAME,
        .num_modes = 1,
        .mode_info = {
            [0] = {
                /**
                 * .. [#touch-value0] Values:
                 *
                 *    0 released, 1 pressed
                 *
                 * @description: Button state
                 * @value0: State (0 or 1)
                 * @value0_footnote: [#touch-value0]_
                 */
                .name = "TOUCH",
                .data_sets = 1,
                .data_type = LEGO_SENSOR_DATA_S32,
                .scale = lego_ev3_touch_sensor_scale,
            },
        },
    },
};
""".split("\n")
    constants = {"LEGO_EV3_TOUCH_SENSOR_NAME": "lego-ev3-touch"}
    (entry,) = extract._defs_tables(defs, constants)
    assert entry["fields"]["name"] == "lego-ev3-touch" and entry["doc"]["vendor_name"] == "LEGO"
    (mode,) = entry["fields"]["mode_info"]["entries"]
    assert mode["fields"] == {
        "name": "TOUCH",
        "data_sets": "1",
        "data_type": "LEGO_SENSOR_DATA_S32",
        "scale": "lego_ev3_touch_sensor_scale",
    }
    assert extract._values(mode["doc"]) == [
        {"text": "State (0 or 1)", "range": [0, 1], "footnotes": ["touch-value0"]}
    ]
    assert mode["footnotes"] == {"touch-value0": "Values:\n\n0 released, 1 pressed"}


def test_the_drivers_data_names_its_source():
    assert DRIVERS["repository"] == "https://github.com/ev3dev/lego-linux-drivers"
    assert re.fullmatch(r"[0-9a-f]{40}", DRIVERS["commit"])
    touch = next(s for s in DRIVERS["sensors"] if s["driver"] == "lego-ev3-touch")
    assert (touch["file"], touch["modes"][0]["data_type"]) == (
        "sensors/ev3_analog_sensor_defs.c",
        "LEGO_SENSOR_DATA_S32",
    )
    assert DRIVERS["bin_data_formats"]["LEGO_SENSOR_DATA_S32"] == "s32"
