"""A program runs with the shim its imports ask for (ev3sim2d/brick/program_kind.py): python-ev3dev2's or
Pybricks', never both, as no EV3 runs both; and our `pybricks` never hides the one a student installed
for their editor."""

import sys

from ev3sim2d.brick.program_kind import ProgramKind, shim_imports


def imports_of(source: str) -> list[tuple[str, int]]:
    return shim_imports(compile(source, "prog.py", "exec"))


def test_the_imports_are_read_from_every_function_of_the_file_with_their_lines():
    source = (
        "import os\n"
        "from ev3dev2.motor import LargeMotor\n"
        "def later():\n"
        "    class Inner:\n"
        "        def go(self):\n"
        "            import pybricks.tools as tools\n"
        "    return [__import__('json') for _ in ()]\n"
        "from . import sibling\n"
        "import pybricks_helper, ev3dev2x\n"
    )
    assert imports_of(source) == [("ev3dev2", 2), ("pybricks", 6)]


def test_the_first_file_decides_and_a_file_of_the_other_kind_is_refused_with_both_places():
    kind = ProgramKind()
    assert (
        kind.check(compile("from pybricks.hubs import EV3Brick\n", "/p/main.py", "exec"), "/p/main.py")
        is None
    )
    assert kind.shim == "pybricks"
    line, message = kind.check(compile("\n\nimport ev3dev2.motor\n", "/p/helper.py", "exec"), "/p/helper.py")
    assert line == 3
    assert "helper.py, line 3, imports ev3dev2" in message and "main.py, line 1, imports pybricks" in message


def test_a_program_that_imports_both_ends_at_once_at_the_second_import(run):
    result = run("""
        print("started")
        from pybricks.parameters import Port
        from ev3dev2.motor import OUTPUT_B
        print("mixed")
    """)
    assert result.status == "error"
    assert result.error["type"] == "ImportError"
    assert result.error["line"] == 4 and result.error["t_s"] == 0.0
    assert (
        "imports ev3dev2" in result.error["message"] and "line 3, imports pybricks" in result.error["message"]
    )
    assert "docs/pybricks.md" in result.error["message"]
    assert [o.text for o in result.trace.output] == []  # refused before its first line ran


def test_a_helper_module_of_the_other_kind_is_refused_where_it_is_imported(run, tmp_path):
    (tmp_path / "moves.py").write_text("from ev3dev2.motor import LargeMotor, OUTPUT_B\n")
    result = run("""
        from pybricks.parameters import Port
        print("before")
        import moves
    """)
    assert result.status == "error" and result.error["type"] == "ImportError"
    assert result.error["line"] == 4
    assert "moves.py, line 1, imports ev3dev2" in result.error["message"]
    assert [o.text for o in result.trace.output] == ["before"]


def test_programs_of_either_kind_run_with_their_own_shim(run):
    ev3dev2 = run("from ev3dev2.motor import OUTPUT_B\nprint(OUTPUT_B)")
    pybricks = run("from pybricks.parameters import Color\nprint(Color.RED)")
    assert ev3dev2.status == pybricks.status == "finished"
    assert (ev3dev2.trace.output[0].text, pybricks.trace.output[0].text) == ("ev3-ports:outB", "Color.RED")


def test_a_pybricks_installed_beside_for_the_editor_is_not_shadowed(run, tmp_path, monkeypatch):
    """The `pybricks` package on PyPI (LEGO's stubs, for completion in editors) stays the student's own
    in their Python: ours is only on a brick's path, and a brick uses ours."""
    for name in [m for m in sys.modules if m == "pybricks" or m.startswith("pybricks.")]:
        monkeypatch.delitem(sys.modules, name)
    stubs = tmp_path / "site" / "pybricks"
    stubs.mkdir(parents=True)
    (stubs / "__init__.py").write_text("STUBS = True\n")
    (stubs / "parameters.py").write_text("STUBS = True\n")
    monkeypatch.syspath_prepend(str(tmp_path / "site"))
    import pybricks.parameters

    assert pybricks.parameters.STUBS
    result = run("""
        import pybricks.parameters
        print(hasattr(pybricks.parameters, "STUBS"), pybricks.parameters.Port.A)
    """)
    assert result.trace.output[0].text == "False Port.A"
    assert sys.modules["pybricks.parameters"] is pybricks.parameters
