"""YAML read with line numbers kept, so every mistake in a world file can name its line.

`load_yaml_text` composes the YAML into `Node`s (a value plus where it was
written); `Fields` reads a mapping key by key with typed accessors that turn a
missing key, a wrong type or an unknown key (usually a typo) into a
`WorldFileError` that says what to write instead.
"""

from __future__ import annotations

import codecs
import difflib
import math
import os
import re
import stat
from collections.abc import Iterable, Iterator
from pathlib import Path, PureWindowsPath
from typing import Any

import yaml
from yaml.constructor import SafeConstructor

from .file_limits import WORLD_FILE, DocumentLimits
from .source_error import WorldFileError

_MAP_TAG = "tag:yaml.org,2002:map"
_SEQ_TAG = "tag:yaml.org,2002:seq"
_NULL_TAG = "tag:yaml.org,2002:null"
_BOOL_TAG = "tag:yaml.org,2002:bool"
_INT_TAG = "tag:yaml.org,2002:int"
_FLOAT_TAG = "tag:yaml.org,2002:float"
_STR_TAG = "tag:yaml.org,2002:str"

_REQUIRED: Any = object()
_EXPONENT_NUMBER = re.compile(r"[-+]?(\d+\.?\d*|\.\d+)[eE][-+]?\d+")
"""A number with an exponent as people write it (`1e12`, `2.5E-3`), which YAML 1.1 reads as text."""


class Node:
    """One YAML value together with the file, line and column where it was written."""

    __slots__ = ("raw", "path")

    def __init__(self, raw: yaml.Node, path: str) -> None:
        self.raw = raw
        self.path = path

    # -- where -----------------------------------------------------------------
    @property
    def line(self) -> int:
        """1-based line where the value starts."""
        return self.raw.start_mark.line + 1

    @property
    def column(self) -> int:
        """1-based column where the value starts."""
        return self.raw.start_mark.column + 1

    def error(self, message: str, *, column: bool = True) -> WorldFileError:
        """An error pointing at this value."""
        return WorldFileError(self.path, self.line, self.column if column else None, message)

    # -- what ------------------------------------------------------------------
    @property
    def is_mapping(self) -> bool:
        return isinstance(self.raw, yaml.MappingNode)

    @property
    def is_sequence(self) -> bool:
        return isinstance(self.raw, yaml.SequenceNode)

    @property
    def is_scalar(self) -> bool:
        return isinstance(self.raw, yaml.ScalarNode)

    @property
    def is_null(self) -> bool:
        return self.is_scalar and self.raw.tag == _NULL_TAG

    @property
    def text(self) -> str:
        """The scalar as written in the file (without quotes), e.g. '3' for `3`."""
        if not self.is_scalar:
            raise self.error(f"expected a single value here, got {self.describe()}")
        return self.raw.value

    @property
    def style(self) -> str | None:
        """The scalar style: None (plain), "'", '"', '|' or '>'."""
        return getattr(self.raw, "style", None)

    def value(self) -> Any:
        """The plain Python value (dicts, lists, numbers, strings)."""
        try:
            return SafeConstructor().construct_object(self.raw, deep=True)
        except (ValueError, KeyError, TypeError, yaml.YAMLError) as err:
            raise self.error(
                f"cannot read this value ({err}); remove the '!!' tag or fix the value"
            ) from None

    def _scalar_value(self) -> Any:
        """The constructed scalar, or None when its tag does not fit its text (e.g. `!!int abc`)."""
        try:
            return SafeConstructor().construct_object(self.raw, deep=True)
        except (ValueError, KeyError, yaml.YAMLError):
            return None

    def describe(self) -> str:
        """How the value reads in a message: 'ten', nothing, a list, a mapping."""
        if self.is_mapping:
            return "a mapping"
        if self.is_sequence:
            return "a list"
        if self.is_null:
            return "nothing"
        return repr(self.raw.value)

    # -- typed reads -------------------------------------------------------------
    def as_number(self, name: str, unit: str = "", example: str | None = None) -> float:
        """A finite int or float; `unit` goes into the message ('cm', 'degrees')."""
        tag = self.raw.tag if self.is_scalar else None
        if tag in (_INT_TAG, _FLOAT_TAG):
            try:
                number = float(self._scalar_value())
            except (TypeError, OverflowError):
                number = math.inf
            if math.isfinite(number):
                return number
        elif tag == _STR_TAG and self.style is None and _EXPONENT_NUMBER.fullmatch(self.raw.value):
            number = float(self.raw.value)  # `1e12`: YAML 1.1 reads it as text, a person as a number
            if math.isfinite(number):
                return number
        kind = f"a number ({unit})" if unit else "a number"
        raise self.error(f"'{name}' must be {kind}, got {self.describe()}{_write(example)}")

    def as_int(self, name: str, example: str | None = None) -> int:
        """A whole number (a float such as 3.0 is accepted)."""
        number = self.as_number(name, example=example)
        if number != int(number):
            raise self.error(f"'{name}' must be a whole number, got {self.describe()}{_write(example)}")
        return int(number)

    def as_text(self, name: str, example: str | None = None) -> str:
        """A string; numbers and words written without quotes count too, nothing does not."""
        if self.is_scalar and not self.is_null and self.raw.tag != _BOOL_TAG:
            return self.raw.value
        raise self.error(f"'{name}' must be text, got {self.describe()}{_write(example)}")

    def as_bool(self, name: str) -> bool:
        """true or false."""
        if self.is_scalar and self.raw.tag == _BOOL_TAG:
            value = self._scalar_value()
            if value is not None:
                return bool(value)
        raise self.error(f"'{name}' must be true or false, got {self.describe()}")

    def as_list(self, name: str, example: str | None = None) -> list[Node]:
        """The items of a YAML list (nothing reads as an empty list)."""
        if self.is_null:
            return []
        if not self.is_sequence:
            raise self.error(f"'{name}' must be a list, got {self.describe()}{_write(example)}")
        return [Node(item, self.path) for item in self.raw.value]

    def as_fields(self, name: str, allowed: Iterable[str], example: str | None = None) -> Fields:
        """The value as a mapping whose keys must be among `allowed` (nothing reads as empty)."""
        if not (self.is_mapping or self.is_null):
            raise self.error(
                f"'{name}' must be a mapping of 'key: value' lines, got {self.describe()}{_write(example)}"
            )
        return Fields(self, f"'{name}'", allowed)

    def as_numbers(self, name: str, count: int, unit: str = "", example: str | None = None) -> list[float]:
        """A list of exactly `count` numbers, e.g. `[3, 5]`."""
        items = self.as_list(name, example)
        if len(items) != count:
            raise self.error(
                f"'{name}' must be a list of {count} numbers, got {len(items)} items{_write(example)}"
            )
        return [item.as_number(name, unit, example) for item in items]


