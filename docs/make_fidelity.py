"""Write docs/fidelity.md: each motor attribute, command, stop action and state, and each sensor mode, that
the ev3dev drivers document, checked against ev3sim2d's simulated devices (✓ or ✗), and every known
difference with why and what a student sees.

    .venv/bin/python docs/make_fidelity.py           # rewrite docs/fidelity.md
    .venv/bin/python docs/make_fidelity.py --check   # exit 1 if docs/fidelity.md is out of date

What the drivers document comes from docs/fidelity/drivers.json (docs/fidelity/extract_drivers.py
writes it from a checkout of ev3dev/lego-linux-drivers); the checks are docs/fidelity/probes.py; the
differences' reasons are docs/fidelity/differences.yaml.  A failed check makes its row ✗; a behaviour
only the drivers' code states, a mode another driver branch documents differently, or a modelling
choice differences.yaml lists `rows:` for, adds a caveat to a ✓ row.  Each links to its entry.
tests/test_fidelity_doc.py runs the check, and that every difference has an entry and every entry a row.
"""

from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path

import yaml

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))  # (run as a script from anywhere: ev3sim2d is the checkout's)


def _load(name: str, path: Path):
    """docs/fidelity/probes.py as a module of a name of its own (docs/ is not a package)."""
    if name not in sys.modules:
        spec = importlib.util.spec_from_file_location(name, path)
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        spec.loader.exec_module(module)
    return sys.modules[name]


probes = _load("ev3sim2d_docs_fidelity_probes", HERE / "fidelity" / "probes.py")
Row = probes.Row

TARGET = HERE / "fidelity.md"
DRIVERS = HERE / "fidelity" / "drivers.json"
DIFFERENCES = HERE / "fidelity" / "differences.yaml"
SENSOR_HEADER = ["mode", "#", "values", "decimals", "units", "bin_data_format", "documented range"]
ENTRY_FIELDS = (("Why", "why"), ("What a student sees", "student_sees"), ("Status", "status"))


def load_drivers() -> dict:
    return json.loads(DRIVERS.read_text(encoding="utf-8"))


def load_differences() -> dict[str, dict]:
    return yaml.safe_load(DIFFERENCES.read_text(encoding="utf-8")) or {}


class Section:
    """A heading, the lines under it, and a table of rows."""

    def __init__(self, title: str, intro: list[str], header: list[str], rows: list[Row]) -> None:
        self.title, self.intro, self.header, self.rows = title, intro, header, rows


def sections(data: dict, differences: dict[str, dict]) -> list[Section]:
    """The page's tables, every check run, and the modelling caveats of differences.yaml added."""
    states: list[str] = []  # every motor state the probes read: the order of their flags is a row too
    link = lambda file, line=None: source_link(data, file, line)  # noqa: E731
    tacho = data["tacho_motor_class"]
    found = [
        Section(
            "Motors: attributes",
            motor_intro(data),
            ["attribute", "access", "the driver documents", "checked here"],
            probes.motor_attribute_rows(data, states),
        ),
        Section(
            "Motors: commands",
            [
                f"Each `command` ({link(tacho['file'], tacho['commands']['line'])}), on a Large and a Medium motor."
            ],
            ["command", "the driver documents", "checked here"],
            probes.listed_rows(
                data, "command", "command", probes.COMMAND_CLAIMS, probes.probe_command, states
            ),
        ),
        Section(
            "Motors: stop actions",
            [
                f"Each `stop_action` ({link(tacho['file'], tacho['stop_actions']['line'])}), on a Large and a Medium motor."
            ],
            ["stop_action", "the driver documents", "checked here"],
            probes.listed_rows(
                data, "stop_action", "stop_action", probes.STOP_CLAIMS, probes.probe_stop_action, states
            ),
        ),
    ]
    state_rows = probes.state_rows(data, states)
    found.append(
        Section(
            "Motors: states",
            [
                f"Each flag of `state` ({link(tacho['file'], tacho['states']['line'])}), where the driver says it shows."
            ],
            ["flag", "the driver documents", "checked here"],
            state_rows + [probes.state_order_row(data, states)],
        )
    )
    for cls, driver, rows in probes.sensor_sections(data):
        if driver is None:
            intro = [f"`{cls.DRIVER}`: the drivers have no sensor of this name."]
        else:
            where = link(driver["file"], driver["line"])
            intro = [
                f"`{driver['driver']}`, {driver['part_name']} ({driver['part_number']}): {where}. Each mode's",
                "table against ours, the mode read in the arena, and its values swept across the range.",
            ]
        found.append(Section(f"Sensor `{cls.KIND}`", intro, SENSOR_HEADER, rows))
    found.append(
        Section(
            "Sensors: the lego-sensor attributes",
            [f"Each attribute of {link(data['lego_sensor_class']['file'])}, on every kind of sensor above."],
            ["attribute", "access", "the driver documents"],
            probes.sensor_class_rows(data),
        )
    )
    found.append(
        Section(
            "LEGO devices not simulated",
            ["The LEGO devices the drivers' tables name that ev3sim2d has no kind for."],
            ["driver", "part", "defined in"],
            probes.not_simulated_rows(data),
        )
    )
    by_id = {row.id: row for section in found for row in section.rows}
    for key, entry in differences.items():
        for row_id in entry.get("rows", []):
            if row_id in by_id:
                by_id[row_id].caveats.append((key, ""))
    return found


