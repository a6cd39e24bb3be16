"""A world file's text written: a new one (`new_maze_text`), or an edited world written back into its
file's text, changing only what was edited.

Each top-level block the editor knows (`cell_cm:`, `legend:`, `grid:`,
`start:`, `regions:`) is replaced only when its content changed; everything
else - comments, `title:`, `robot:`, keys the editor does not know - is kept
byte for byte, so saving an unchanged world gives back the same text.  A cell
kind the legend lacks gets a new legend entry with a free character.
"""

from __future__ import annotations

import json
import re
from collections.abc import Mapping

import yaml

from .cell import Cell
from .grid_text import text_rows
from .legend import Legend, LegendEntry, as_entry
from .pose import Pose
from .world_json import EditedWorld, MazeSource
from .yaml_source import Fields, Node, load_yaml_text

FREE_CHARS = "ABCDEFHIJKLMOPQSTUVXZacdefhijlmopqstuvxz@%&+=*~^$!?<>"
"""Characters a new legend entry may take (never a quote, backslash, space or '#')."""
PLAIN_KEY = re.compile(r"^[A-Za-z][A-Za-z0-9_-]*$")
YAML_WORDS = {"true", "false", "null", "yes", "no", "on", "off", "y", "n"}
_KEY_LINE_TAIL = re.compile(r"^\s*:\s*(?:\|[-+0-9]*)?\s*(#.*)?$")


def write_maze_text(source: MazeSource, edited: EditedWorld) -> str:
    """The world file's text with the edits in; the same text when nothing changed."""
    original = source.as_edited()
    text = source.text
    blocks = _top_level(text, source.path)
    edits: list[tuple[int, int, str]] = []  # (start, end, new text), by character offset

    if edited.cell_cm != original.cell_cm:
        if "cell_cm" in blocks:
            value = blocks["cell_cm"][1]
            edits.append((value.raw.start_mark.index, value.raw.end_mark.index, _num(edited.cell_cm)))
        else:
            at = _span(text, blocks, "grid")[0]
            edits.append((at, at, f"cell_cm: {_num(edited.cell_cm)}\n"))

    if _chars_unchanged(source, edited):
        pass
    else:
        rows, new_entries = _grid_chars(source, edited)
        start, end = _span(text, blocks, "grid")
        edits.append((start, end, _grid_text(text, blocks["grid"], rows)))
        if new_entries:
            edits.append(_legend_edit(text, blocks, new_entries))

    if edited.starts != original.starts:
        start, end = _span(text, blocks, "start")
        edits.append((start, end, _start_text(text, blocks["start"], edited)))

    if edited.regions != original.regions:
        new = _regions_text(text, blocks.get("regions"), edited)
        if "regions" in blocks:
            start, end = _span(text, blocks, "regions")
            edits.append((start, end, new))
        elif new:
            at = len(text)
            edits.append((at, at, ("" if text.endswith("\n") or not text else "\n") + new))

    for start, end, new in sorted(edits, key=lambda e: (e[0], e[1]), reverse=True):
        text = text[:start] + new + text[end:]
    return text


# -- where the blocks are ---------------------------------------------------------------------


def _top_level(text: str, path: str) -> dict[str, tuple[Node, Node]]:
    fields = Fields(load_yaml_text(text, path), "the maze file", None)
    return {key.text: (key, value) for key, value in fields.items()}


def _line_starts(text: str) -> list[int]:
    starts = [0]
    for i, char in enumerate(text):
        if char == "\n":
            starts.append(i + 1)
    return starts


def _span(text: str, blocks: dict[str, tuple[Node, Node]], name: str) -> tuple[int, int]:
    """Character offsets of a top-level key's lines: from its key line to the next key, less the
    blank lines and column-0 comments just before that next key (they belong to it)."""
    line_starts = _line_starts(text)
    key = blocks[name][0]
    first = key.raw.start_mark.line
    later = sorted(k.raw.start_mark.line for k, _ in blocks.values() if k.raw.start_mark.line > first)
    stop = later[0] if later else len(line_starts)
    lines = text.split("\n")
    last_value_line = blocks[name][1].raw.end_mark.line
    while stop - 1 > max(first, last_value_line - 1):
        line = lines[stop - 1] if stop - 1 < len(lines) else ""
        if line.strip() == "" or line.startswith("#"):
            stop -= 1
        else:
            break
    end = line_starts[stop] if stop < len(line_starts) else len(text)
    return line_starts[first], end


def _key_comment(text: str, key: Node, value: Node) -> str:
    """The comment on a key's own line (`start:   # one pose`), kept when the block is rewritten."""
    if value.raw.start_mark.line == key.raw.start_mark.line and value.style != "|":
        return ""
    line_end = text.find("\n", key.raw.end_mark.index)
    tail = text[key.raw.end_mark.index : line_end if line_end >= 0 else len(text)]
    match = _KEY_LINE_TAIL.match(tail)
    return "  " + match.group(1) if match and match.group(1) else ""


# -- grid and legend --------------------------------------------------------------------------


