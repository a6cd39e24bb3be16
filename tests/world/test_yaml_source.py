"""Reading YAML with line numbers: syntax errors, missing, mistyped and unknown keys all name their line."""

import pytest

from ev3sim2d.world.source_error import WorldFileError
from ev3sim2d.world.yaml_source import Fields, load_yaml_text


def fields(text: str, allowed=("cell_cm", "title", "grid")) -> Fields:
    return Fields(load_yaml_text(text, "w.yaml"), "'world'", allowed)


def error_of(call) -> WorldFileError:
    with pytest.raises(WorldFileError) as info:
        call()
    return info.value


def test_error_text_is_path_line_column_message():
    assert str(WorldFileError("a.yaml", 3, 7, "bad")) == "a.yaml:3:7: bad"
    assert str(WorldFileError("a.yaml", 3, None, "bad")) == "a.yaml:3: bad"
    assert str(WorldFileError("a.yaml", None, None, "bad")) == "a.yaml: bad"


def test_values_keep_their_line_and_column():
    node = load_yaml_text("title: x\ngrid:\n  - a\n  - bb\n", "w.yaml")
    items = Fields(node, "w", None).get("grid").as_list("grid")
    assert [(item.text, item.line, item.column) for item in items] == [("a", 3, 5), ("bb", 4, 5)]


def test_typed_reads():
    world = fields("cell_cm: 4\ntitle: 12\n")
    assert world.number("cell_cm") == 4.0
    assert world.text("title") == "12"
    assert world.number("grid", default=None) is None


def test_missing_key_says_what_to_add():
    err = error_of(lambda: fields("title: x\n").number("cell_cm", example="cell_cm: 10"))
    assert err.message == "missing key 'cell_cm' in 'world'; add e.g. `cell_cm: 10`"
    assert err.line == 1


def test_wrong_type_says_what_was_found():
    err = error_of(lambda: fields("title: x\ncell_cm: ten\n").number("cell_cm", unit="cm"))
    assert err.message == "'cell_cm' must be a number (cm), got 'ten'"
    assert (err.line, err.column) == (2, 10)


@pytest.mark.parametrize("value", ["true", "[1]", "", ".nan", "'4'"])
def test_only_real_numbers_are_numbers(value):
    err = error_of(lambda: fields(f"cell_cm: {value}\n").number("cell_cm", unit="cm"))
    assert "'cell_cm' must be a number (cm)" in err.message


def test_unknown_key_suggests_the_nearest_and_lists_the_allowed():
    err = error_of(lambda: fields("title: x\ncel_cm: 4\n"))
    assert err.line == 2
    assert "unknown key 'cel_cm'" in err.message
    assert "did you mean 'cell_cm'" in err.message
    assert "cell_cm, title, grid" in err.message


def test_a_key_written_twice_is_refused():
    err = error_of(lambda: fields("title: a\ngrid: x\ntitle: b\n"))
    assert err.line == 3 and "first on line 1" in err.message


@pytest.mark.parametrize(
    ("text", "line", "words"),
    [
        ("title: [a, b\ngrid: x\n", 2, ["YAML syntax error", "flow sequence on line 1"]),
        ("title: x\ngrid:\n\t- a\n", 3, ["tabs"]),
        ("title: a: b\n", 1, ["quotes"]),
        ("title: x\n---\ntitle: y\n", 2, ["one document"]),
        ('title: "unclosed\n', 2, ["YAML syntax error"]),
    ],
)
def test_syntax_errors_become_world_file_errors_with_the_line(text, line, words):
    err = error_of(lambda: load_yaml_text(text, "w.yaml"))
    assert err.path == "w.yaml" and err.line == line, str(err)
    for word in words:
        assert word in err.message


def test_an_empty_file_is_refused():
    err = error_of(lambda: load_yaml_text("# only a comment\n", "w.yaml"))
    assert "empty" in err.message
