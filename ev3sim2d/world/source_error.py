"""The one error a user's maze or robot file can cause: where it is wrong and what to write instead."""

from __future__ import annotations


class WorldFileError(Exception):
    """A mistake in a world or robot file, shown as `path:line:column: message`."""

    def __init__(
        self, path: str, line: int | None = None, column: int | None = None, message: str = ""
    ) -> None:
        super().__init__(path, line, column, message)
        self.path = str(path)
        self.line = line
        self.column = column
        self.message = message

    def __str__(self) -> str:
        where = self.path
        if self.line is not None:
            where += f":{self.line}"
            if self.column is not None:
                where += f":{self.column}"
        return f"{where}: {self.message}"
