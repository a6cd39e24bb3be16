"""The characters of a text grid and the cells they stand for.

Default legend: `#` wall, `.` white floor, `0`-`9` grey shades (digit d is
shade round(d*100/9)), `k` black, `b` blue, `g` green, `y` yellow, `r` red,
`w` white, `n` brown.  A world file may add or override characters; an entry
may also put its cells into a named region (e.g. a green `goal`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from .cell import WALL, Cell
from .colors import EV3_COLORS
from .file_limits import MAX_LEGEND_ENTRIES, MAX_NAME_CHARS
from .yaml_source import Node

ENTRY_HELP = (
    "`wall`, a colour name (" + ", ".join(EV3_COLORS) + "), `shade 40` (0 black .. 100 white), "
    "or a mapping like `{color: red}`, `{shade: 40, region: goal}` or `{wall: true, color: red}`"
)


@dataclass(frozen=True)
class LegendEntry:
    """What one character means: its cell, and the region its cells belong to (if any)."""

    cell: Cell
    region: str | None = None


class Legend:
    """An ordered, read-only mapping from single characters to legend entries."""

    def __init__(self, entries: Mapping[str, LegendEntry]) -> None:
        for char in entries:
            if len(char) != 1 or char.isspace():
                raise ValueError(f"legend characters are single non-space characters, got {char!r}")
        self._entries = dict(entries)
        self._char_of_cell: dict[Cell, str] = {}
        for char, entry in self._entries.items():
            self._char_of_cell.setdefault(entry.cell, char)

    def __contains__(self, char: str) -> bool:
        return char in self._entries

    def __len__(self) -> int:
        return len(self._entries)

    @property
    def chars(self) -> list[str]:
        """The characters, in legend order."""
        return list(self._entries)

    def entry(self, char: str) -> LegendEntry | None:
        """The entry for `char`, or None if the legend does not know it."""
        return self._entries.get(char)

    def cell(self, char: str) -> Cell:
        """The cell for a known character."""
        return self._entries[char].cell

    def region(self, char: str) -> str | None:
        """The region a character's cells belong to, if any."""
        return self._entries[char].region

    def char_for(self, cell: Cell) -> str:
        """A character that draws `cell`: its own, else the nearest of the same kind, else '?'."""
        char = self._char_of_cell.get(cell)
        if char is not None:
            return char
        same_kind = [(c, e.cell) for c, e in self._entries.items() if e.cell.wall == cell.wall]
        if cell.color is not None:
            for c, other in same_kind:
                if other.color == cell.color:
                    return c
        if cell.wall:
            return same_kind[0][0] if same_kind else "?"
        shades = [(abs(other.reflected - cell.reflected), c) for c, other in same_kind if other.color is None]
        return min(shades)[1] if shades else "?"

    def extended(self, entries: Mapping[str, LegendEntry | Cell | str]) -> Legend:
        """A new legend with `entries` added or replacing existing characters."""
        merged = dict(self._entries)
        for char, value in entries.items():
            merged[char] = as_entry(value)
        return Legend(merged)

    def describe(self) -> str:
        """The known characters for messages: `'#' wall, '.' shade 100, ...`."""
        return ", ".join(f"'{char}' {entry.cell.describe()}" for char, entry in self._entries.items())


def _default_entries() -> dict[str, LegendEntry]:
    entries = {"#": LegendEntry(WALL), ".": LegendEntry(Cell.floor_shade(100))}
    for char, name in zip(
        "kbgyrwn", ("black", "blue", "green", "yellow", "red", "white", "brown"), strict=True
    ):
        entries[char] = LegendEntry(Cell.floor_color(name))
    for digit in range(10):
        entries[str(digit)] = LegendEntry(Cell.floor_shade(round(digit * 100 / 9)))
    return entries


DEFAULT_LEGEND = Legend(_default_entries())
"""The characters every world knows without a `legend:` section."""


def as_entry(value: LegendEntry | Cell | str) -> LegendEntry:
    """A legend entry from an entry, a cell, or a word such as 'wall', 'red', 'shade 40'."""
    if isinstance(value, LegendEntry):
        return value
    if isinstance(value, Cell):
        return LegendEntry(value)
    cell = cell_from_words(value)
    if cell is None:
        raise ValueError(f"unknown legend entry {value!r}; write {ENTRY_HELP}")
    return LegendEntry(cell)


