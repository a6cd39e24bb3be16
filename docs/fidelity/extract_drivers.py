"""Write docs/fidelity/drivers.json: what the ev3dev kernel drivers document about the LEGO devices.

    .venv/bin/python docs/fidelity/extract_drivers.py CHECKOUT [--ref REF] [--also REF ...]

CHECKOUT is a git clone of github.com/ev3dev/lego-linux-drivers (a work tree or a bare mirror); its
files are read at REF (default HEAD) with `git show`, so the commit each fact comes from is known.
`--also ev3dev-stretch` records, for each sensor mode, what another branch documents differently
(ev3dev-stretch is the release most EV3 bricks run).  Run it by hand when the drivers change, then
`.venv/bin/python docs/make_fidelity.py` (nothing here needs the network; CI reads the JSON).

What it reads, the way the drivers' own Documentation/json/sensor_defs_to_json.py and
motor_defs_to_json.py read it (the `*_defs[]` tables and their `/** @key: value */` comments):
- sensors/*_sensor_defs.c: every LEGO sensor, each mode's name, data_sets, num_values, data_type (and
  the `bin_data_format` text sensors/lego_sensor_class.c gives it), units, decimals, raw/pct/si
  min and max, scale function, the @valueN descriptions with their documented ranges, footnotes;
- sensors/lego_sensor_class.c and motors/tacho_motor_class.c: the sysfs attribute tables of their
  `DOC: userspace` comments (name, access, description, and the listed values of command, polarity,
  state, stop_action), and the names in the drivers' own order;
- motors/ev3_motor_defs.c: each LEGO motor's max_speed, count_per_rot, PID constants;
- a few facts that only the drivers' code states (`FACTS`), each with its file, line and source text.
"""

from __future__ import annotations

import argparse
import json
import re
import subprocess
import sys
from pathlib import Path

REPOSITORY = "https://github.com/ev3dev/lego-linux-drivers"
OUT = Path(__file__).resolve().parent / "drivers.json"

SENSOR_DEFS = [  # (defs file, the header naming its drivers)
    ("sensors/ev3_analog_sensor_defs.c", "sensors/ev3_analog_sensor.h"),
    ("sensors/ev3_uart_sensor_defs.c", "sensors/ev3_uart_sensor.h"),
    ("sensors/nxt_analog_sensor_defs.c", "sensors/nxt_analog_sensor.h"),
    ("sensors/nxt_i2c_sensor_defs.c", "sensors/nxt_i2c_sensor.h"),
]
MOTOR_DEFS = ("motors/ev3_motor_defs.c", "motors/ev3_motor.h")
SENSOR_CLASS = "sensors/lego_sensor_class.c"
TACHO_CLASS = "motors/tacho_motor_class.c"
EV3_MOTOR = "ev3/legoev3_motor.c"
DC_MOTOR_CLASS = "motors/dc_motor_class.c"

# Facts from the drivers' code that the fidelity checks rely on: name -> (file, a regex one line
# matches, what the line means).  The first matching line is recorded with its number and text.
FACTS = {
    "ramp_sp_max": (
        TACHO_CLASS,
        r"if \(ms < 0 \|\| ms > (\d+)\)",
        "ramp_up_sp and ramp_down_sp refuse values below 0 or above this (EINVAL)",
    ),
    "stalled_ms": (
        EV3_MOTOR,
        r"#define TACHO_MOTOR_STALLED_MS\s+(\d+)",
        "a running motor whose speed has been 0 this long reports stalled (update_stall)",
    ),
    "position_busy_test": (
        EV3_MOTOR,
        r"if \(legoev3_motor_get_state\(ev3_tm\) & (TM_STATE_RUNNING)\)",
        "legoev3_motor_set_position returns EBUSY when this is true; get_state sets BIT(TM_STATE_RUNNING) "
        "and TM_STATE_RUNNING is 0 (state_running_index), so it never is: position is written at any time",
    ),
    "state_running_index": (
        "include/tacho_motor_class.h",
        r"^\s*(TM_STATE_RUNNING),",
        "TM_STATE_RUNNING is the first value of enum tacho_motor_state, 0: a flag's index, not its bit",
    ),
    "position_write_sets_target": (
        EV3_MOTOR,
        r"ev3_tm->position_sp = (position);",
        "legoev3_motor_set_position makes the written position a run to a position's target, so "
        "update_position ends that run where the shaft is",
    ),
    "rel_pos_after_rel_pos": (
        TACHO_CLASS,
        r"if \(tm->params\.command == (TM_COMMAND_RUN_TO_REL_POS)\)",
        "tm_send_command: when the last command written (command_store sets tm->params.command) was "
        "run-to-rel-pos, whether it still runs or not, the next one counts from its target",
    ),
    "rel_pos_from_setpoint": (
        TACHO_CLASS,
        r"new_params\.position_sp = tm->active_params\.position_sp \+",
        "run-to-rel-pos right after a run-to-rel-pos counts from the previous target, not the position",
    ),
    "reset_coasts": (
        EV3_MOTOR,
        r"__legoev3_motor_stop\(ev3_tm, (TM_STOP_ACTION_COAST)\);",
        "legoev3_motor_reset stops the motor with coast",
    ),
    "position_follows_polarity": (
        TACHO_CLASS,
        r"if \(tm->polarity == DC_MOTOR_POLARITY_INVERSED\)",
        "position_show (and speed, duty_cycle, the setpoints) negate the motor's count when inversed",
    ),
    "touch_threshold_mv": (
        "sensors/ev3_analog_sensor_defs.c",
        r"\*value = \(raw_value > (\d+)\) \? 1 : 0;",
        "lego_ev3_touch_sensor_scale: value0 is 1 when the raw reading (mV) is above this",
    ),
}