class Fields:
    """A YAML mapping read key by key; unknown keys are refused with the allowed ones listed."""

    def __init__(self, node: Node, where: str, allowed: Iterable[str] | None) -> None:
        self.node = node
        self.where = where
        self._keys: dict[str, Node] = {}
        self._values: dict[str, Node] = {}
        if node.is_null:
            return
        for key_raw, value_raw in node.raw.value:
            key = Node(key_raw, node.path)
            if not key.is_scalar or key.is_null:
                raise key.error(f"a key in {where} must be a plain word, got {key.describe()}")
            name = key.text
            if name in self._keys:
                first = self._keys[name].line
                raise key.error(f"key '{name}' appears twice in {where} (first on line {first}); keep one")
            self._keys[name] = key
            self._values[name] = Node(value_raw, node.path)
        if allowed is not None:
            self.check_keys(allowed)

    def check_keys(self, allowed: Iterable[str]) -> None:
        """Refuse keys not in `allowed`, suggesting the nearest allowed one."""
        allowed = list(allowed)
        for name, key in self._keys.items():
            if name not in allowed:
                close = difflib.get_close_matches(name, allowed, n=1)
                hint = f"did you mean '{close[0]}'? " if close else ""
                listed = ", ".join(allowed)
                raise key.error(f"unknown key '{name}' in {self.where}; {hint}allowed keys: {listed}")

    def __contains__(self, name: str) -> bool:
        return name in self._values

    def __iter__(self) -> Iterator[str]:
        return iter(self._values)

    def __len__(self) -> int:
        return len(self._values)

    def items(self) -> list[tuple[Node, Node]]:
        """(key node, value node) pairs in file order."""
        return [(self._keys[name], self._values[name]) for name in self._values]

    def key(self, name: str) -> Node:
        """The node of the key itself (for errors that point at the key)."""
        return self._keys[name]

    def get(self, name: str) -> Node | None:
        """The value of an optional key, or None when it is not written."""
        return self._values.get(name)

    def require(self, name: str, example: str) -> Node:
        """The value of a required key; `example` is a line to suggest, e.g. 'cell_cm: 10'."""
        node = self._values.get(name)
        if node is None:
            raise self.node.error(f"missing key '{name}' in {self.where}; add e.g. `{example}`", column=False)
        return node

    def number(
        self, name: str, default: Any = _REQUIRED, unit: str = "", example: str | None = None
    ) -> float:
        """A number under `name` (required unless a default is given)."""
        node = self._lookup(name, default, example or f"{name}: 10")
        return default if node is None else node.as_number(name, unit, example)

    def integer(self, name: str, default: Any = _REQUIRED, example: str | None = None) -> int:
        """A whole number under `name`."""
        node = self._lookup(name, default, example or f"{name}: 1")
        return default if node is None else node.as_int(name, example)

    def text(self, name: str, default: Any = _REQUIRED, example: str | None = None) -> str:
        """Text under `name`."""
        node = self._lookup(name, default, example or f"{name}: ...")
        return default if node is None else node.as_text(name, example)

    def boolean(self, name: str, default: Any = _REQUIRED) -> bool:
        """true/false under `name`."""
        node = self._lookup(name, default, f"{name}: true")
        return default if node is None else node.as_bool(name)

    def _lookup(self, name: str, default: Any, example: str) -> Node | None:
        if default is _REQUIRED:
            return self.require(name, example)
        return self._values.get(name)


