"""A brick started through sandbox-exec (macOS's Seatbelt) reaches no network and writes only in its
scratch folder; no folder name can break out of the profile's strings; where sandbox-exec is
missing or refuses, the layer says so and the brick's command is left as it was."""

import json
import os
import socket
import subprocess
import sys
import textwrap
from subprocess import PIPE

import pytest

from ev3sim2d.simulator import sandbox_exec

has_sandbox_exec = os.access(sandbox_exec.SANDBOX_EXEC, os.X_OK)
HOSTILE_NAMES = [
    'quote"inside',
    "paren)inside",
    "new\nline",
    'escape ")(allow default)(allow network*)("',  # a folder name cannot hold a slash
    "back\\slash",
    "ends in a backslash\\",
    "; a comment",
    "spaces and ünïcödé 名前",
]
ANY_NAME = pytest.mark.needs_linux("file_names")  # (Windows refuses quotes, backslashes, new lines)


@pytest.fixture(autouse=True)
def fresh_probe():
    """Each test looks for sandbox-exec anew (available() remembers what it found)."""
    sandbox_exec._probe.cache_clear()
    yield
    sandbox_exec._probe.cache_clear()


class Text(str):
    """A string literal read from a profile (a bare str is a symbol or a number)."""


def read_profile(text: str) -> list:
    """The forms of an SBPL profile, read as TinyScheme's reader reads them (lists, atoms, strings).

    In a string only a backslash and a double quote are special; our profiles may escape nothing
    else, since TinyScheme gives other escapes (\\n, \\x41, \\101) meanings of their own."""
    forms: list = []
    open_lists: list[list] = []
    current = forms
    i = 0
    while i < len(text):
        c = text[i]
        if c.isspace():
            i += 1
        elif c == ";":
            end = text.find("\n", i)
            i = len(text) if end < 0 else end
        elif c == "(":
            open_lists.append(current)
            current.append([])
            current = current[-1]
            i += 1
        elif c == ")":
            assert open_lists, f"a ) closes nothing at {i}: {text!r}"
            current = open_lists.pop()
            i += 1
        elif c == '"':
            chars, i = [], i + 1
            while True:
                assert i < len(text), f"a string is not closed: {text!r}"
                if text[i] == "\\":
                    assert text[i + 1 : i + 2] in ('"', "\\"), f"escape \\{text[i + 1]} in {text!r}"
                    chars.append(text[i + 1])
                    i += 2
                elif text[i] == '"':
                    i += 1
                    break
                else:
                    chars.append(text[i])
                    i += 1
            current.append(Text("".join(chars)))
        else:
            start = i
            while i < len(text) and not text[i].isspace() and text[i] not in '()";':
                i += 1
            current.append(text[start:i])
    assert not open_lists, f"a ( is not closed: {text!r}"
    return forms


def expected_forms(*writable: str) -> list:
    return [
        ["version", "1"],
        ["allow", "default"],
        ["deny", "network*"],
        ["deny", "file-write*"],
        ["allow", "file-write*", ["literal", "/dev/null"], *(["subpath", path] for path in writable)],
        ["deny", "file-link"],
    ]


def strings_in(forms: list) -> list[Text]:
    found = []
    for form in forms:
        if isinstance(form, list):
            found += strings_in(form)
        elif isinstance(form, Text):
            found.append(form)
    return found


# The profile, on every system


def test_the_profile_denies_the_network_hard_links_and_writes_but_beneath_the_scratch_folder(tmp_path):
    forms = read_profile(sandbox_exec.profile([str(tmp_path)]))
    assert forms == expected_forms(str(tmp_path))
    # the last rule that matches wins: the scratch folder's allow comes after the deny of all writes
    assert strings_in(forms) == ["/dev/null", str(tmp_path)]


@pytest.mark.needs_linux("symlinks")
def test_write_paths_go_in_as_real_paths_without_repeats(tmp_path):
    real = tmp_path / "real"
    real.mkdir()
    (tmp_path / "alias").symlink_to(real)  # like /tmp -> /private/tmp and /var -> /private/var on macOS
    other = tmp_path / "other"
    other.mkdir()
    written = [str(tmp_path / "alias"), str(real) + "/", str(other / ".." / "other"), str(real)]
    assert read_profile(sandbox_exec.profile(written)) == expected_forms(str(real), str(other))


def test_with_no_write_paths_only_dev_null_is_writable():
    assert read_profile(sandbox_exec.profile([])) == expected_forms()