class Checkout:
    """The drivers' files at one commit of a git repository (bare or not)."""

    def __init__(self, path: Path, ref: str) -> None:
        self.path = path
        self.commit = self._git("rev-parse", f"{ref}^{{commit}}").strip()
        self.ref = ref.removeprefix("origin/")  # (a clone's branches are origin/..., a mirror's not)
        if ref == "HEAD":  # name the branch HEAD stands for, when there is one
            done = subprocess.run(
                ["git", "-C", str(path), "symbolic-ref", "--short", "-q", "HEAD"],
                capture_output=True,
                text=True,
            )
            self.ref = done.stdout.strip() or self.commit
        self._files: dict[str, list[str]] = {}

    def _git(self, *args: str) -> str:
        done = subprocess.run(["git", "-C", str(self.path), *args], capture_output=True, text=True)
        if done.returncode != 0:
            raise SystemExit(f"git {' '.join(args)} in {self.path}: {done.stderr.strip()}")
        return done.stdout

    def lines(self, file: str) -> list[str]:
        if file not in self._files:
            self._files[file] = self._git("show", f"{self.commit}:{file}").split("\n")
        return self._files[file]


# ----------------------------------------------------------------------------- the defs tables
ENTRY = re.compile(r"\s*\[(\w+)\]\s*=\s*\{\s*$")
FIELD = re.compile(r"\s*\.([\w.]+)\s*=\s*(?:\([^)]*\)\s*)?(.*?),?\s*$")
DOC_KEY = re.compile(r"\s*\*\s*@(\w+):\s*(.*)")
FOOTNOTE = re.compile(r"\s*\*\s*\.\. \[#([\w-]+)\]\s*(.*)")
RANGE = re.compile(r"\((?P<low>-?\d+)(?: and (?P<low2>-?\d+))?\s*(?:to|-|or)\s*(?P<high>-?\d+)(?:\?+)?\)\s*$")


def _doc_comment(lines: list[str], i: int) -> tuple[dict, dict, int]:
    """A `/** ... */` comment from line i: its @key: value pairs and its footnotes (name -> text)."""
    doc: dict[str, str] = {}
    notes: dict[str, str] = {}
    current = None
    i += 1
    while not re.match(r"\s*\*/", lines[i]):
        line = lines[i]
        key, note = DOC_KEY.match(line), FOOTNOTE.match(line)
        if key:
            doc[key.group(1)] = key.group(2).strip()
            current = None
        elif note:
            current = note.group(1)
            notes[current] = note.group(2).strip()
        elif current is not None:
            text = re.sub(r"^\s*\*\s?", "", line)
            if text.strip():
                notes[current] += "\n" + text.rstrip()
            else:
                notes[current] += "\n"
        i += 1
    for name, text in notes.items():  # the footnote's own indentation is RST's, not ours
        notes[name] = "\n".join(part.strip() for part in text.strip().split("\n"))
    return doc, notes, i + 1