def load_yaml_text(text: str, path: str = "<string>", limits: DocumentLimits = WORLD_FILE) -> Node:
    """Compose YAML text into a Node tree; syntax errors become WorldFileError with the line.

    The text is held to `limits` (file_limits.py) while it is composed, before anything is built from it:
    its length, and its nodes, characters and depth as its aliases expand, so neither a deeply nested
    file nor a small file of anchors that stands for a huge one gets further than its first excess."""
    if len(text) > limits.chars:
        raise WorldFileError(path, None, None, _too_long(len(text), limits))
    loader = _BoundedLoader(text, path, limits)
    try:
        raw = loader.get_single_node()
    except yaml.MarkedYAMLError as err:
        raise _syntax_error(err, path) from None
    except yaml.YAMLError as err:
        raise WorldFileError(path, None, None, f"this is not readable YAML text ({err})") from None
    finally:
        loader.dispose()
    if raw is None:
        raise WorldFileError(path, 1, None, "the file is empty; write its keys, e.g. `title: My world`")
    return Node(raw, path)


class _BoundedLoader(yaml.SafeLoader):
    """PyYAML's safe loader whose composer counts as it goes: depth (its composing is recursive, so a
    deep file would end in RecursionError), and nodes and characters with each alias counted as often
    as it is used (its aliases share one node, so a bomb costs nothing until something walks it)."""

    def __init__(self, text: str, path: str, limits: DocumentLimits) -> None:
        super().__init__(text)
        self._path = path
        self._limits = limits
        self._depth = 0
        self._nodes = 0
        self._chars = 0
        self._sizes: dict[int, tuple[int, int]] = {}  # id of an anchored node -> (nodes, chars) it expands to

    def compose_node(self, parent, index):  # noqa: ANN001, ANN201 (PyYAML's signature)
        mark = self.peek_event().start_mark
        if self.check_event(yaml.AliasEvent):
            node = super().compose_node(parent, index)
            size = self._sizes.get(id(node))
            if size is None:
                raise self._refuse(mark, "an alias is used inside the value its anchor names (a loop)")
            self._count(size[0], size[1], mark)
            return node
        anchored = self.peek_event().anchor is not None
        if self._depth >= self._limits.depth:
            raise self._refuse(
                mark,
                f"values nested more than {self._limits.depth} deep; a {self._limits.kind} needs no more "
                "than a few levels (docs/world-files.md, Limits)",
            )
        nodes_before, chars_before = self._nodes, self._chars
        self._depth += 1
        try:
            node = super().compose_node(parent, index)
        finally:
            self._depth -= 1
        self._count(1, len(node.value) if isinstance(node, yaml.ScalarNode) else 0, mark)
        if anchored:
            self._sizes[id(node)] = (self._nodes - nodes_before, self._chars - chars_before)
        return node

    def _count(self, nodes: int, chars: int, mark: yaml.Mark) -> None:
        self._nodes += nodes
        self._chars += chars
        limits = self._limits
        if self._nodes > limits.nodes:
            raise self._refuse(
                mark,
                f"the {limits.kind} holds more than {limits.nodes:,} values (aliases counted each time they "
                "are used); a "
                f"{limits.kind} needs far fewer: write it out plainly, without anchors and aliases that repeat "
                "big parts (docs/world-files.md, Limits)",
            )
        if self._chars > limits.chars:
            raise self._refuse(
                mark,
                f"the {limits.kind}'s text, with its aliases written out, is more than {limits.chars:,} "
                "characters; write it out plainly, without anchors and aliases that repeat big parts "
                "(docs/world-files.md, Limits)",
            )

    def _refuse(self, mark: yaml.Mark, message: str) -> WorldFileError:
        return WorldFileError(self._path, mark.line + 1, mark.column + 1, message)


def _too_long(size: int, limits: DocumentLimits) -> str:
    return (
        f"the {limits.kind} is {size:,} characters long, more than the {limits.chars:,} a {limits.kind} may "
        "be (docs/world-files.md, Limits); is this the right file?"
    )