def as_legend(legend: Legend | Mapping[str, LegendEntry | Cell | str] | None) -> Legend:
    """The default legend, a given legend, or the default legend extended by a mapping."""
    if legend is None:
        return DEFAULT_LEGEND
    if isinstance(legend, Legend):
        return legend
    return DEFAULT_LEGEND.extended(legend)


def cell_from_words(text: str) -> Cell | None:
    """'wall', a colour name or 'shade 40' as a cell; None if the words mean none of these."""
    words = text.strip().lower().split()
    if words == ["wall"]:
        return WALL
    if len(words) == 1 and words[0] in EV3_COLORS:
        return Cell.floor_color(words[0])
    if len(words) == 2 and words[0] == "shade":
        try:
            shade = float(words[1])
        except ValueError:
            return None
        if 0 <= shade <= 100:
            return Cell.floor_shade(shade)
    return None


def legend_from_node(node: Node, base: Legend = DEFAULT_LEGEND) -> Legend:
    """The `legend:` section of a world file, added to `base`."""
    fields = node.as_fields("legend", allowed=None, example="legend: {G: green}")
    if len(fields) > MAX_LEGEND_ENTRIES:
        raise node.error(
            f"'legend' has {len(fields):,} entries, more than the {MAX_LEGEND_ENTRIES} a world may add "
            "(docs/world-files.md, Limits); use fewer characters"
        )
    entries: dict[str, LegendEntry] = {}
    for key, value in fields.items():
        char = key.text
        if len(char) != 1 or char.isspace():
            raise key.error(
                f"legend keys are single characters (not spaces), got {char!r}; "
                'write e.g. `G: green` (quote special ones: `"#": wall`)'
            )
        entries[char] = _entry_from_node(char, value)
    return base.extended(entries)


def _entry_from_node(char: str, node: Node) -> LegendEntry:
    if node.is_scalar and not node.is_null:
        cell = cell_from_words(node.text)
        if cell is None:
            raise node.error(f"legend entry for '{char}' is {node.describe()}; write {ENTRY_HELP}")
        return LegendEntry(cell)
    if not node.is_mapping:
        raise node.error(f"legend entry for '{char}' is {node.describe()}; write {ENTRY_HELP}")
    fields = node.as_fields(f"legend entry '{char}'", allowed=("wall", "color", "shade", "region"))
    wall = fields.boolean("wall", default=False)
    color = None
    if "color" in fields:
        color_node = fields.get("color")
        color = color_node.as_text("color").strip().lower()
        if color not in EV3_COLORS:
            raise color_node.error(
                f"unknown colour {color_node.describe()}; the EV3 colours are {', '.join(EV3_COLORS)}"
            )
    shade = None
    if "shade" in fields:
        shade_node = fields.get("shade")
        shade = shade_node.as_number("shade", "0 black .. 100 white", "shade: 40")
        if not 0 <= shade <= 100:
            raise shade_node.error(f"'shade' must be between 0 (black) and 100 (white), got {shade:g}")
    if color is not None and shade is not None:
        raise node.error(f"legend entry for '{char}' has both 'color' and 'shade'; keep one")
    if not wall and color is None and shade is None:
        raise node.error(f"legend entry for '{char}' says neither wall, colour nor shade; write {ENTRY_HELP}")
    region = None
    if "region" in fields:
        region = _region_name(fields.get("region"))
    return LegendEntry(Cell(wall=wall, shade=shade, color=color), region)


def _region_name(node: Node) -> str:
    name = node.as_text("region", "region: goal").strip()
    if not name:
        raise node.error("'region' needs a name, e.g. `region: goal`")
    if len(name) > MAX_NAME_CHARS or any(ord(c) < 32 or ord(c) == 127 for c in name):
        raise node.error(
            f"a region's name is 1 to {MAX_NAME_CHARS} characters, not control characters; "
            "write e.g. `region: goal`"
        )
    return name
