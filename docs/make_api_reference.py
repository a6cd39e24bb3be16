"""Write docs/api.md, the Python API's reference, from the docstrings and signatures of its public names.

    .venv/bin/python docs/make_api_reference.py        # rewrite docs/api.md
    .venv/bin/python docs/make_api_reference.py --check   # exit 1 if docs/api.md is out of date

tests/api/test_api_reference.py runs the check, so the reference always says what the code does.
"""

from __future__ import annotations

import inspect
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

import ev3sim2d  # noqa: E402
from ev3sim2d.render import plot as plot_module  # noqa: E402
from ev3sim2d.results.series import RobotSeries  # noqa: E402

TARGET = HERE / "api.md"
SECTIONS = [
    ("Running programs", [ev3sim2d.simulate, ev3sim2d.SimulationResult]),
    ("Worlds", [ev3sim2d.World, ev3sim2d.load_maze]),
    ("Timelines and tables", [RobotSeries, ev3sim2d.Table, plot_module.plot]),
]


def _doc(thing) -> str:
    return inspect.cleandoc(thing.__doc__ or "").strip()


def _signature(name: str, thing) -> str:
    try:
        return f"{name}{inspect.signature(thing)}"
    except (TypeError, ValueError):
        return name


def _members(cls) -> list[tuple[str, object]]:
    """Public methods and properties the class itself defines, in source order."""
    found = []
    for name, value in vars(cls).items():
        if name.startswith("_") and name != "_repr_html_":
            continue
        if isinstance(value, property | classmethod | staticmethod) or inspect.isfunction(value):
            found.append((name, value))
    return found


def _entry(thing) -> list[str]:
    name = thing.__name__
    if inspect.isclass(thing):
        lines = [f"### class `{name}`", "", _doc(thing), ""]
        for member, value in _members(thing):
            if isinstance(value, property):
                lines += [f"- **`.{member}`** (property): {_doc(value)}"]
                continue
            function = value.__func__ if isinstance(value, classmethod | staticmethod) else value
            signature = _signature(member, function).replace("(self, ", "(").replace("(self)", "()")
            signature = signature.replace("(cls, ", "(").replace("(cls)", "()")
            doc = _doc(function) or "(shows the result in Jupyter)"
            lines += [f"- **`{signature}`**", "", "  " + doc.replace("\n", "\n  ")]
        return lines + [""]
    return [f"### `{_signature(name, thing)}`", "", _doc(thing), ""]


def reference() -> str:
    lines = [
        "# ev3sim2d Python API",
        "",
        "<!-- written by docs/make_api_reference.py from the docstrings; do not edit by hand -->",
        "",
        _doc(ev3sim2d),
        "",
        "A worked example: [python-api.ipynb](python-api.ipynb).",
        "",
    ]
    for title, things in SECTIONS:
        lines += [f"## {title}", ""]
        for thing in things:
            lines += _entry(thing)
    return "\n".join(lines).rstrip() + "\n"


def main(argv: list[str]) -> int:
    text = reference()
    if "--check" in argv:
        if not TARGET.is_file() or TARGET.read_text(encoding="utf-8") != text:
            print(
                f"{TARGET} is out of date: run .venv/bin/python docs/make_api_reference.py", file=sys.stderr
            )
            return 1
        return 0
    TARGET.write_text(text, encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
