"""Grading a class: results as they come, resuming, the same score every time, either way of starting workers."""

import json
import os
from pathlib import Path

import pytest

from ev3sim2d.grading import grader
from ev3sim2d.grading.grader import CoreShare, default_jobs, grade, load_results
from ev3sim2d.grading.grader_key import grader_key
from ev3sim2d.grading.lesson import load_lesson
from ev3sim2d.grading.submission import find_submissions

from .lesson_maker import GOOD, HIDDEN, SHORT, write_lesson, write_program


@pytest.fixture
def lesson(tmp_path):
    return load_lesson(write_lesson(tmp_path / "lesson"))


@pytest.fixture
def programs(tmp_path):
    folder = tmp_path / "class"
    write_program(folder, "alice.py", GOOD)
    write_program(folder, "bob.py", SHORT)
    write_program(folder, "carol.py", "raise ValueError('oops')\n")
    return folder


def test_results_are_written_as_each_submission_finishes(lesson, programs, tmp_path):
    results_file = tmp_path / "results.json"
    seen = []

    def on_result(result):
        saved = json.loads(results_file.read_text())
        seen.append((result.submission, [s["submission"] for s in saved["submissions"]]))

    grading = grade(
        lesson, find_submissions([programs]), jobs=2, results_path=results_file, on_result=on_result
    )
    assert [name for name, _ in seen] == [r.submission for r in grading.results]
    for name, saved in seen:
        assert name in saved  # already in the file when the callback heard of it
    assert [len(saved) for _, saved in seen] == [1, 2, 3]
    data = json.loads(results_file.read_text())
    assert data["lesson"] == "lesson" and data["max_score"] == 10
    assert data["variants"] == [
        {"name": "room", "hidden": False, "world": "room"},
        {"name": "hidden variant 1", "hidden": True},
    ]
    carol = data["submissions"][2]
    assert carol["status"] == "error" and carol["score"] == 0
    assert "ValueError: oops (line 1)" in carol["variants"][0]["message"]


def test_an_interrupted_run_resumes_without_grading_again(lesson, programs, tmp_path):
    results_file = tmp_path / "results.json"
    first = grade(lesson, find_submissions([programs / "alice.py"]), results_path=results_file)
    assert first.reused == 0
    second = grade(lesson, find_submissions([programs]), jobs=2, results_path=results_file, resume=True)
    assert second.reused == 1
    assert [Path(r.submission).name for r in second.results] == ["alice.py", "bob.py", "carol.py"]
    assert second.results[0].full_marks
    (programs / "alice.py").write_text(SHORT)  # changed since: graded again
    third = grade(lesson, find_submissions([programs]), jobs=2, results_path=results_file, resume=True)
    assert third.reused == 2 and not third.results[0].full_marks
    assert grade(lesson, find_submissions([programs]), results_path=results_file).reused == 0  # not asked


def test_results_of_another_lesson_are_not_reused(lesson, programs, tmp_path):
    results_file = tmp_path / "results.json"
    grade(lesson, find_submissions([programs / "alice.py"]), results_path=results_file)
    data = json.loads(results_file.read_text())
    assert len(load_results(results_file, lesson, grader_key())) == 1  # signed by this grader
    data["lesson"] = "another"
    results_file.write_text(json.dumps(data))
    assert load_results(results_file, lesson, grader_key()) == {}


def test_the_same_submission_always_gets_the_same_result(lesson, programs):
    runs = [grade(lesson, find_submissions([programs]), jobs=jobs).results for jobs in (1, 2, 2)]
    as_json = [[r.to_dict() for r in results] for results in runs]
    assert as_json[0] == as_json[1] == as_json[2]


def test_nothing_to_run_is_a_result_too(lesson, tmp_path):
    [result] = grade(lesson, find_submissions([tmp_path / "nobody.py"])).results
    assert result.status == "missing" and result.score == 0 and result.max_score == 10


@pytest.mark.skipif(not hasattr(os, "fork"), reason="compares with forked workers")
def test_spawned_workers_grade_as_forked_ones_do(lesson, programs):
    subs = find_submissions([programs / "alice.py", programs / "bob.py"])
    forked = [r.to_dict() for r in grade(lesson, subs, jobs=2, use_fork=True).results]
    spawned = [r.to_dict() for r in grade(lesson, subs, jobs=2, use_fork=False).results]
    assert forked == spawned


@pytest.mark.skipif(not hasattr(os, "fork"), reason="compares with forked workers")
def test_spawned_workers_grade_hidden_variants_from_a_teachers_private_folder(programs, tmp_path):
    private = tmp_path / "private"
    private.mkdir()
    (private / "hidden.yaml").write_text(HIDDEN.replace("seed: 3", "seed: 3\n    time_s: 0.2"))
    lesson = load_lesson(write_lesson(tmp_path / "lesson2", hidden_text=None), hidden=private)
    subs = find_submissions([programs / "alice.py"])
    forked = [r.to_dict() for r in grade(lesson, subs, jobs=2, use_fork=True).results]
    spawned = [r.to_dict() for r in grade(lesson, subs, jobs=2, use_fork=False).results]
    assert forked == spawned
    assert forked[0]["variants"][1]["name"] == "hidden variant 1"
    assert forked[0]["variants"][1]["score"] == 0  # too short a time: the private variant was graded


