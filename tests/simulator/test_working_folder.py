"""A program works in (a copy of) its own folder, as on a brick.

Brickman starts a program with `brickrun --directory=<the program's folder>` (brickman's
src/file_browser.vala, and brickrun's --directory option: "the working directory of the program"),
so a program on an EV3 opens its data files by relative paths and writes its logs beside itself.
A brick here works in a copy of what it may read, made in its scratch folder: nothing it writes
outlasts the run unless `ev3sim2d run` keeps it (the files it made beside itself, never over a file),
nothing outside it is readable, and the copy is bounded.
"""

import os
import tempfile
import textwrap

import pytest

from ev3sim2d import cli
from ev3sim2d.simulator import working_folder
from ev3sim2d.simulator.run import run_programs
from ev3sim2d.simulator.working_folder import make_working_folder
from ev3sim2d.simulator.zygote import BrickZygote
from tests.inline_world import arena

READS_AND_WRITES = """
    import os
    with open("data/gains.txt") as f:                      # its own data, by a relative path
        print("gains", f.read().split())
    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, "log.csv"), "w") as f:   # a log beside itself
        f.write("t,x\\n0,1\\n")
    os.makedirs("logs", exist_ok=True)
    with open("logs/run1.txt", "w") as f:
        f.write("ran")
    print("read back", open("log.csv").read().splitlines()[-1], open("logs/run1.txt").read())
    import tuning                                          # a module beside it
    print("tuning", tuning.KP)
"""


def _program_folder(tmp_path, source=READS_AND_WRITES):
    folder = tmp_path / "robot"
    (folder / "data").mkdir(parents=True)
    (folder / "data" / "gains.txt").write_text("1.5 0.02\n")
    (folder / "tuning.py").write_text("KP = 1.5\n")
    program = folder / "prog.py"
    program.write_text(textwrap.dedent(source))
    return folder, program


def _printed(result):
    return [line.text for line in result.trace.output]


@pytest.fixture(scope="module")
def zygote():
    z = BrickZygote()
    yield z
    z.close()


@pytest.mark.parametrize(
    "start",
    ["fresh", pytest.param("zygote", marks=pytest.mark.needs_linux("fork", "unix_sockets")), "portable"],
)
def test_a_program_reads_its_data_and_writes_its_logs_beside_itself(tmp_path, request, monkeypatch, start):
    """brickrun --directory: relative paths are the program's folder (fails on a brick working in an
    empty scratch folder, with the program's folder read-only: FileNotFoundError, then PermissionError)."""
    if start == "portable":
        monkeypatch.setenv("EV3SIM2D_PORTABLE", "1")
    folder, program = _program_folder(tmp_path)
    before = sorted(p.relative_to(folder) for p in folder.rglob("*"))
    zygote = request.getfixturevalue("zygote") if start == "zygote" else None
    result = run_programs([program], arena(), time_limit_s=5, hang_after_s=2, zygote=zygote)
    assert result.status == "finished", (result.reason, result.error)
    assert _printed(result) == ["gains ['1.5', '0.02']", "read back 0,1 ran", "tuning 1.5"]
    # what it wrote was the copy's: the student's folder is as it was, and the run left nothing behind
    assert sorted(p.relative_to(folder) for p in folder.rglob("*")) == before
    assert result.notes == []


def test_an_error_names_the_program_and_its_modules_as_the_student_named_them(tmp_path, monkeypatch):
    """The traceback shows the files the student has, not the copy the brick worked in."""
    folder, program = _program_folder(tmp_path, "import tuning\ntuning.go()\n")
    (folder / "tuning.py").write_text("def go():\n    raise ValueError('too fast')\n")
    monkeypatch.chdir(folder)
    result = run_programs(["prog.py"], arena(), time_limit_s=5, hang_after_s=2)
    assert result.status == "error"
    assert result.error["file"] == "prog.py" and result.error["line"] == 2
    assert 'File "tuning.py", line 2, in go' in result.error["traceback"]
    assert "ev3sim2d-brick-" not in result.error["traceback"]


