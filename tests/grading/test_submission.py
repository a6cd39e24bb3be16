"""Finding what was handed in: a file, a student's folder, or a class folder."""

from pathlib import Path

from ev3sim2d.grading.submission import find_submissions

from .lesson_maker import GOOD, write_program


def test_a_file_is_one_submission(tmp_path):
    prog = write_program(tmp_path, "alice.py", GOOD)
    [found] = find_submissions([prog])
    assert found.entry == prog and found.problem is None


def test_a_folder_with_main_py_is_one_students_submission(tmp_path):
    write_program(tmp_path / "bob", "main.py", "import helper\n")
    write_program(tmp_path / "bob", "helper.py", "X = 1\n")
    [found] = find_submissions([tmp_path / "bob"])
    assert found.entry.name == "main.py"
    assert sorted(p.name for p in found.files) == ["helper.py", "main.py"]


def test_a_class_folder_holds_one_submission_per_file_or_folder(tmp_path):
    write_program(tmp_path, "alice.py", GOOD)
    write_program(tmp_path / "bob", "main.py", GOOD)
    write_program(tmp_path / "carol", "my_robot.py", GOOD)
    write_program(tmp_path / "dave", "one.py", GOOD)
    write_program(tmp_path / "dave", "two.py", GOOD)
    (tmp_path / "erin").mkdir()
    (tmp_path / "__pycache__").mkdir()
    found = {Path(s.name).name: s for s in find_submissions([tmp_path])}
    assert sorted(found) == ["alice.py", "bob", "carol", "dave", "erin"]
    assert found["carol"].entry.name == "my_robot.py"
    assert found["dave"].entry is None and "several programs (one.py, two.py)" in found["dave"].problem
    assert found["erin"].entry is None and "no Python program" in found["erin"].problem


def test_another_entry_name(tmp_path):
    write_program(tmp_path / "dave", "one.py", GOOD)
    write_program(tmp_path / "dave", "two.py", GOOD)
    [found] = find_submissions([tmp_path / "dave"], entry_name="two.py")
    assert found.entry.name == "two.py"


def test_a_missing_path(tmp_path):
    [found] = find_submissions([tmp_path / "nobody.py"])
    assert found.entry is None and "no such file or folder" in found.problem


def test_the_key_follows_the_content(tmp_path):
    prog = write_program(tmp_path, "alice.py", GOOD)
    key = find_submissions([prog])[0].key("lesson")
    assert find_submissions([prog])[0].key("lesson") == key
    assert find_submissions([prog])[0].key("other lesson") != key
    prog.write_text(GOOD + "\n# changed\n")
    assert find_submissions([prog])[0].key("lesson") != key