def _block(lines: list[str], i: int, constants: dict[str, str]) -> tuple[dict, int]:
    """The struct initialiser whose `{` ended line i-1, up to its closing `}`: fields, doc, entries."""
    found: dict = {"fields": {}, "entries": []}
    while True:
        line = lines[i]
        stripped = line.strip()
        if re.match(r"\}\s*[,;]?\s*$", stripped):
            return found, i + 1
        if stripped.startswith("/**"):
            doc, notes, i = _doc_comment(lines, i)
            found["doc"], found["footnotes"] = doc, notes
            continue
        if stripped.startswith("/*"):
            while "*/" not in lines[i]:
                i += 1
            i += 1
            continue
        if not stripped or stripped.startswith("#"):
            i += 1
            continue
        entry = ENTRY.match(line)
        if entry:
            body, after = _block(lines, i + 1, constants)
            body["id"], body["line"] = entry.group(1), i + 1
            found["entries"].append(body)
            i = after
            continue
        field = FIELD.match(line)
        if not field:
            raise SystemExit(f"cannot read line {i + 1}: {line!r}")
        name, value = field.group(1), field.group(2).strip()
        if value.endswith("{"):
            body, i = _block(lines, i + 1, constants)
            found["fields"][name] = body
            continue
        if value.startswith("{"):  # one line: { .p = 1000, .i = 60, .d = 0 }
            pairs = re.findall(r"\.(\w+)\s*=\s*(-?\w+)", value)
            found["fields"][name] = {"fields": dict(pairs), "entries": []}
        else:
            value = value.strip('"')
            found["fields"][name] = constants.get(value, value)
        i += 1


def _constants(lines: list[str]) -> dict[str, str]:
    """A header's `#define NAME "text"` lines: the drivers' names."""
    return dict(re.findall(r'^#define\s+(\w+)\s+"([\w-]+)"', "\n".join(lines), re.M))


def _defs_tables(lines: list[str], constants: dict[str, str]) -> list[dict]:
    """Each entry of every `<type> <name>_defs[] = {` table in a file."""
    entries = []
    i = 0
    while i < len(lines):
        if re.match(r"(?:\w+\s)+\w+_defs\[\w*\]\s*=\s*\{", lines[i]):
            block, i = _block(lines, i + 1, constants)
            entries += block["entries"]
            continue
        i += 1
    return entries


def _int(value, default: int = 0) -> int:
    return default if value is None else int(value)


def _values(doc: dict) -> list[dict]:
    """The @valueN lines of a mode: text, documented range (None when the text gives none), footnotes."""
    values = []
    n = 0
    while f"value{n}" in doc:
        text = doc[f"value{n}"]
        found = RANGE.search(text)
        entry: dict = {"text": text, "range": None}
        if found:
            lows = [int(found["low"])] + ([int(found["low2"])] if found["low2"] else [])
            entry["range"] = [min(lows), int(found["high"])]
        if f"value{n}_footnote" in doc:
            entry["footnotes"] = re.findall(r"\[#([\w-]+)\]_", doc[f"value{n}_footnote"])
        values.append(entry)
        n += 1
    return values


def sensors(checkout: Checkout, formats: dict[str, str]) -> list[dict]:
    """Every LEGO sensor of the defs files, with its modes."""
    found = []
    for defs, header in SENSOR_DEFS:
        constants = _constants(checkout.lines(header))
        for entry in _defs_tables(checkout.lines(defs), constants):
            doc = entry.get("doc", {})
            if doc.get("vendor_name") != "LEGO":
                continue
            fields = entry["fields"]
            modes = []
            mode_table = fields.get("mode_info", {"entries": []})["entries"]
            for index, mode in enumerate(mode_table):
                f, mode_doc = mode["fields"], mode.get("doc", {})
                data_type = f.get("data_type")
                data_sets = _int(f.get("data_sets"), 1)
                modes.append(
                    {
                        "index": index,
                        "name": f["name"],
                        "line": mode["line"],
                        "description": mode_doc.get("description", ""),
                        "data_sets": data_sets,
                        "num_values": _int(f.get("num_values")) or data_sets,
                        "data_type": data_type,
                        "bin_data_format": formats.get(data_type) if data_type else None,
                        "units": f.get("units", ""),
                        "units_description": mode_doc.get("units_description", ""),
                        "decimals": _int(f.get("decimals")),
                        **{k: _int(f.get(k)) for k in ("raw_min", "raw_max", "pct_min", "pct_max")},
                        **{k: _int(f.get(k)) for k in ("si_min", "si_max")},
                        "scale": f.get("scale"),
                        "values": _values(mode_doc),
                        "footnotes": mode.get("footnotes", {}),
                        **(
                            {"name_footnote": mode_doc["name_footnote"]}
                            if "name_footnote" in mode_doc
                            else {}
                        ),
                    }
                )
            found.append(
                {
                    "driver": fields["name"],
                    "id": entry["id"],
                    "part_name": doc.get("vendor_part_name", ""),
                    "part_number": doc.get("vendor_part_number", ""),
                    "file": defs,
                    "line": entry["line"],
                    "num_modes": _int(fields.get("num_modes"), len(modes)),
                    "modes": modes,
                }
            )
    return found


