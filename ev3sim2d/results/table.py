"""A small table of named columns (numpy arrays of one length), without pandas.

`pandas.DataFrame(table.columns)` makes a DataFrame of it when pandas is at hand; in Jupyter it shows
itself as an HTML table, elsewhere as aligned text; `to_csv` writes it for a spreadsheet.
"""

from __future__ import annotations

import csv
import html
import io
from pathlib import Path

import numpy as np

from .output_files import write_file

SHOWN_ROWS = 12
"""Rows shown (half from the start, half from the end) when a long table prints itself."""


class Table:
    """Named columns of equal length; `table["x_cm"]` is a column, `len(table)` the rows."""

    def __init__(self, columns: dict[str, np.ndarray]) -> None:
        lengths = {len(values) for values in columns.values()}
        if len(lengths) > 1:
            raise ValueError(f"columns of different lengths: {sorted(lengths)}")
        self.columns = {name: np.asarray(values) for name, values in columns.items()}

    def __len__(self) -> int:
        return len(next(iter(self.columns.values()), ()))

    def __getitem__(self, name: str) -> np.ndarray:
        return self.columns[name]

    def rows(self) -> list[tuple]:
        """The rows, each a tuple in column order."""
        return list(zip(*self.columns.values(), strict=True))

    def to_csv(self, path: str | Path) -> None:
        """Write the table as CSV (UTF-8, a header row)."""
        text = io.StringIO(newline="")
        writer = csv.writer(text)
        writer.writerow(self.columns)
        writer.writerows([[_cell(v) for v in row] for row in self.rows()])
        write_file(path, text.getvalue())

    def _shown(self) -> list[tuple | None]:
        rows = self.rows()
        if len(rows) <= SHOWN_ROWS:
            return list(rows)
        half = SHOWN_ROWS // 2
        return [*rows[:half], None, *rows[-half:]]

    def __str__(self) -> str:
        header = list(self.columns)
        body = [
            [_cell(v) for v in row] if row is not None else ["..."] * len(header) for row in self._shown()
        ]
        widths = [max(len(h), *(len(r[i]) for r in body)) if body else len(h) for i, h in enumerate(header)]
        lines = ["  ".join(h.rjust(w) for h, w in zip(header, widths, strict=True))]
        lines += ["  ".join(c.rjust(w) for c, w in zip(r, widths, strict=True)) for r in body]
        return "\n".join(lines)

    def __repr__(self) -> str:
        return f"Table({len(self)} rows: {', '.join(self.columns)})"

    def _repr_html_(self) -> str:
        head = "".join(f"<th>{html.escape(name)}</th>" for name in self.columns)
        body = []
        for row in self._shown():
            if row is None:
                body.append(f'<tr><td colspan="{len(self.columns)}">...</td></tr>')
            else:
                body.append("<tr>" + "".join(f"<td>{html.escape(_cell(v))}</td>" for v in row) + "</tr>")
        return f"<table><tr>{head}</tr>{''.join(body)}</table><p>{len(self)} rows</p>"


def _cell(value) -> str:
    if isinstance(value, float | np.floating):
        return "" if np.isnan(value) else f"{float(value):.6g}"
    return str(value)
