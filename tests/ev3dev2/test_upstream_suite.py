"""
python-ev3dev2 2.1.0's own test suite passes against our shim, but for a short allow-list.

upstream_suite.py runs the suite (api_tests.py, unmodified) against the shim on a fake sysfs
(fake_sysfs.py), in a process of its own, from a checkout of python-ev3dev2 that
EV3SIM2D_UPSTREAM_EV3DEV2 names and upstream_files.sha256 pins; its docstring says what it uses
of upstream, from where, and why python-ev3dev2's tests/motor/ is not among it.  Each upstream
test is a test here: it passes when upstream's passes, is an expected failure when
upstream_allowlist.yaml lists it with its reason, and fails when it fails unlisted or passes
while listed (a stale entry).  The count shows under pytest's summary: "N of M upstream tests
pass, K allowed".

Without EV3SIM2D_UPSTREAM_EV3DEV2 those tests skip, saying how to make a checkout; with
EV3SIM2D_REQUIRE_UPSTREAM_EV3DEV2=1 (GitHub's workflow sets it) they fail instead.  A checkout
that is named but missing, or is not 2.1.0, always fails: it was asked for.  The tests' names
are upstream_suite.TEST_IDS, the same with a checkout or without, so the allow-list is checked
everywhere; with a checkout, they are checked against its api_tests.py.  The rest (the judging,
the refusing of a wrong checkout) runs on made-up data, without one.
"""

import ast
import hashlib
import json
import os
import subprocess
import sys

import pytest
import yaml

from . import upstream_suite
from .upstream_suite import (
    CHECKOUT_VARIABLE,
    REQUIRE_VARIABLE,
    ROOT,
    SUITE_FILES,
    TEST_IDS,
    UpstreamCheckoutError,
    checkout_from,
    copy_suite,
    expected_digests,
    how_to_run,
    not_named,
    required,
    verified_files,
)

HERE = os.path.dirname(os.path.abspath(__file__))
ALLOWLIST = os.path.join(HERE, "upstream_allowlist.yaml")
SUMMARY_PLUGIN = "ev3dev2-upstream-suite-summary"


def checkout_for_pytest(environ) -> str:
    """The checkout to run, verified; a skip when none is named, a failure when one is required or
    the one named is not python-ev3dev2 2.1.0."""
    checkout = checkout_from(environ)
    if checkout is None:
        if required(environ):
            pytest.fail(
                f"{REQUIRE_VARIABLE} is set, so python-ev3dev2 2.1.0's own tests must run, but "
                f"{CHECKOUT_VARIABLE} is not set.\nTo run them, {how_to_run()}",
                pytrace=False,
            )
        pytest.skip(not_named())
    try:
        verified_files(checkout)
    except UpstreamCheckoutError as error:
        refusal = str(error)
    else:
        return checkout
    pytest.fail(refusal, pytrace=False)


def upstream_test_ids(checkout: str) -> list[str]:
    """The id unittest gives each test method of the checkout's suite files (module.Class.method)."""
    ids = []
    for name in SUITE_FILES:
        with open(os.path.join(checkout, *name.split("/")), encoding="utf-8") as file:
            tree = ast.parse(file.read())
        module = os.path.splitext(os.path.basename(name))[0]
        for node in tree.body:
            if isinstance(node, ast.ClassDef) and any(
                ast.unparse(b).endswith("TestCase") for b in node.bases
            ):
                ids += [
                    f"{module}.{node.name}.{item.name}"
                    for item in node.body
                    if isinstance(item, ast.FunctionDef) and item.name.startswith("test")
                ]
    return sorted(ids)


def load_allowlist() -> dict[str, str]:
    with open(ALLOWLIST, encoding="utf-8") as file:
        return yaml.safe_load(file) or {}