@pytest.mark.needs_linux("symlinks")
def test_a_link_in_the_folder_is_not_followed(tmp_path):
    """The copy is made by the simulator from files a student controls: a link to a file or folder
    elsewhere (a lesson's hidden variants, the teacher's home) is not copied, so not readable."""
    secret = tmp_path / "secret"
    secret.mkdir()
    (secret / "answers.txt").write_text("the hidden variant's walls\n")
    folder, program = _program_folder(
        tmp_path,
        """
        import os
        print(sorted(os.listdir(".")))
        for name in ("answers.txt", "elsewhere/answers.txt"):
            try:
                print(open(name).read())
            except OSError as err:
                print(name, type(err).__name__)
        """,
    )
    (folder / "answers.txt").symlink_to(secret / "answers.txt")
    (folder / "elsewhere").symlink_to(secret)
    result = run_programs([program], arena(), time_limit_s=5, hang_after_s=2)
    assert result.status == "finished", result.reason
    assert _printed(result) == [
        "['data', 'prog.py', 'tuning.py']",
        "answers.txt FileNotFoundError",
        "elsewhere/answers.txt FileNotFoundError",
    ]


def test_a_graded_file_works_in_a_folder_of_its_own(tmp_path):
    """A brick that may read only its program's file (a lesson's own program, a graded file in a class
    folder) gets a folder holding that file only: the other students' files are not in it."""
    folder, program = _program_folder(tmp_path, "import os\nprint(sorted(os.listdir('.')))\n")
    (folder / "someone_else.py").write_text("print('not yours')\n")
    result = run_programs([program], arena(), time_limit_s=5, hang_after_s=2, readable=[[program]])
    assert result.status == "finished", result.reason
    assert _printed(result) == ["['prog.py']"]


def test_a_folder_too_big_to_copy_is_cut_and_the_run_says_so(tmp_path, monkeypatch, capsys):
    """The copy is bounded (files, bytes, depth); what was left out is said, and the program runs."""
    folder, program = _program_folder(tmp_path, "import os\nprint(len(os.listdir('data')))\n")
    for i in range(10):
        (folder / "data" / f"frame{i:02}.bin").write_bytes(b"x" * 100)
    monkeypatch.setattr(working_folder, "MAX_ENTRIES", 6)
    monkeypatch.chdir(tmp_path)
    status = cli.main(["run", "robot/prog.py", "--time", "2", "--maze", "empty"])
    out, err = capsys.readouterr()
    assert status == 0, err
    assert "[   0.000 s] " in out and out.split("] ")[1].strip().isdigit()
    assert int(out.split("] ")[1]) == 3  # prog.py, tuning.py, data/ and 3 of its files: nearest first
    assert (
        "ev3sim2d: note: robot/prog.py: its folder holds more than a brick's copy may (6 files and folders"
        in err
    )
    assert "keep a program in a folder of its own" in err


@pytest.mark.needs_linux("symlinks")
def test_the_copy_keeps_hidden_files_caches_links_and_fifos_out(tmp_path):
    """What the copy holds: regular files and folders, none hidden (.git, .venv), no __pycache__,
    no link, no FIFO (a FIFO would block the simulator that copies it)."""
    folder, program = _program_folder(tmp_path)
    (folder / ".git").mkdir()
    (folder / ".git" / "config").write_text("[core]\n")
    (folder / "__pycache__").mkdir()
    (folder / "__pycache__" / "tuning.cpython-311.pyc").write_bytes(b"\0")
    (folder / "link.txt").symlink_to(folder / "data" / "gains.txt")
    if hasattr(os, "mkfifo"):
        os.mkfifo(folder / "pipe")
    scratch = tmp_path / "scratch"
    scratch.mkdir()
    copy = make_working_folder(scratch, [folder], program)
    copied = sorted(str(p.relative_to(copy.folder)) for p in copy.folder.rglob("*"))
    assert copied == ["data", "data/gains.txt", "prog.py", "tuning.py"]
    assert copy.program == copy.folder / "prog.py" and copy.note is None