def source_link(data: dict, file: str, line: int | None = None) -> str:
    place = f"{file}:{line}" if line else file
    anchor = f"#L{line}" if line else ""
    return f"[{place}]({data['repository']}/blob/{data['commit']}/{file}{anchor})"


def motor_intro(data: dict) -> list[str]:
    tacho = data["tacho_motor_class"]
    lines = [
        f"Each attribute of {source_link(data, tacho['file'])}, probed on a Large and a Medium motor that",
        "drive no wheel. The motors, as the drivers define them:",
        "",
    ]
    for kind, motor in probes.motor_kinds(data):
        if motor is None:
            continue
        speed, hold = motor["speed_pid"], motor["hold_pid"]
        lines.append(
            f"- `{kind}`: `{motor['driver']}`, {motor['part_name']} ({motor['part_number']}), max_speed "
            f"{motor['max_speed']}, count_per_rot {motor['count_per_rot']}, speed_pid {speed['Kp']}/{speed['Ki']}/"
            f"{speed['Kd']}, hold_pid {hold['Kp']}/{hold['Ki']}/{hold['Kd']} "
            f"({source_link(data, motor['file'], motor['line'])})."
        )
    return lines


def status(row: Row) -> str:
    links = ", ".join(f"[{key}](#{key})" for key in row.keys())
    return ("✓" if row.ok else "✗") + (f" {links}" if links else "")


def table(section: Section) -> list[str]:
    lines = [
        "| " + " | ".join(section.header + ["ev3sim2d"]) + " |",
        "|" + "---|" * (len(section.header) + 1),
    ]
    for row in section.rows:
        cells = [cell.replace("|", "\\|") for cell in row.cells] + [status(row)]
        lines.append("| " + " | ".join(cells) + " |")
    return lines


