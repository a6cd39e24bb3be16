"""Adding to an editor's JSON-with-comments file (VS Code's tasks.json, launch.json, settings.json)
without touching what is already in it.

VS Code's files allow `//` and `/* */` comments and trailing commas, and the ones it makes start with a
comment.  What a student (or VS Code) wrote stays as it was, byte for byte: entries are inserted as text,
into the top-level object's array (`add_to_array`) or as a new top-level key (`add_key`); nothing is
parsed and written back.  `parse` reads such a file as VS Code does, and says where it cannot.
"""

from __future__ import annotations

import json
import re

_TOKEN = re.compile(r'"(?:[^"\\\n]|\\.)*"|//[^\n]*|/\*.*?\*/|[{}\[\],:]|[^\s{}\[\],:"/]+|/', re.S)


class JsoncError(ValueError):
    """The file is not JSON with comments: `line` says where."""

    def __init__(self, message: str, line: int) -> None:
        super().__init__(f"line {line}: {message}")
        self.line = line


def parse(text: str):
    """The value of a JSON-with-comments text (comments and trailing commas allowed); JsoncError if not."""
    plain, position = [], 0
    tokens = list(_TOKEN.finditer(text))
    code = [m for m in tokens if not m.group().startswith(("//", "/*"))]
    following = {id(m): n for m, n in zip(code, [*code[1:], None], strict=False)}
    for match in tokens:
        token = match.group()
        plain.append(text[position : match.start()])
        if token.startswith(("//", "/*")) or (
            token == "," and following[id(match)] is not None and following[id(match)].group() in ("}", "]")
        ):
            token = re.sub(r"[^\n]", " ", token)  # (blanked, keeping the lines where they are)
        plain.append(token)
        position = match.end()
    plain.append(text[position:])
    joined = "".join(plain)
    try:
        return json.loads(joined) if joined.strip() else {}
    except json.JSONDecodeError as err:
        raise JsoncError(err.msg, err.lineno) from None


def add_to_array(text: str, key: str, entries: list[dict]) -> str:
    """The text with entries first in the top-level object's array `key` (made if there is none)."""
    if not entries:
        return text
    body = ",\n".join(_indented(entry, 2) for entry in entries)
    opening = _top_level_value(text, key)
    if opening is None:
        return add_key(text, key, entries)
    if text[opening] != "[":
        raise JsoncError(f'"{key}" is not a list', text.count("\n", 0, opening) + 1)
    empty = _next_token(text, opening + 1) == "]"
    return text[: opening + 1] + "\n" + body + _after(text, opening + 1, empty) + text[opening + 1 :]


def add_key(text: str, key: str, value) -> str:
    """The text with `"key": value` first in its top-level object (an empty text: a new object)."""
    start = _object_start(text)
    if start is None:
        return "{\n" + f"    {json.dumps(key)}: {_indented(value, 1).lstrip()}\n" + "}\n"
    empty = _next_token(text, start + 1) == "}"
    entry = f"\n    {json.dumps(key)}: {_indented(value, 1).lstrip()}" + _after(text, start + 1, empty)
    return text[: start + 1] + entry + text[start + 1 :]


def _after(text: str, position: int, empty: bool) -> str:
    """What follows an inserted entry: a comma before what was there, and a line break where none is."""
    return ("" if empty else ",") + ("" if text[position : position + 1].isspace() else "\n")


def _indented(value, levels: int) -> str:
    pad = "    " * levels
    return "\n".join(pad + line for line in json.dumps(value, indent=4, ensure_ascii=False).splitlines())


def _tokens(text: str, start: int = 0):
    """(position, token) of the text's tokens from start, comments left out."""
    for match in _TOKEN.finditer(text, start):
        token = match.group()
        if not (token.startswith("//") or token.startswith("/*")):
            yield match.start(), token


def _next_token(text: str, start: int) -> str | None:
    return next((token for _, token in _tokens(text, start)), None)


def _object_start(text: str) -> int | None:
    first = next(_tokens(text), None)
    if first is None:
        return None
    if first[1] != "{":
        raise JsoncError("the file is not an object ({ ... })", text.count("\n", 0, first[0]) + 1)
    return first[0]


def _top_level_value(text: str, key: str) -> int | None:
    """The position of the first token of the top-level object's value for key, or None."""
    start = _object_start(text)
    if start is None:
        return None
    depth, expecting_key, found = 0, True, False
    for position, token in _tokens(text, start):
        if token in "{[":
            if depth == 1 and found:
                return position
            depth += 1
        elif token in "}]":
            depth -= 1
            if depth == 0:
                return None
        elif depth == 1:
            if found and token != ":":
                return position
            if expecting_key and token.startswith('"'):
                found = json.loads(token) == key
                expecting_key = False
            elif token == ",":
                expecting_key = True
    return None