def test_the_copy_stops_at_its_depth_and_byte_budget(tmp_path, monkeypatch):
    folder, program = _program_folder(tmp_path)
    deep = folder
    for i in range(working_folder.MAX_DEPTH + 3):
        deep = deep / f"d{i}"
    deep.mkdir(parents=True)
    (deep / "bottom.txt").write_text("too deep")
    (folder / "big.bin").write_bytes(b"x" * 5000)
    monkeypatch.setattr(working_folder, "MAX_BYTES", 4000)
    scratch = tmp_path / "scratch"
    scratch.mkdir()
    copy = make_working_folder(scratch, [folder], program)
    assert not list(copy.folder.rglob("bottom.txt"))
    assert not (copy.folder / "big.bin").exists()
    assert (copy.folder / "prog.py").exists() and (copy.folder / "data" / "gains.txt").exists()
    assert "the files nearest the program were copied first" in copy.note


def test_a_program_in_a_folder_of_thousands_of_files_starts_as_fast_as_one_in_its_own(tmp_path, monkeypatch):
    """A student's program saved in Downloads: the copy takes the nearest files and stops looking, so
    the time it takes does not grow with the folder (it opened and counted every file before)."""
    crowded = tmp_path / "Downloads"
    for i in range(40):
        deep = crowded / f"unpacked{i:02}" / "src"
        deep.mkdir(parents=True)
        for j in range(60):
            (deep / f"file{j}.txt").write_text("x")
    program = crowded / "prog.py"
    program.write_text("print('hi')\n")
    scratch = tmp_path / "scratch"
    scratch.mkdir()
    looked_in = []
    real_scandir = os.scandir
    monkeypatch.setattr(os, "scandir", lambda path: looked_in.append(path) or real_scandir(path))
    copy = make_working_folder(scratch, [crowded], program)
    monkeypatch.undo()
    copied = list(copy.folder.rglob("*"))
    assert len(copied) <= working_folder.MAX_ENTRIES + 1  # (+ the program itself, which always goes)
    assert copy.program.read_text() == "print('hi')\n"
    assert copy.note is not None
    # nearest first: every folder beside the program is there; and the walk stopped once the copy was
    # full: of the 81 folders, the 40 with 60 files each were not all opened (500 entries fit 7 of them)
    assert len([p for p in copy.folder.iterdir() if p.is_dir()]) == 40
    assert len(looked_in) < 1 + 40 + 10


def test_a_temporary_folder_inside_the_programs_folder_is_not_copied(tmp_path, monkeypatch):
    """A program saved in the folder that holds the system's temporary folder (a teacher's home, a
    grading folder with TMPDIR inside it): the copy would copy its own scratch folder, and other
    bricks' scratch folders, until its budget was spent.  They are not the program's files."""
    folder, program = _program_folder(tmp_path, "import os\nprint(sorted(os.listdir('.')))\n")
    temporary = folder / "tmp"
    temporary.mkdir()
    other = temporary / "ev3sim2d-brick-other"  # another brick's scratch folder, running beside it
    other.mkdir()
    (other / "their_program.py").write_text("print('theirs')\n")
    monkeypatch.setattr(tempfile, "tempdir", str(temporary))
    result = run_programs([program], arena(), time_limit_s=5, hang_after_s=2)
    assert result.status == "finished", (result.reason, result.error)
    assert _printed(result) == ["['data', 'prog.py', 'tuning.py']"]
    assert result.notes == []
    assert sorted(p.name for p in temporary.iterdir()) == ["ev3sim2d-brick-other"]  # and cleaned up


# ---------------------------------------------------------------- what `ev3sim2d run` keeps