def test_failed_runs_are_handed_on_with_their_trace(lesson, programs):
    kept = []

    def on_failed_run(submission, variant, trace_path):
        kept.append((Path(submission.name).name, variant, trace_path.is_file()))

    grade(lesson, find_submissions([programs / "alice.py", programs / "bob.py"]), on_failed_run=on_failed_run)
    assert sorted(kept) == [("bob.py", 0, True), ("bob.py", 1, True)]


def test_an_interrupt_keeps_what_is_done_and_leaves_no_worker_behind(lesson, programs, tmp_path):
    results_file = tmp_path / "results.json"

    def interrupt(result):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        grade(lesson, find_submissions([programs]), jobs=2, results_path=results_file, on_result=interrupt)
    saved = json.loads(results_file.read_text())["submissions"]
    assert [Path(s["submission"]).name for s in saved] == ["alice.py"]
    if hasattr(os, "fork"):  # (without fork, as on Windows, os.waitpid takes a process handle, not -1)
        with pytest.raises(ChildProcessError):
            os.waitpid(-1, os.WNOHANG)  # no child process left, not even a zombie
    resumed = grade(lesson, find_submissions([programs]), jobs=2, results_path=results_file, resume=True)
    assert resumed.reused == 1 and len(resumed.results) == 3


@pytest.mark.parametrize(
    "cores, jobs, running, expected",
    [
        ({0, 1}, 2, [], 0),  # two runs on two cores: each run keeps to a core of its own
        ({0, 1}, 2, [0], 1),
        ({0, 1}, 3, [0, 1], 0),
        ({0, 1}, 3, [1, 0, 1], 0),
        ({2, 5}, 2, [2], 5),  # the cores this process may use, whatever their numbers
        ({0, 1}, 1, [], None),  # one run on two cores: a core each for simulator and brick, which spin
        ({0, 1, 2, 3}, 2, [], None),
        ({0, 1, 2, 3}, 3, [None], 0),
    ],
)
def test_runs_share_out_the_cores_only_when_they_must(monkeypatch, cores, jobs, running, expected):
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: cores, raising=False)
    assert CoreShare(jobs).least_used(running) == expected


@pytest.mark.parametrize(
    "lesson_id, cores, spin, expected",
    [
        ("line-follow", {0, 1}, True, 1),  # the simulator and the brick: a core each
        ("line-follow", {0, 1, 2, 3}, True, 2),
        ("line-follow", {4, 7, 9, 11, 12}, True, 2),  # whatever the cores' numbers
        ("convoy", {0, 1}, True, 1),  # the simulator and two bricks, the student's and the pacer's
        ("convoy", {0, 1, 2, 3}, True, 1),
        ("convoy", {0, 1, 2, 3, 4, 5}, True, 2),
        ("line-follow", {0}, True, 1),  # one core: still one run
        ("convoy", {0, 1}, False, 2),  # where nothing can spin (Windows): each waits asleep, a run a core
        (None, {0, 1, 2, 3}, True, 2),  # no lesson (the command's help): a lesson of one robot
    ],
)
def test_runs_at_a_time_by_default_give_each_process_of_a_run_a_core(
    monkeypatch, lesson_id, cores, spin, expected
):
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: cores, raising=False)
    monkeypatch.setattr(grader, "can_spin", lambda: spin)
    lesson = load_lesson(lesson_id) if lesson_id else None
    assert default_jobs(lesson) == expected


def test_a_lesson_of_two_robots_on_two_cores_is_graded_a_run_at_a_time_with_its_processes_placed(
    monkeypatch, tmp_path
):
    """Without --jobs: one run at a time, each alone on the machine, so its simulator and bricks take cores
    of their own (Job.alone: run_programs(place=True)), and nothing is pinned to one core."""
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0, 1}, raising=False)
    monkeypatch.setattr(grader, "can_spin", lambda: True)
    lesson = load_lesson("convoy")
    for name in ("a", "b"):
        (tmp_path / f"{name}.py").write_text((lesson.folder / "solution.py").read_text())
    started = []
    start_job = grader.start_job

    def watched(job, *args):
        started.append((job.alone, job.cpu, len(started)))
        return start_job(job, *args)

    monkeypatch.setattr(grader, "start_job", watched)
    grading = grade(lesson, find_submissions([str(tmp_path)]))
    assert [r.score for r in grading.results] == [lesson.max_score] * 2
    assert len(started) == 2 * len(lesson.variants)
    assert all(alone and cpu is None for alone, cpu, _ in started)