@pytest.mark.parametrize(
    "name",
    [pytest.param(name, marks=ANY_NAME) if set(name) & set('"\\\n') else name for name in HOSTILE_NAMES],
)
def test_a_hostile_folder_name_stays_inside_its_string(tmp_path, name):
    folder = tmp_path / name
    folder.mkdir()
    text = sandbox_exec.profile([str(folder)])
    assert read_profile(text) == expected_forms(str(folder))


def test_spaces_and_non_ascii_letters_are_kept_as_they_are(tmp_path):
    folder = tmp_path / "spaces and ünïcödé 名前"
    folder.mkdir()
    assert f'(subpath "{folder}")' in sandbox_exec.profile([str(folder)])


def test_a_nul_in_a_write_path_is_refused():
    with pytest.raises(ValueError, match="NUL"):
        sandbox_exec.profile(["/tmp/a\0b"])


@pytest.mark.skipif(has_sandbox_exec, reason="this system has sandbox-exec")
def test_without_sandbox_exec_the_layer_is_off_and_the_command_is_left_alone(tmp_path):
    assert sandbox_exec.available() is None
    assert sandbox_exec.describe() == f"off: no executable {sandbox_exec.SANDBOX_EXEC} on this system"
    argv = [sys.executable, "-S", "-c", "pass"]
    wrapped = sandbox_exec.wrap(argv, [str(tmp_path)])
    assert wrapped == argv and wrapped is not argv


# The composed command, through a stand-in sandbox-exec


STAND_IN = """\
#!{python}
# A stand-in for macOS's sandbox-exec: checks `-p PROFILE command ...`, notes the profile, execs the command.
import json, os, sys
arguments = sys.argv[1:]
if len(arguments) < 3 or arguments[0] != "-p" or not arguments[1].startswith("(version 1)"):
    sys.exit("usage: sandbox-exec -p PROFILE command [argument ...]")
with open({log!r}, "a", encoding="utf-8") as log:
    log.write(json.dumps(arguments[1]) + "\\n")
os.execv(arguments[2], arguments[2:])
"""

REFUSING = """\
#!{python}
import sys
sys.stderr.write("sandbox-exec: sandbox_apply: Operation not permitted\\n")
sys.exit(71)
"""


def install(monkeypatch, tmp_path, script: str, **values) -> str:
    path = tmp_path / "bin" / "sandbox-exec"
    path.parent.mkdir(exist_ok=True)
    path.write_text(script.format(python=sys.executable, **values))
    path.chmod(0o755)
    monkeypatch.setattr(sandbox_exec, "SANDBOX_EXEC", str(path))
    return str(path)


ECHO = """\
import json, os, socket, sys
connection = socket.socket(fileno=int(sys.argv[1]))
connection.sendall(b"ping")
print(json.dumps({"pid": os.getpid(), "reply": connection.recv(4).decode()}))
"""


@pytest.mark.needs_linux("script_exec")  # (the stand-in sandbox-exec is a #! script, handed an fd)
def test_wrap_runs_python_through_sandbox_exec_with_its_connection_and_pid(monkeypatch, tmp_path):
    log = tmp_path / "profiles.jsonl"
    stand_in = install(monkeypatch, tmp_path, STAND_IN, log=str(log))
    scratch = tmp_path / "scratch"
    scratch.mkdir()
    assert sandbox_exec.available() == stand_in
    assert sandbox_exec.describe() == "on (no network, writes only in the scratch folder)"

    ours, theirs = socket.socketpair()
    with ours, theirs:
        argv = sandbox_exec.wrap([sys.executable, "-S", "-c", ECHO, str(theirs.fileno())], [str(scratch)])
        assert argv[:3] == [stand_in, "-p", sandbox_exec.profile([str(scratch)])]
        popen = subprocess.Popen(argv, pass_fds=[theirs.fileno()], stdout=PIPE, stderr=PIPE)
        theirs.close()
        ours.settimeout(30)
        if ours.recv(4) == b"ping":
            ours.sendall(b"pong")
        out, err = popen.communicate(timeout=30)
    assert popen.returncode == 0, err.decode()
    # sandbox-exec execs the command: the pid the simulator holds is the program's
    assert json.loads(out) == {"pid": popen.pid, "reply": "pong"}
    probed, used = [json.loads(line) for line in log.read_text().splitlines()]
    assert probed == sandbox_exec.profile([])  # available() ran Python under a profile once
    assert used == sandbox_exec.profile([str(scratch)])


