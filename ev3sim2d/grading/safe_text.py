"""Text from a student's program, made safe to show: in a terminal, in XML, in a spreadsheet.

A program chooses its own error messages and file names, so it could put terminal escape sequences
into a teacher's terminal, characters XML forbids into the JUnit report (a parser then rejects it
whole), or a formula into the class spreadsheet.  Every report passes such text through here.
"""

from __future__ import annotations

import re

# C0 and C1 controls but tab and newline, DEL, and what XML 1.0 forbids (lone surrogates, U+FFFE/F)
_UNSAFE = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f\ud800-\udfff\ufffe\uffff]")
_FORMULA_START = ("=", "+", "-", "@", "\t", "\r")


def printable(text: str) -> str:
    """The text with each control character written as a visible escape (\\x1b), tabs and newlines kept."""
    return _UNSAFE.sub(lambda m: ascii(m.group())[1:-1], str(text))


def one_line(text: str) -> str:
    """printable(text) on one line (newlines shown as \\n)."""
    return printable(text).replace("\n", "\\n")


def spreadsheet_cell(text: str) -> str:
    """A CSV cell no spreadsheet reads as a formula (a leading = + - @ gets a quote before it)."""
    cell = one_line(text)
    return "'" + cell if cell.startswith(_FORMULA_START) else cell