def verdict(test_id: str, result: dict | None, reason: str | None) -> tuple[str, str]:
    """What an upstream test's result means here: (pass | allowed | stale | unexpected, why)."""
    if result is None:
        return "unexpected", f"{test_id} did not run"
    if result["outcome"] == "passed":
        if reason is None:
            return "pass", ""
        return "stale", f"{test_id} passes now: remove it from upstream_allowlist.yaml (it said: {reason})"
    if reason is not None:
        return "allowed", reason
    return "unexpected", (
        f"{test_id} {result['outcome']} against the shim:\n{result['details']}\n"
        "Where the shim differs from python-ev3dev2 2.1.0, fix the shim; where the test cannot apply "
        "to a simulated EV3, list it in tests/ev3dev2/upstream_allowlist.yaml with why."
    )


def judge(test_ids, outcomes, allowlist) -> tuple[str, list[str]]:
    """The summary line, and the problems: unexpected outcomes and stale entries."""
    verdicts = [verdict(i, outcomes.get(i), allowlist.get(i)) for i in test_ids]
    passed = sum(kind in ("pass", "stale") for kind, _ in verdicts)
    summary = f"{passed} of {len(test_ids)} upstream tests pass, {len(allowlist)} allowed"
    return summary, [why for kind, why in verdicts if kind in ("stale", "unexpected")]


class _Summary:
    def __init__(self, line):
        self.line = line

    def pytest_terminal_summary(self, terminalreporter):
        terminalreporter.write_line(f"python-ev3dev2 2.1.0's own tests against the ev3dev2 shim: {self.line}")


def _summarise(config, line):
    if not config.pluginmanager.has_plugin(SUMMARY_PLUGIN):
        config.pluginmanager.register(_Summary(line), SUMMARY_PLUGIN)


@pytest.fixture(scope="module")
def allowlist():
    return load_allowlist()


@pytest.fixture(scope="module")
def checkout(request):
    try:
        return checkout_for_pytest(os.environ)
    except pytest.skip.Exception:
        _summarise(
            request.config, f"not run, {CHECKOUT_VARIABLE} is not set (pytest -rs says how to run them)"
        )
        raise
    except pytest.fail.Exception as failure:
        _summarise(request.config, "not run: " + str(failure.msg).splitlines()[0])
        raise


