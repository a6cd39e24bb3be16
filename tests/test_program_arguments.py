"""A program's own command line: `ev3sim2d run prog.py -- 26 1 1.5` is `python3 prog.py 26 1 1.5` on a
brick (from a shell over SSH, or a shell script that passes tuning values): sys.argv[0] is the
program's name in its folder (its working folder: brickrun --directory), the rest as given, strings."""

import pytest

from ev3sim2d import cli

PRINTS_ARGV = "import sys\nprint(sys.argv)\n"


@pytest.fixture
def program(tmp_path, monkeypatch):
    (tmp_path / "prog.py").write_text(PRINTS_ARGV)
    monkeypatch.chdir(tmp_path)
    return "prog.py"


def _printed(out: str) -> list[str]:
    return [line.split("] ", 1)[1] for line in out.splitlines() if line.startswith("[")]


def test_arguments_after_two_dashes_are_the_programs(program, capsys):
    assert cli.main(["run", program, "--time", "1", "--", "26", "1", "1.5"]) == 0
    assert _printed(capsys.readouterr().out) == ["['prog.py', '26', '1', '1.5']"]


def test_options_after_two_dashes_are_the_programs_not_ours(program, capsys):
    """`--time 9` after -- is the program's (a tuning value named like an option), not the run's."""
    assert cli.main(["run", program, "--time", "1", "--", "--time", "9", "-v"]) == 0
    assert _printed(capsys.readouterr().out) == ["['prog.py', '--time', '9', '-v']"]


def test_without_arguments_argv_is_the_programs_name(tmp_path, monkeypatch, capsys):
    (tmp_path / "robot").mkdir()
    (tmp_path / "robot" / "prog.py").write_text(PRINTS_ARGV)
    monkeypatch.chdir(tmp_path)
    assert cli.main(["run", "robot/prog.py", "--time", "1"]) == 0
    assert _printed(capsys.readouterr().out) == ["['prog.py']"]


def test_the_arguments_are_given_to_every_program(tmp_path, monkeypatch, capsys):
    for name in ("a.py", "b.py"):
        (tmp_path / name).write_text(PRINTS_ARGV)
    monkeypatch.chdir(tmp_path)
    status = cli.main(["run", "a.py", "b.py", "--maze", "sumo", "--time", "1", "--", "fast"])
    assert status == 0
    printed = sorted(_printed(capsys.readouterr().out))
    assert printed == ["['a.py', 'fast']", "['b.py', 'fast']"]


def test_two_dashes_keep_their_meaning_for_other_commands(tmp_path, capsys):
    """Only run and live pass what follows -- on; elsewhere it is argparse's end of options."""
    with pytest.raises(SystemExit):
        cli.main(["mazes", "--", "--nonsense"])
    assert "unrecognized arguments: -- --nonsense" in capsys.readouterr().err