DATALOG = """
    from pybricks.tools import DataLog
    log = DataLog("t", "x")
    log.log(0, 1)
    with open("notes.txt", "w") as f:
        f.write("ran")
    import os
    os.makedirs("logs", exist_ok=True)
    open("logs/deep.txt", "w").write("not kept: only the top of the folder is")
"""


def test_ev3sim2d_run_keeps_what_the_program_wrote_beside_itself_and_never_overwrites(tmp_path, capsys):
    """On a brick a DataLog's CSV stays beside the program (pybricks tools.py DataLog: a file by a relative
    name, in brickrun's --directory): `ev3sim2d run` keeps the files the program made or changed at the
    top of its folder; a name taken (a second run's log, whose virtual clock gives it the same name) gets a
    number, and nothing there is overwritten."""
    folder, program = _program_folder(tmp_path, DATALOG)
    (folder / "notes.txt").write_text("the student's own notes\n")
    for _ in range(2):
        assert cli.main(["run", str(program), "--maze", "empty", "--time", "2", "--quiet"]) == 0
    logs = sorted((p.name for p in folder.glob("log_*.csv")), key=len)
    assert len(logs) == 2 and logs[1] == logs[0].replace(".csv", "-2.csv")
    assert (folder / logs[0]).read_text() == "t, x\n0, 1\n"  # the firmware's format
    assert (folder / "notes.txt").read_text() == "the student's own notes\n"  # never overwritten
    assert sorted(p.name for p in folder.glob("notes-*.txt")) == ["notes-2.txt", "notes-3.txt"]
    assert not (folder / "logs").exists()
    err = capsys.readouterr().err
    assert f"kept what it wrote beside itself: {logs[0]}" in err and "notes.txt as notes-2.txt" in err


def test_a_grader_or_the_python_api_keeps_nothing(tmp_path):
    """run_programs keeps nothing unless asked (`ev3sim2d run` asks): a class folder a grader runs in,
    and the folder of a program given to simulate(), stay as they were."""
    folder, program = _program_folder(tmp_path, DATALOG)
    before = sorted(p.relative_to(folder) for p in folder.rglob("*"))
    result = run_programs([program], arena(), time_limit_s=2, hang_after_s=2)
    assert result.status == "finished", result.reason
    assert sorted(p.relative_to(folder) for p in folder.rglob("*")) == before


@pytest.mark.needs_linux("symlinks")
def test_a_link_planted_at_a_kept_name_is_not_written_through(tmp_path):
    """Whoever can write into the program's folder may plant a link where the program's file will be kept:
    the file is kept under a free name, and the link's target is untouched."""
    victim = tmp_path / "victim.txt"
    victim.write_text("precious\n")
    folder, program = _program_folder(tmp_path, "open('notes.txt', 'w').write('ran')\n")
    (folder / "notes.txt").symlink_to(victim)
    result = run_programs([program], arena(), time_limit_s=2, hang_after_s=2, keep_written=True)
    assert result.status == "finished", result.reason
    assert victim.read_text() == "precious\n" and (folder / "notes.txt").is_symlink()
    assert (folder / "notes-2.txt").read_text() == "ran"


def test_only_so_many_files_of_so_many_bytes_are_kept(tmp_path, monkeypatch):
    monkeypatch.setattr(working_folder, "KEEP_FILES", 3)
    monkeypatch.setattr(working_folder, "KEEP_BYTES", 100)
    folder, program = _program_folder(
        tmp_path, "for i in range(5):\n    open(f'f{i}.txt', 'w').write('x' * (10 if i else 500))\n"
    )
    result = run_programs([program], arena(), time_limit_s=2, hang_after_s=2, keep_written=True)
    assert sorted(p.name for p in folder.glob("f*.txt")) == ["f1.txt", "f2.txt", "f3.txt"]
    said = " ".join(result.notes)
    assert "f0.txt (larger than 0 MB)" in said and "f4.txt (only the first 3 files" in said
