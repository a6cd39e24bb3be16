"""Text from a student's program, made safe to show: in a terminal, in XML, in a spreadsheet.

A program chooses its own error messages and file names, so it could put terminal escape sequences
into a teacher's terminal (a window title, the clipboard, a cleared screen, a line rewritten by a lone
carriage return), characters XML forbids into the JUnit report (a parser then rejects it whole), or a
formula into the class spreadsheet.  Every report passes such text through here, and so does every
front door that shows what a program printed or raised (`run`, `serve`, `join`).  Escaped: C0 controls
(tab and newline kept), DEL, C1 controls, what XML 1.0 forbids, and the invisible characters that reorder
or hide text (BiDi embeddings, overrides, isolates and marks, zero-width characters, line and paragraph
separators): each is shown as its Python escape (\x1b, \u202e).
"""

from __future__ import annotations

import re

# C0 and C1 controls but tab and newline, DEL, what XML 1.0 forbids (lone surrogates, U+FFFE/F), and the
# format characters that reorder or hide text: ALM, zero-width and direction marks, line and paragraph
# separators, BiDi embeddings and overrides, invisible operators and isolates, the BOM, interlinear annotations
_UNSAFE = re.compile(
    "[\x00-\x08\x0b-\x1f\x7f-\x9f\u061c\u180e\u200b-\u200f\u2028-\u202e\u2060-\u206f"
    "\ufeff\ufff9-\ufffb\ud800-\udfff\ufffe\uffff]"
)
_FORMULA_START = ("=", "+", "-", "@", "\t", "\r")


def printable(text: str) -> str:
    """The text with each unsafe character written as a visible escape (\\x1b), tabs and newlines kept."""
    return _UNSAFE.sub(lambda m: ascii(m.group())[1:-1], str(text))


def one_line(text: str) -> str:
    """printable(text) on one line (newlines shown as \\n)."""
    return printable(text).replace("\n", "\\n")


def spreadsheet_cell(text: str) -> str:
    """A CSV cell no spreadsheet reads as a formula (a leading = + - @ gets a quote before it)."""
    cell = one_line(text)
    return "'" + cell if cell.startswith(_FORMULA_START) else cell