def render(data: dict, found: list[Section], differences: dict[str, dict]) -> str:
    rows = [row for section in found for row in section.rows]
    simulated = [row for row in rows if not row.id.startswith("not-simulated:")]
    good = [row for row in simulated if row.ok]
    caveated = [row for row in good if row.caveats]
    others = "; ".join(f"{o['ref']} (commit {o['commit'][:12]})" for o in data["other_refs"])
    repository = data["repository"]
    lines = [
        "# How faithful the simulated devices are",
        "",
        "<!-- written by docs/make_fidelity.py; do not edit by hand (the reasons are in docs/fidelity/differences.yaml) -->",
        "",
        "Every motor attribute, command, stop action and state, and every sensor mode, that the ev3dev kernel",
        "drivers document for the devices ev3sim2d simulates, checked on ev3sim2d's own devices the way a",
        "program on the brick reads and writes them: ✓ when it does what the driver documents, ✗ when not.",
        "A link after the mark names a known difference (below); after a ✓, a caveat. Nothing here is",
        "asserted by hand: each row is a check that ran when this page was written.",
        "",
        f"**{len(simulated)} rows: {len(good)} ✓ ({len(caveated)} of them with a caveat), "
        f"{len(simulated) - len(good)} ✗;** and {len(rows) - len(simulated)} LEGO devices the drivers know are not "
        "simulated.",
        "",
        "## Where this comes from",
        "",
        f"- The drivers: [{repository.removeprefix('https://github.com/')}]({repository}), branch {data['ref']},",
        f"  commit [{data['commit'][:12]}]({repository}/tree/{data['commit']}); each table names its file and",
        f"  line. Compared with {others or 'no other branch'} for the modes it documents differently.",
        "- What they document, as data: [fidelity/drivers.json](fidelity/drivers.json), written by",
        "  [fidelity/extract_drivers.py](fidelity/extract_drivers.py), which reads the `*_defs.c` tables",
        "  as the drivers' own `Documentation/json/sensor_defs_to_json.py` does.",
        "- The checks: [fidelity/probes.py](fidelity/probes.py); this page: [make_fidelity.py](make_fidelity.py);",
        "  why each difference is there: [fidelity/differences.yaml](fidelity/differences.yaml).",
        "- `tests/test_fidelity_doc.py` fails when this page is out of date, when a difference has no entry",
        "  or an entry no row, and when a sensor's mode table differs from its driver's on a ✓ row.",
        "",
        "To write it again after the devices change:",
        "",
        "    .venv/bin/python docs/make_fidelity.py",
        "",
        "and after the drivers change (from a clone of lego-linux-drivers; nothing else needs the network):",
        "",
        "    .venv/bin/python docs/fidelity/extract_drivers.py ../lego-linux-drivers --also origin/ev3dev-stretch",
        "",
    ]
    for section in found:
        lines += [f"## {section.title}", "", *section.intro, "", *table(section), ""]
    lines += known_differences(rows, differences)
    return "\n".join(lines).rstrip() + "\n"


def known_differences(rows: list[Row], differences: dict[str, dict]) -> list[str]:
    lines = [
        "## Known differences",
        "",
        "Each entry names its rows, says why ev3sim2d differs and what a student sees: first what the checks",
        "found (✗, then caveats: what they found is listed), then the modelling choices no check can see.",
        "",
    ]
    used: dict[str, list[Row]] = {}
    for row in rows:
        for key in row.keys():
            used.setdefault(key, []).append(row)

    def order(key: str) -> tuple[int, str]:
        failing = any(k == key for row in used[key] for k, _ in row.failures)
        return (0 if failing else 1 if not differences.get(key, {}).get("rows") else 2, key)

    for key in sorted(used, key=order):
        entry = differences.get(key)
        title = entry["title"] if entry else "No entry in docs/fidelity/differences.yaml yet."
        ids = [row.id for row in used[key]]
        lines += [f"### {key}", "", f"**{title}**", "", "Rows: " + ", ".join(f"`{i}`" for i in ids) + ".", ""]
        found = [what for row in used[key] for k, what in row.failures + row.caveats if k == key and what]
        found = list(dict.fromkeys(found))
        if found:
            shown = found[:8] + ([f"… and {len(found) - 8} more"] if len(found) > 8 else [])
            lines += ["What the checks found:", "", *[f"- {what}" for what in shown], ""]
        for label, name in ENTRY_FIELDS:
            if entry and entry.get(name):
                lines += [f"{label}: {' '.join(str(entry[name]).split())}", ""]
    return lines


def generate() -> tuple[str, list[Row], dict[str, dict]]:
    """The page, its rows, and the entries of differences.yaml."""
    data, differences = load_drivers(), load_differences()
    found = sections(data, differences)
    rows = [row for section in found for row in section.rows]
    return render(data, found, differences), rows, differences


def main(argv: list[str]) -> int:
    text, _rows, _differences = generate()
    if "--check" in argv:
        if not TARGET.is_file() or TARGET.read_text(encoding="utf-8") != text:
            print(f"{TARGET} is out of date: run .venv/bin/python docs/make_fidelity.py", file=sys.stderr)
            return 1
        return 0
    TARGET.write_text(text, encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