def read_text_file(path: str | Path, limits: DocumentLimits = WORLD_FILE) -> str:
    """A file's text as an editor on any system may have saved it: UTF-8 with or without a BOM (or UTF-16
    with one), with Windows, Mac or Unix line endings (each a plain "\\n" in the text, so lines and columns
    count as an editor counts them).  A missing, unreadable, non-UTF-8 file, one that is not a plain file
    (a device, a pipe) or one longer than `limits.chars` bytes is a WorldFileError; no more than that is
    read."""
    try:
        # a pipe would block an ordinary open until something writes to it: open without waiting, then look
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0))
        with open(fd, "rb") as file:
            if not stat.S_ISREG(os.fstat(file.fileno()).st_mode):
                raise WorldFileError(
                    str(path), None, None, "this is not a plain file; give the path of a .yaml file"
                )
            data = file.read(limits.chars + 1)
    except FileNotFoundError:
        raise WorldFileError(str(path), None, None, "no such file; check the name and folder") from None
    except IsADirectoryError:
        raise WorldFileError(
            str(path), None, None, "this is a folder; give the path of a .yaml file"
        ) from None
    except OSError as err:
        raise WorldFileError(str(path), None, None, f"cannot read the file: {err.strerror}") from None
    if len(data) > limits.chars:
        raise WorldFileError(
            str(path),
            None,
            None,
            f"the {limits.kind} is more than {limits.chars:,} bytes, the most a {limits.kind} may be "
            "(docs/world-files.md, Limits); is this the right file?",
        )
    return decode_text(data, str(path))


def decode_text(data: bytes, path: str = "<string>") -> str:
    """The text of a YAML file's bytes (see read_text_file); `path` names the file in errors."""
    for bom, encoding in (
        (codecs.BOM_UTF8, "utf-8"),
        (codecs.BOM_UTF16_LE, "utf-16-le"),
        (codecs.BOM_UTF16_BE, "utf-16-be"),
    ):
        if data.startswith(bom):
            data, codec = data[len(bom) :], encoding
            break
    else:
        codec = "utf-8"
    try:
        text = data.decode(codec)
    except UnicodeDecodeError as err:
        lines = _one_newline(data[: err.start].decode(codec, "replace")).split("\n")
        raise WorldFileError(
            path,
            len(lines),
            len(lines[-1]) + 1,
            f"byte 0x{data[err.start]:02x} is not {codec[:6].upper()} text (the file was saved in another "
            "encoding, e.g. Windows' cp1252); save the file as UTF-8 (in Notepad: File, Save as, "
            "Encoding: UTF-8)",
        ) from None
    return _one_newline(text)


def _one_newline(text: str) -> str:
    """Windows' "\\r\\n" and old Macs' "\\r" line endings as "\\n"."""
    return text.replace("\r\n", "\n").replace("\r", "\n")


def written_path(text: str) -> Path:
    """A path as a file written on any system gives it: '\\' separates folders as '/' does, so
    `robots\\my bot.yaml`, written on Windows, names the same file on Linux and macOS."""
    return Path(text.replace("\\", "/"))


def foreign_path_hint(text: str) -> str:
    """A hint for a path that is absolute only on another system (`C:\\Users\\...` read on Linux, `/home/...`
    on Windows), else ''."""
    if Path(text).is_absolute() or not (PureWindowsPath(text).is_absolute() or text.startswith("/")):
        return ""
    return (
        f"; '{text}' is a path on another computer: put the file beside this one (or in a folder "
        "beside it) and write its path from here, e.g. `robots/my-bot.yaml`"
    )


def _syntax_error(err: yaml.MarkedYAMLError, path: str) -> WorldFileError:
    mark = err.problem_mark or err.context_mark
    line = mark.line + 1 if mark is not None else None
    column = mark.column + 1 if mark is not None else None
    problem = err.problem or "cannot read this"
    if err.context and err.context_mark is not None and err.context_mark is not mark:
        problem = f"{problem} ({err.context} on line {err.context_mark.line + 1})"
    if "'\\t'" in problem:
        hint = "indent with spaces, not tabs"
    elif "mapping values are not allowed" in problem:
        hint = "check the indentation, and put quotes around a value that contains ': '"
    elif "escape character" in problem:
        hint = (
            "in \"double quotes\" a backslash starts an escape such as \\n; write a path with '/' instead "
            "of '\\', or in 'single quotes'"
        )
    elif "expected a single document" in problem:
        hint = "a world file holds one document; remove the extra '---' line"
    else:
        hint = "check the indentation, and put quotes around text that starts with '#', '[', '{', '*' or '&'"
    return WorldFileError(path, line, column, f"YAML syntax error: {problem}; {hint}")


def _write(example: str | None) -> str:
    return f"; write e.g. `{example}`" if example else ""