@pytest.mark.needs_linux("script_exec")
def test_a_sandbox_exec_that_refuses_turns_the_layer_off(monkeypatch, tmp_path):
    install(monkeypatch, tmp_path, REFUSING)
    assert sandbox_exec.available() is None
    assert sandbox_exec.describe().startswith("off: ")
    assert "sandbox_apply: Operation not permitted" in sandbox_exec.describe()
    argv = [sys.executable, "-S", "-c", "pass"]
    assert sandbox_exec.wrap(argv, [str(tmp_path)]) == argv


@pytest.mark.needs_linux("file_modes")  # (chmod 644 takes the x away)
def test_a_sandbox_exec_that_is_not_executable_is_not_used(monkeypatch, tmp_path):
    path = install(monkeypatch, tmp_path, STAND_IN, log=str(tmp_path / "log"))
    os.chmod(path, 0o644)
    assert sandbox_exec.available() is None
    assert sandbox_exec.describe() == f"off: no executable {path} on this system"


# Seatbelt itself: only where a real sandbox-exec is (macOS)


UNDER_SEATBELT = textwrap.dedent(
    """\
    import json, os, socket, sys
    scratch, outside, port, fd = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
    found = {"pid": os.getpid()}

    def attempt(name, action):
        try:
            action()
            found[name] = "done"
        except OSError as err:
            found[name] = type(err).__name__

    def write(path):
        with open(path, "w") as f:
            f.write("written")

    attempt("write inside", lambda: write(os.path.join(scratch, "inside.txt")))
    attempt("write outside", lambda: write(os.path.join(outside, "outside.txt")))
    attempt("write /dev/null", lambda: write(os.devnull))
    attempt("move out", lambda: os.rename(os.path.join(scratch, "inside.txt"), os.path.join(outside, "moved.txt")))
    attempt("symlink", lambda: os.symlink(os.path.join(outside, "through-symlink.txt"), os.path.join(scratch, "sym")))
    attempt("write through symlink", lambda: write(os.path.join(scratch, "sym")))
    attempt("hard link", lambda: os.link(os.path.join(outside, "victim.txt"), os.path.join(scratch, "alias.txt")))
    attempt("connect", lambda: socket.create_connection(("127.0.0.1", port), timeout=10).close())
    connection = socket.socket(fileno=fd)
    connection.sendall(b"ping")
    found["reply"] = connection.recv(4).decode()
    print(json.dumps(found))
    """
)


@pytest.mark.skipif(not has_sandbox_exec, reason=f"no {sandbox_exec.SANDBOX_EXEC} on this system")
@pytest.mark.parametrize(
    "name",
    ["scratch", 'hostile ")(allow default)\n; ü("', "long-" + "x" * 200],
    ids=["plain", "hostile", "long"],
)
def test_under_seatbelt_a_program_writes_only_in_its_scratch_folder_and_reaches_no_network(tmp_path, name):
    assert sandbox_exec.available() is not None, sandbox_exec.describe()
    real_scratch = tmp_path / name
    real_scratch.mkdir()
    scratch = tmp_path / "scratch-alias"  # given through a symlink, as /var/folders/... is on macOS
    scratch.symlink_to(real_scratch)
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "victim.txt").write_text("untouched")

    listener = socket.create_server(("127.0.0.1", 0))
    ours, theirs = socket.socketpair()
    with listener, ours, theirs:
        port = listener.getsockname()[1]
        command = [sys.executable, "-S", "-B", "-c", UNDER_SEATBELT, str(scratch), str(outside), str(port)]
        argv = sandbox_exec.wrap([*command, str(theirs.fileno())], [str(scratch)])
        popen = subprocess.Popen(argv, pass_fds=[theirs.fileno()], stdout=PIPE, stderr=PIPE)
        try:
            theirs.close()
            ours.settimeout(60)
            if ours.recv(4) == b"ping":  # else the program never ran: sandbox-exec said why on stderr
                ours.sendall(b"pong")
            out, err = popen.communicate(timeout=60)
        finally:
            popen.kill()
            popen.wait()
    assert popen.returncode == 0, err.decode()
    assert err == b""  # the interpreter wanted to write nothing it was refused
    assert json.loads(out) == {
        "pid": popen.pid,
        "write inside": "done",
        "write outside": "PermissionError",
        "write /dev/null": "done",
        "move out": "PermissionError",
        "symlink": "done",
        "write through symlink": "PermissionError",
        "hard link": "PermissionError",
        "connect": "PermissionError",
        "reply": "pong",
    }
    assert (real_scratch / "inside.txt").read_text() == "written"
    assert sorted(p.name for p in outside.iterdir()) == ["victim.txt"]
    assert (outside / "victim.txt").read_text() == "untouched"