@pytest.fixture(scope="module")
def outcomes(request, checkout, tmp_path_factory, allowlist):
    results = tmp_path_factory.mktemp("upstream") / "results.json"
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONSAFEPATH", "FAKE_SYS")}
    env[CHECKOUT_VARIABLE] = checkout
    run = subprocess.run(
        [sys.executable, "-m", "tests.ev3dev2.upstream_suite", str(results)],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 0, f"the upstream suite did not run:\n{run.stdout}\n{run.stderr}"
    found = json.loads(results.read_text(encoding="utf-8"))
    _summarise(request.config, judge(TEST_IDS, found, allowlist)[0])
    return found


# -- with a checkout: upstream's tests, one by one and as a whole --------------------------------


@pytest.mark.parametrize("test_id", TEST_IDS)
def test_upstream(test_id, outcomes, allowlist):
    kind, why = verdict(test_id, outcomes.get(test_id), allowlist.get(test_id))
    if kind == "allowed":
        pytest.xfail(why)
    assert kind == "pass", why


def test_the_whole_upstream_suite_ran_and_passes_but_for_the_allowed(outcomes, allowlist):
    assert sorted(outcomes) == TEST_IDS, "the suite ran other tests than upstream_suite.TEST_IDS"
    summary, problems = judge(TEST_IDS, outcomes, allowlist)
    print(summary)
    assert not problems, summary + "\n\n" + "\n\n".join(problems)


def test_the_tests_we_name_are_those_of_the_checkouts_suite(checkout):
    assert upstream_test_ids(checkout) == TEST_IDS, "update upstream_suite.TEST_IDS"


# -- without one: our data ---------------------------------------------------------------------


def test_every_allowed_test_is_an_upstream_test_and_says_why_in_one_line(allowlist):
    assert isinstance(allowlist, dict)
    unknown = sorted(set(allowlist) - set(TEST_IDS))
    assert not unknown, f"upstream_allowlist.yaml names tests upstream does not have: {unknown}"
    for test_id, reason in allowlist.items():
        assert isinstance(reason, str) and reason.strip() and "\n" not in reason.strip(), test_id


def test_the_test_ids_are_sorted_and_distinct():
    assert TEST_IDS == sorted(set(TEST_IDS))


def test_the_digests_cover_the_suite_and_fake_sys_and_name_where_they_come_from():
    digests = expected_digests()
    names = list(digests)
    assert names == sorted(names), "sorted by path, as `LC_ALL=C sort` sorts"
    assert set(SUITE_FILES) <= set(names)
    assert {"tests/fake-sys/populate_arena.py", "tests/fake-sys/clean_arena.py"} <= set(names)
    assert all(n.startswith("tests/") and "\\" not in n for n in names)
    with open(upstream_suite.DIGESTS, encoding="utf-8") as file:
        header = "".join(line for line in file if line.startswith("#"))
    for fact in (
        "UPSTREAM_REPOSITORY",
        "UPSTREAM_TAG",
        "UPSTREAM_COMMIT",
        "FAKE_SYS_REPOSITORY",
        "FAKE_SYS_COMMIT",
    ):
        assert getattr(upstream_suite, fact) in header, f"upstream_files.sha256's header lacks {fact}"


# -- without one: a checkout is named, found, or refused ---------------------------------------

API_TESTS = b"import unittest\n\nclass TestAPI(unittest.TestCase):\n    def test_a(self):\n        pass\n"
POPULATE = b"def populate_arena(devices):\n    pass\n"


@pytest.fixture
def made_up(tmp_path):
    """A checkout holding two files, and the digests that pin them."""
    (tmp_path / "tests" / "fake-sys").mkdir(parents=True)
    (tmp_path / "tests" / "api_tests.py").write_bytes(API_TESTS)
    (tmp_path / "tests" / "fake-sys" / "populate_arena.py").write_bytes(POPULATE)
    digests = {
        "tests/api_tests.py": hashlib.sha256(API_TESTS).hexdigest(),
        "tests/fake-sys/populate_arena.py": hashlib.sha256(POPULATE).hexdigest(),
    }
    return tmp_path, digests


def test_a_checkout_as_pinned_gives_its_files_and_they_are_copied_by_their_paths(made_up, tmp_path_factory):
    checkout, digests = made_up
    files = verified_files(str(checkout), digests)
    assert files == {"tests/api_tests.py": API_TESTS, "tests/fake-sys/populate_arena.py": POPULATE}

    scratch = tmp_path_factory.mktemp("scratch")
    folder = copy_suite(files, str(scratch))
    assert folder == os.path.join(str(scratch), "tests")
    assert (scratch / "tests" / "fake-sys" / "populate_arena.py").read_bytes() == POPULATE


def test_a_changed_file_is_refused_by_its_name(made_up):
    checkout, digests = made_up
    (checkout / "tests" / "api_tests.py").write_bytes(API_TESTS + b"# changed\n")

    with pytest.raises(UpstreamCheckoutError) as refusal:
        verified_files(str(checkout), digests)
    message = str(refusal.value)
    assert f"{CHECKOUT_VARIABLE}={checkout} is not python-ev3dev2 2.1.0" in message
    assert "differs: tests/api_tests.py (sha256 " in message
    assert "populate_arena" not in message
    assert "checkout ev3dev-stretch/2.1.0" in message


def test_a_missing_file_is_refused_by_its_name(made_up):
    checkout, digests = made_up
    os.remove(checkout / "tests" / "api_tests.py")

    with pytest.raises(UpstreamCheckoutError, match="missing: tests/api_tests.py"):
        verified_files(str(checkout), digests)


def test_a_fake_sys_not_checked_out_is_named_as_the_submodule(made_up):
    checkout, digests = made_up
    os.remove(checkout / "tests" / "fake-sys" / "populate_arena.py")

    with pytest.raises(UpstreamCheckoutError, match="submodule update --init tests/fake-sys"):
        verified_files(str(checkout), digests)


def test_windows_line_endings_from_git_are_turned_back_into_the_pinned_bytes(made_up):
    checkout, digests = made_up
    (checkout / "tests" / "api_tests.py").write_bytes(API_TESTS.replace(b"\n", b"\r\n"))

    assert verified_files(str(checkout), digests)["tests/api_tests.py"] == API_TESTS


def test_without_the_variable_the_suite_is_skipped_saying_how_to_run_it():
    with pytest.raises(pytest.skip.Exception) as skip:
        checkout_for_pytest({})
    reason = str(skip.value.msg)
    assert reason.startswith(f"{CHECKOUT_VARIABLE} is not set")
    assert "git clone --branch ev3dev-stretch/2.1.0 --recurse-submodules" in reason
    assert "https://github.com/ev3dev/ev3dev-lang-python" in reason
    assert "\n" not in reason


@pytest.mark.parametrize(
    "environ", [{REQUIRE_VARIABLE: "1"}, {REQUIRE_VARIABLE: "1", CHECKOUT_VARIABLE: " "}]
)
def test_without_the_variable_but_required_the_suite_fails(environ):
    with pytest.raises(pytest.fail.Exception) as failure:
        checkout_for_pytest(environ)
    message = str(failure.value.msg)
    assert message.startswith(f"{REQUIRE_VARIABLE} is set, so python-ev3dev2 2.1.0's own tests must run")
    assert f"{CHECKOUT_VARIABLE} is not set.\nTo run them, make a checkout with `git clone" in message


@pytest.mark.parametrize("require", [{}, {REQUIRE_VARIABLE: "1"}])
def test_a_named_checkout_that_is_not_there_fails_required_or_not(tmp_path, require):
    with pytest.raises(pytest.fail.Exception, match="there is no such folder"):
        checkout_for_pytest({CHECKOUT_VARIABLE: str(tmp_path / "nowhere"), **require})


def test_required_means_set_and_not_zero():
    assert [required({REQUIRE_VARIABLE: v}) for v in ("1", "true", "0", "")] == [True, True, False, False]
    assert not required({})


def test_the_runner_refuses_to_run_without_a_checkout(monkeypatch, capsys, tmp_path):
    monkeypatch.delenv(CHECKOUT_VARIABLE, raising=False)

    assert upstream_suite.main([str(tmp_path / "results.json")]) == 2
    assert capsys.readouterr().err.startswith(f"{CHECKOUT_VARIABLE} is not set")
    assert not (tmp_path / "results.json").exists()


# -- the judging, on made-up outcomes ---------------------------------------------------------

IDS = ["api_tests.T.test_a", "api_tests.T.test_b", "api_tests.T.test_c"]
PASSED = {"outcome": "passed", "details": ""}
FAILED = {"outcome": "failed", "details": "AssertionError: 1 != 2"}


def test_all_passing_is_no_problem():
    assert judge(IDS, dict.fromkeys(IDS, PASSED), {}) == ("3 of 3 upstream tests pass, 0 allowed", [])


def test_an_allowed_failure_is_counted_and_no_problem():
    outcomes = {**dict.fromkeys(IDS, PASSED), IDS[1]: FAILED}
    allowed = {IDS[1]: "needs a real motor turning"}
    assert judge(IDS, outcomes, allowed) == ("2 of 3 upstream tests pass, 1 allowed", [])
    assert verdict(IDS[1], FAILED, allowed[IDS[1]]) == ("allowed", "needs a real motor turning")


def test_an_unlisted_failure_and_a_test_that_did_not_run_are_problems():
    summary, problems = judge(IDS, {IDS[0]: PASSED, IDS[1]: FAILED}, {})
    assert summary == "1 of 3 upstream tests pass, 0 allowed"
    assert len(problems) == 2
    assert "AssertionError: 1 != 2" in problems[0] and "fix the shim" in problems[0]
    assert problems[1] == f"{IDS[2]} did not run"


def test_an_allowed_test_that_passes_is_a_stale_entry():
    summary, problems = judge(IDS, dict.fromkeys(IDS, PASSED), {IDS[2]: "was broken"})
    assert summary == "3 of 3 upstream tests pass, 1 allowed"
    assert problems == [f"{IDS[2]} passes now: remove it from upstream_allowlist.yaml (it said: was broken)"]