def motors(checkout: Checkout) -> list[dict]:
    """Every LEGO motor of motors/ev3_motor_defs.c."""
    defs, header = MOTOR_DEFS
    found = []
    for entry in _defs_tables(checkout.lines(defs), _constants(checkout.lines(header))):
        doc, fields = entry.get("doc", {}), entry["fields"]
        if doc.get("vendor_name") != "LEGO":
            continue
        pid = fields["legoev3_info"]["fields"]
        speed, position = pid["speed_pid_k"]["fields"], pid["position_pid_k"]["fields"]
        found.append(
            {
                "driver": fields["name"],
                "id": entry["id"],
                "part_name": doc.get("vendor_part_name", ""),
                "part_number": doc.get("vendor_part_number", ""),
                "file": defs,
                "line": entry["line"],
                "max_speed": int(fields["max_speed"]),
                "count_per_rot": int(fields["count_per_rot"]),
                "motion_type": fields["motion_type"],
                "speed_pid": {"Kp": int(speed["p"]), "Ki": int(speed["i"]), "Kd": int(speed["d"])},
                "hold_pid": {"Kp": int(position["p"]), "Ki": int(position["i"]), "Kd": int(position["d"])},
            }
        )
    return found


# ------------------------------------------------------------------- the classes' attribute tables
def attribute_table(lines: list[str], file: str) -> list[dict]:
    """The `.. flat-table:: ... attributes` of a class's `DOC: userspace` comment."""
    start = next(i for i, line in enumerate(lines) if "flat-table::" in line)
    rows: list[dict] = []
    cell = -1
    for i in range(start + 1, len(lines)):
        line = lines[i]
        if line.strip() == "*/":
            break
        text = re.sub(r"^\s*\*\s?", "", line)
        head = re.match(r"\s*\* - ``(.+?)``\s*$", text)
        if head:
            rows.append({"name": head.group(1), "line": i + 1, "file": file, "access": "", "text": []})
            cell = 0
            continue
        if not rows:
            continue
        part = re.match(r"\s{3,}- (.*)$", text)
        if part and cell in (0, 1) and re.match(r"\s{5}- ", text) and not re.match(r"\s{6,}- ", text):
            cell += 1
            if cell == 1:
                rows[-1]["access"] = part.group(1).strip()
            else:
                rows[-1]["text"].append(part.group(1))
            continue
        if cell == 2:
            rows[-1]["text"].append(text)
    for row in rows:
        row["description"], row["values"] = _description(row.pop("text"))
    return rows


def _description(text: list[str]) -> tuple[str, list[dict]]:
    """A description cell: its prose (one paragraph of words) and the `- ``value``: meaning` items."""
    prose: list[str] = []
    values: list[dict] = []
    item_indent = None
    for raw in text:
        indent = len(raw) - len(raw.lstrip())
        item = re.match(r"\s*- ``(.+?)``:\s*(.*)", raw)
        if item:
            values.append({"name": item.group(1), "text": item.group(2).strip()})
            item_indent = indent
        elif item_indent is not None and indent > item_indent and raw.strip():
            values[-1]["text"] += " " + raw.strip()
        elif raw.strip():
            prose.append(raw.strip())
            item_indent = None
    return " ".join(prose), values


def names(lines: list[str], array: str, file: str) -> dict:
    """The names of a `static ... <array>[...] = { [X] = { "name" }, ... }` table, in the enum's order."""
    start = next(i for i, line in enumerate(lines) if re.search(rf"\b{array}\b\s*\[", line))
    found = []
    for i in range(start, len(lines)):
        item = re.search(r'\[\w+\]\s*=\s*\{?\s*"([\w-]+)"', lines[i])
        if item:
            found.append(item.group(1))
        if lines[i].strip() == "};":
            break
    return {"names": found, "file": file, "line": start + 1}