def _kept_char(legend: Legend, edited_cell, original_char: str | None) -> str | None:
    """The cell's own character, when it still means this cell."""
    char = edited_cell.char
    if char is None or char not in legend or legend.cell(char) != edited_cell.cell:
        return None
    if legend.region(char) is not None and char != original_char:
        return None  # a region character only stays where it was
    return char


def _chars_unchanged(source: MazeSource, edited: EditedWorld) -> bool:
    if (edited.width, edited.height) != (source.grid.width, source.grid.height):
        return False
    legend = source.grid.legend
    return all(
        _kept_char(legend, edited.cells[row][col], source.chars[row][col]) == source.chars[row][col]
        for row in range(edited.height)
        for col in range(edited.width)
    )


def _grid_chars(source: MazeSource, edited: EditedWorld) -> tuple[list[str], dict[str, Cell]]:
    """The grid rows (top row first) and the legend entries it needs that the file lacks."""
    legend = source.grid.legend
    width, height = source.grid.width, source.grid.height
    new_entries: dict[str, Cell] = {}
    chosen: dict[Cell, str] = {}
    free = [c for c in FREE_CHARS if c not in legend]
    rows = []
    for row in range(edited.height):
        chars = []
        for col in range(edited.width):
            item = edited.cells[row][col]
            original = source.chars[row][col] if row < height and col < width else None
            char = _kept_char(legend, item, original)
            if char is None:
                char = chosen.get(item.cell) or _plain_char(legend, item.cell)
            if char is None:
                if not free:
                    raise ValueError(
                        "too many different kinds of cell for one legend; use fewer shades or colours"
                    )
                char = free.pop(0)
                new_entries[char] = item.cell
            chosen[item.cell] = char
            chars.append(char)
        rows.append("".join(chars))
    return list(reversed(rows)), new_entries


def _plain_char(legend: Legend, cell: Cell) -> str | None:
    """A legend character for exactly this cell that puts it in no region."""
    for char in legend.chars:
        if legend.cell(char) == cell and legend.region(char) is None:
            return char
    return None


def _grid_text(text: str, block: tuple[Node, Node], rows: list[str]) -> str:
    key, value = block
    comment = _key_comment(text, key, value)
    if value.is_sequence:
        items = value.as_list("grid")
        indent = " " * (items[0].raw.start_mark.column - 2) if items else "  "
        return f"grid:{comment}\n" + "".join(f"{indent}- {json.dumps(row)}\n" for row in rows)
    indent = "  "
    first_row = value.raw.start_mark.line + 1
    lines = text.split("\n")
    for line in lines[first_row : first_row + 50]:
        if line.strip():
            indent = line[: len(line) - len(line.lstrip(" "))] or "  "
            break
    return f"grid: |{comment}\n" + "".join(f"{indent}{row}\n" for row in rows)


def _entry_text(cell: Cell) -> str:
    parts = ["wall: true"] if cell.wall else []
    if cell.color is not None:
        parts.append(f"color: {cell.color}")
    if cell.shade is not None:
        parts.append(f"shade: {_num(cell.shade)}")
    return "{" + ", ".join(parts) + "}"


def _legend_edit(
    text: str, blocks: dict[str, tuple[Node, Node]], entries: dict[str, Cell]
) -> tuple[int, int, str]:
    """Add entries at the end of the legend (written as a block), or a new legend before the grid."""
    if "legend" not in blocks or blocks["legend"][1].is_null:
        lines = "".join(f"  {json.dumps(char)}: {_entry_text(cell)}\n" for char, cell in entries.items())
        if "legend" in blocks:
            start, end = _span(text, blocks, "legend")
            return (start, end, "legend:\n" + lines)
        at = _span(text, blocks, "grid")[0]
        return (at, at, "legend:\n" + lines)
    key, value = blocks["legend"]
    items = Fields(value, "'legend'", None).items()
    if value.raw.flow_style or not items:
        # a flow mapping `{G: green}`: written again as a block, each entry as it was written
        kept = "".join(
            f"  {text[k.raw.start_mark.index : k.raw.end_mark.index]}: "
            f"{text[v.raw.start_mark.index : v.raw.end_mark.index]}\n"
            for k, v in items
        )
        added = "".join(f"  {json.dumps(char)}: {_entry_text(cell)}\n" for char, cell in entries.items())
        start, end = _span(text, blocks, "legend")
        return (start, end, f"legend:{_key_comment(text, key, value)}\n" + kept + added)
    indent = " " * items[0][0].raw.start_mark.column
    last_line = max(
        v.raw.end_mark.line if v.raw.end_mark.column > 0 else v.raw.end_mark.line - 1 for _, v in items
    )
    line_starts = _line_starts(text)
    at = line_starts[last_line + 1] if last_line + 1 < len(line_starts) else len(text)
    prefix = "" if at == 0 or text[at - 1] == "\n" else "\n"
    return (
        at,
        at,
        prefix
        + "".join(f"{indent}{json.dumps(char)}: {_entry_text(cell)}\n" for char, cell in entries.items()),
    )


# -- starts and regions -----------------------------------------------------------------------


