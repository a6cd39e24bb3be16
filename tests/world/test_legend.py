"""The legend: which character stands for which cell, and how a world file extends it."""

import textwrap

import pytest

from ev3sim2d.world.cell import WALL, Cell
from ev3sim2d.world.legend import DEFAULT_LEGEND, LegendEntry, as_legend, cell_from_words, legend_from_node
from ev3sim2d.world.source_error import WorldFileError
from ev3sim2d.world.yaml_source import Fields, load_yaml_text


def test_default_characters():
    assert DEFAULT_LEGEND.cell("#") == WALL
    assert DEFAULT_LEGEND.cell(".") == Cell.floor_shade(100)
    letters = {"k": "black", "b": "blue", "g": "green", "y": "yellow", "r": "red", "w": "white", "n": "brown"}
    for char, color in letters.items():
        assert DEFAULT_LEGEND.cell(char) == Cell.floor_color(color)
    assert " " not in DEFAULT_LEGEND


@pytest.mark.parametrize(
    ("digit", "shade"), [("0", 0), ("1", 11), ("3", 33), ("5", 56), ("8", 89), ("9", 100)]
)
def test_digits_are_grey_shades(digit, shade):
    assert DEFAULT_LEGEND.cell(digit) == Cell.floor_shade(shade)


def test_printing_prefers_the_plain_characters():
    assert DEFAULT_LEGEND.char_for(Cell.floor_shade(100)) == "."
    assert DEFAULT_LEGEND.char_for(Cell.floor_shade(0)) == "0"
    assert DEFAULT_LEGEND.char_for(Cell.floor_color("black")) == "k"
    assert DEFAULT_LEGEND.char_for(Cell(wall=True, color="red")) == "#"


@pytest.mark.parametrize(
    ("words", "cell"),
    [
        ("wall", WALL),
        ("red", Cell.floor_color("red")),
        (" Blue ", Cell.floor_color("blue")),
        ("shade 40", Cell.floor_shade(40)),
        ("shade 140", None),
        ("purple", None),
        ("shade dark", None),
    ],
)
def test_entries_written_as_words(words, cell):
    assert cell_from_words(words) == cell


def test_a_python_mapping_extends_the_default_legend():
    legend = as_legend({"G": LegendEntry(Cell.floor_color("green"), "goal"), "X": "wall", "#": "red"})
    assert legend.region("G") == "goal"
    assert legend.cell("X") == WALL
    assert legend.cell("#") == Cell.floor_color("red")
    assert legend.cell(".") == Cell.floor_shade(100)
    with pytest.raises(ValueError):
        as_legend({"Q": "purple"})


def legend_section(text: str):
    root = load_yaml_text(textwrap.dedent(text).lstrip("\n"), "w.yaml")
    return legend_from_node(Fields(root, "the file", None).get("legend"))


def test_a_legend_section_adds_and_overrides_characters():
    legend = legend_section(
        """
        legend:
          G: {color: green, region: goal}
          X: {wall: true, color: red}
          "=": shade 40
          3: {shade: 30}
          ".": {shade: 90}
          B: blue
        """
    )
    assert legend.entry("G") == LegendEntry(Cell.floor_color("green"), "goal")
    assert legend.cell("X") == Cell(wall=True, color="red")
    assert legend.cell("=") == Cell.floor_shade(40)
    assert legend.cell("3") == Cell.floor_shade(30)
    assert legend.cell(".") == Cell.floor_shade(90)
    assert legend.cell("B") == Cell.floor_color("blue")
    assert legend.cell("#") == WALL


@pytest.mark.parametrize(
    ("text", "line", "words"),
    [
        ("legend:\n  G: purple\n", 2, ["legend entry for 'G'", "colour name"]),
        ("legend:\n  GG: red\n", 2, ["single characters"]),
        ("legend:\n  G: {color: red, shade: 4}\n", 2, ["both 'color' and 'shade'"]),
        ("legend:\n  G:\n    color: pink\n", 3, ["unknown colour 'pink'", "green"]),
        ("legend:\n  G: {shade: 120}\n", 2, ["between 0 (black) and 100 (white)"]),
        ("legend:\n  G: {colour: red}\n", 2, ["unknown key 'colour'", "did you mean 'color'"]),
        ("legend:\n  G: {wall: false}\n", 2, ["neither wall, colour nor shade"]),
        ("legend:\n  G: {wall: yes please}\n", 2, ["'wall' must be true or false"]),
        ("legend:\n  G: [red]\n", 2, ["legend entry for 'G'"]),
        ("legend: [G, red]\n", 1, ["'legend' must be a mapping"]),
    ],
)
def test_mistakes_in_the_legend_name_their_line(text, line, words):
    with pytest.raises(WorldFileError) as info:
        legend_section(text)
    assert info.value.line == line, str(info.value)
    for word in words:
        assert word in info.value.message