def bin_data_formats(lines: list[str]) -> dict[str, str]:
    """lego_sensor_bin_data_format_to_str: data_type -> the text bin_data_format shows."""
    start = next(i for i, line in enumerate(lines) if "lego_sensor_bin_data_format_to_str(enum" in line)
    formats, case = {}, None
    for line in lines[start:]:
        found = re.match(r"\s*case (LEGO_SENSOR_DATA_\w+):", line)
        if found:
            case = found.group(1)
        text = re.match(r'\s*return "([\w]+)";', line)
        if text and case:
            formats[case] = text.group(1)
            case = None
        if line.startswith("}"):
            break
    return formats


def facts(checkout: Checkout) -> dict:
    found = {}
    for name, (file, pattern, meaning) in FACTS.items():
        for number, line in enumerate(checkout.lines(file), 1):
            match = re.search(pattern, line)
            if match:
                value = match.group(1) if match.groups() else None
                if value is not None and value.isdigit():
                    value = int(value)
                found[name] = {"value": value, "meaning": meaning, "file": file, "line": number}
                found[name]["source"] = line.strip()
                break
        else:
            raise SystemExit(f"{file}: no line matches {pattern!r} (fact {name}); update FACTS")
    return found


def extract(checkout: Checkout) -> dict:
    formats = bin_data_formats(checkout.lines(SENSOR_CLASS))
    tacho = checkout.lines(TACHO_CLASS)
    return {
        "commit": checkout.commit,
        "ref": checkout.ref,
        "bin_data_formats": formats,
        "lego_sensor_class": {
            "file": SENSOR_CLASS,
            "attributes": attribute_table(checkout.lines(SENSOR_CLASS), SENSOR_CLASS),
        },
        "tacho_motor_class": {
            "file": TACHO_CLASS,
            "attributes": attribute_table(tacho, TACHO_CLASS),
            "commands": names(tacho, "tacho_motor_command_names", TACHO_CLASS),
            "stop_actions": names(tacho, "tm_stop_action_names", TACHO_CLASS),
            "states": names(tacho, "tacho_motor_states", TACHO_CLASS),
            "polarities": names(checkout.lines(DC_MOTOR_CLASS), "dc_motor_polarity_values", DC_MOTOR_CLASS),
        },
        "motors": motors(checkout),
        "sensors": sensors(checkout, formats),
        "facts": facts(checkout),
    }


MODE_KEYS = ("num_values", "data_sets", "data_type", "bin_data_format", "units", "decimals")


def differences(main: dict, other: dict) -> dict:
    """Per sensor driver and mode: the properties another branch documents differently."""
    theirs = {(s["driver"], m["name"]): m for s in other["sensors"] for m in s["modes"]}
    found: dict[str, dict] = {}
    for sensor in main["sensors"]:
        for mode in sensor["modes"]:
            them = theirs.get((sensor["driver"], mode["name"]))
            if them is None:
                found.setdefault(sensor["driver"], {})[mode["name"]] = {"missing": True}
                continue
            changed = {k: them[k] for k in MODE_KEYS if them[k] != mode[k]}
            if [v["range"] for v in them["values"]] != [v["range"] for v in mode["values"]]:
                changed["ranges"] = [v["range"] for v in them["values"]]
            if changed:
                found.setdefault(sensor["driver"], {})[mode["name"]] = changed
    return found


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("checkout", type=Path, help="a git clone of ev3dev/lego-linux-drivers")
    parser.add_argument("--ref", default="HEAD", help="the branch, tag or commit to read (default HEAD)")
    parser.add_argument("--also", action="append", default=[], help="another ref to compare the modes with")
    parser.add_argument("--out", type=Path, default=OUT)
    args = parser.parse_args(argv)
    checkout = Checkout(args.checkout, args.ref)
    data = {
        "about": (
            "What lego-linux-drivers documents about the LEGO devices; written by "
            "docs/fidelity/extract_drivers.py, read by docs/make_fidelity.py. Do not edit by hand."
        ),
        "repository": REPOSITORY,
        **extract(checkout),
        "other_refs": [],
    }
    for ref in args.also:
        other = Checkout(args.checkout, ref)
        data["other_refs"].append(
            {"ref": other.ref, "commit": other.commit, "modes": differences(data, extract(other))}
        )
    args.out.write_text(json.dumps(data, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    print(f"wrote {args.out} from {REPOSITORY} {data['ref']} {data['commit'][:12]}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