def _start_text(text: str, block: tuple[Node, Node], edited: EditedWorld) -> str:
    key, value = block
    comment = _key_comment(text, key, value)
    poses = [_pose_fields(pose, edited) for pose in edited.starts]
    for fields, robot in zip(poses, _start_robots(text, value), strict=False):
        if robot:  # a start's own robot (`robot: FILE`) stays with it
            fields.append(robot)
    if len(poses) == 1 and not value.is_sequence:
        return f"start:{comment}\n" + "".join(f"  {field}\n" for field in poses[0])
    return f"start:{comment}\n" + "".join("  - {" + ", ".join(fields) + "}\n" for fields in poses)


def _start_robots(text: str, value: Node) -> list[str]:
    """Each start's `robot: ...` as written (a file name or a shipped robot's), or "" for none."""
    starts = list(value.raw.value) if value.is_sequence else [value.raw]
    found = []
    for start in starts:
        robot = ""
        if isinstance(start, yaml.MappingNode):
            for key, item in start.value:
                if key.value == "robot" and isinstance(item, yaml.ScalarNode):
                    robot = "robot: " + text[item.start_mark.index : item.end_mark.index]
        found.append(robot)
    return found


def _pose_fields(pose, edited: EditedWorld) -> list[str]:
    s = edited.cell_cm
    col, row = pose.x_cm / s - 0.5, pose.y_cm / s - 0.5
    heading = f"heading_deg: {_num(pose.heading_deg)}"
    if (
        col == int(col)
        and row == int(row)
        and (int(col) + 0.5) * s == pose.x_cm
        and (int(row) + 0.5) * s == pose.y_cm
    ):
        return [f"cell: [{int(col)}, {int(row)}]", heading]
    return [f"x_cm: {_num(pose.x_cm)}", f"y_cm: {_num(pose.y_cm)}", heading]


def _regions_text(text: str, block: tuple[Node, Node] | None, edited: EditedWorld) -> str:
    if not edited.regions:
        return ""
    comment = _key_comment(text, *block) if block is not None else ""
    lines = [f"regions:{comment}"]
    for name, rects in edited.regions:
        lines.append(f"  {_key(name)}:")
        if len(rects) == 1:
            lines.append(f"    rect_cm: {_rect(rects[0])}")
        else:
            lines.append("    rects_cm: [" + ", ".join(_rect(r) for r in rects) + "]")
    return "\n".join(lines) + "\n"


def _rect(rect) -> str:
    return "[" + ", ".join(_num(v) for v in rect) + "]"


def _key(name: str) -> str:
    return name if PLAIN_KEY.match(name) and name.lower() not in YAML_WORDS else json.dumps(name)


def _num(value: float) -> str:
    value = float(value)
    if value.is_integer():
        return str(int(value))
    return repr(round(value, 6))


# -- a new world file ---------------------------------------------------------------------------


def new_maze_text(
    grid_text: str,
    *,
    cell_cm: float,
    starts: list[Pose | tuple],
    legend: Mapping[str, LegendEntry | Cell | str] | None = None,
    title: str = "",
    description: str = "",
    robot: str | None = None,
) -> str:
    """The YAML of a new maze file: a text grid (top row first), starts as Poses, (col, row) or
    (col, row, heading_deg) cells, legend entries beyond the default ones, and a robot file's name."""
    lines = [f"title: {json.dumps(title)}"] if title else []
    if description:
        lines.append(f"description: {json.dumps(description)}")
    lines.append(f"cell_cm: {cell_cm:g}")
    if legend:
        lines.append("legend:")
        for char, value in legend.items():
            lines.append(f"  {json.dumps(char)}: {json.dumps(_entry_mapping(as_entry(value)))}")
    lines.append("grid: |")
    lines += [f"  {row.text}" for row in text_rows(grid_text)]
    lines.append("start:")
    for start in starts:
        fields = ", ".join(f"{key}: {json.dumps(value)}" for key, value in _start_mapping(start).items())
        lines.append(f"  - {{{fields}}}")
    if robot:
        lines.append(f"robot: {json.dumps(robot)}")
    return "\n".join(lines) + "\n"


def _entry_mapping(entry: LegendEntry) -> dict:
    cell = entry.cell
    mapping: dict = {"wall": True} if cell.wall else {}
    if cell.color is not None:
        mapping["color"] = cell.color
    if cell.shade is not None:
        mapping["shade"] = cell.shade
    if entry.region is not None:
        mapping["region"] = entry.region
    return mapping


def _start_mapping(start: Pose | tuple) -> dict:
    if isinstance(start, Pose):
        return {"x_cm": start.x_cm, "y_cm": start.y_cm, "heading_deg": start.heading_deg}
    if isinstance(start, tuple | list) and len(start) in (2, 3):
        heading = start[2] if len(start) == 3 else 0
        return {"cell": [int(start[0]), int(start[1])], "heading_deg": heading}
    raise ValueError(
        f"a start is a Pose(x_cm, y_cm, heading_deg), a (col, row) cell or (col, row, heading_deg), got {start!r}"
    )
