"""The brick's sandbox against a determined student, on Linux and on the systems that lack its layers.

Each test starts a real brick-like process (sandboxed_program.py: python -I -S, the repository on
sys.path, a fixed environment, a session of its own) that enters the sandbox with a scratch folder
and then plays one trick; the trick must fail, and honest work beside it must still succeed.
A trick that gets through on a machine lacking a layer that would stop it is skipped, naming the
layer; with CI=true it fails instead (CI machines have every layer).

The same tricks run in a brick of a Windows-like and of a macOS-like Python
(tests/portable/other_system.py, on Linux), and on those systems themselves in the workflow's OS
matrix.  There the expected outcome follows the layers: a trick may get through only where the
brick reports every layer that would stop it off (the report never claims a wall that is not
there), honest work must still succeed, and the walls such a system does have (resource limits,
a session) must hold.  A trick whose success would harm the machine the tests run on (signal
every process, a fork bomb, filling the memory) is not played where its layer is reported off:
the report's word is checked instead; a trick aimed at the grader aims at a stand-in process.
"""

from __future__ import annotations

import importlib.util
import json
import os
import shutil
import signal
import site
import socket
import subprocess
import sys
import tempfile
import textwrap
import time
import uuid
from dataclasses import dataclass
from pathlib import Path

import pytest

from ev3sim2d.brick import sandbox

REPO = Path(__file__).resolve().parents[2]
HELPER = Path(__file__).with_name("sandboxed_program.py")
SITE_PACKAGES = [p for p in sys.path if p.rstrip("/").endswith("-packages") and os.path.isdir(p)]


def _uid_mapped(uid: int) -> bool:
    try:
        with open("/proc/self/uid_map") as f:
            return any(
                int(a) <= uid < int(a) + int(n) for a, _, n in (line.split() for line in f if line.strip())
            )
    except OSError:  # no user namespaces here (not Linux)
        return False


LINUX = sandbox.linux_kernel()
ROOT = hasattr(os, "geteuid") and os.geteuid() == 0
AS_ROOT = LINUX and ROOT and _uid_mapped(65534)  # root that can give itself up (not a rootless container's)
BRICK_UID = 65534 if AS_ROOT else (os.getuid() if hasattr(os, "getuid") else None)
IN_CI = os.environ.get("CI") == "true"
LAYERS = (
    "session",
    "root_dropped",
    "capabilities",
    "user_ns",
    "mount_ns",
    "net_ns",
    "pid_ns",
    "ipc_ns",
    "no_new_privs",
    "rlimits",
    "landlock",
    "landlock_net",
    "landlock_scope",
    "seccomp",
    "fds",
)


@dataclass
class Brick:
    """What a sandboxed program did: the sandbox's report and one result per attempt."""

    report: dict
    results: dict
    returncode: int
    stdout: str
    stderr: str
    seconds: float
    system: str = "linux"  # linux, or the kind of system without Linux's layers: windows, macos

    @property
    def elsewhere(self) -> bool:
        return self.system != "linux"

    def worked(self, name: str) -> bool:
        assert name in self.results, f"no attempt {name!r}: {self.describe()}"
        return self.results[name]["ok"]

    def describe(self) -> str:
        return f"exit {self.returncode}\nstdout:\n{self.stdout[-3000:]}\nstderr:\n{self.stderr[-3000:]}"


def stopped(brick: Brick, tricks: list[str], layers: tuple[str, ...]) -> None:
    """Every trick failed; if one got through, skip when one of `layers` is off here (fail in CI).
    On a system without Linux's layers a trick may get through only where every one of `layers` is
    reported off: that is its expected outcome there."""
    through = [name for name in tricks if brick.worked(name)]
    if not through:
        return
    off = {layer: brick.report.get(layer, "not reported") for layer in layers}
    off = {layer: state for layer, state in off.items() if not state.startswith("on")}
    if brick.elsewhere:
        claimed = {layer: brick.report.get(layer) for layer in layers if layer not in off}
        assert not claimed, f"{through} got through, yet the report says {claimed}:\n{brick.describe()}"
        return
    if off and not IN_CI:
        pytest.skip(f"{through} got through; this machine lacks {off}")
    pytest.fail(f"{through} got through the sandbox {brick.report}:\n{brick.describe()}")


def honest(brick: Brick, names: list[str]) -> None:
    failed = {name: brick.results.get(name) for name in names if not brick.worked(name)}
    assert not failed, f"honest work failed inside the sandbox: {failed}\n{brick.describe()}"


def require(brick: Brick, *layers: str) -> None:
    off = {layer: brick.report.get(layer, "not reported") for layer in layers}
    off = {layer: state for layer, state in off.items() if not state.startswith("on")}
    if off and brick.elsewhere:
        pytest.skip(f"a {brick.system}-like system has none of {sorted(off)}: {off}")
    if off:
        if IN_CI:
            pytest.fail(f"CI machines must have every layer: {off}")
        pytest.skip(f"this machine lacks {off}")


@pytest.fixture
def scratch(tmp_path) -> Path:
    folder = tmp_path / "scratch"
    folder.mkdir()
    return folder


@pytest.fixture
def outside():
    """A folder outside the sandbox anyone may read (hidden.yaml) and write (drop/), like a
    teacher's folder of hidden variants or the test's output: only the sandbox stands in the way."""
    folder = Path(tempfile.mkdtemp(prefix="ev3sim2d-outside-"))
    folder.chmod(0o755)
    (folder / "hidden.yaml").write_text("start: {x_cm: 42, y_cm: 17}\n")
    (folder / "hidden.yaml").chmod(0o644)
    (folder / "drop").mkdir()
    (folder / "drop").chmod(0o777)
    yield folder
    shutil.rmtree(folder, ignore_errors=True)


SYSTEMS = ("this system", "windows-like", "macos-like")


def this_system() -> str:
    """linux, or the kind of system this is without Linux's layers: macos (POSIX), windows."""
    return "linux" if LINUX else "macos" if hasattr(os, "setsid") else "windows"


@pytest.fixture(params=SYSTEMS)
def system(request) -> tuple[str, str]:
    """(kind, python): this system and its Python, or a stand-in for another system (on Linux)."""
    if request.param == "this system":
        return this_system(), sys.executable
    kind = request.param.removesuffix("-like")
    return kind, str(request.getfixturevalue("other_systems")[kind])


@pytest.fixture
def stand_in():
    """A process standing in for the grader where a trick against it could succeed (a system without
    Linux's walls): what the trick does lands there, and shows."""
    process = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    yield process
    process.kill()
    process.wait()


@pytest.fixture
def run_brick(scratch, system):
    """run_brick(program, args=..., limits=..., read=...) -> Brick: the program runs inside the sandbox."""
    kind, system_python = system

    def run(
        program,
        *,
        args=None,
        limits=None,
        read=(),
        timeout=30,
        python=None,
        user=None,
        scratch=scratch,
        seed=None,
        wrapper=(),
    ):
        python = python or system_python
        setup = {
            "repo": str(REPO),
            "site_packages": SITE_PACKAGES if python == sys.executable else [],
            "scratch": str(scratch),
            "read": [str(p) for p in read],
            "limits": limits or {},
            "program": textwrap.dedent(program),
            "args": {"scratch": str(scratch), "test_pid": os.getpid(), **(args or {})},
        }
        if seed is not None:
            setup["seed"] = seed
        environment = {
            "PATH": "/usr/local/bin:/usr/bin:/bin",
            "HOME": str(scratch),
            "TMPDIR": str(scratch),
            "LANG": "C.UTF-8",
            "PYTHONHASHSEED": "0",
        }
        if "SYSTEMROOT" in os.environ:  # (Windows: sockets need it)
            environment["SYSTEMROOT"] = os.environ["SYSTEMROOT"]
        started = time.monotonic()
        as_user = {"user": user, "group": user, "extra_groups": []} if user is not None else {}
        done = subprocess.run(
            [*wrapper, python, "-I", "-S", "-B", str(HELPER), json.dumps(setup)],
            stdin=subprocess.DEVNULL,
            capture_output=True,
            text=True,
            env=environment,
            cwd=scratch,
            timeout=timeout,
            **({"start_new_session": True} if hasattr(os, "setsid") else {}),
            **as_user,
        )
        report, results = {}, {}
        for line in done.stdout.splitlines():
            if line.startswith("REPORT "):
                report = json.loads(line[7:])
            elif line.startswith("RESULT "):
                result = json.loads(line[7:])
                results[result["name"]] = result
        seconds = time.monotonic() - started
        brick = Brick(report, results, done.returncode, done.stdout, done.stderr, seconds, kind)
        assert report, f"the program never got into the sandbox:\n{brick.describe()}"
        return brick

    run.system = kind
    run.elsewhere = kind != "linux"
    return run


def processes_with(marker: str) -> list[int]:
    """Processes whose command line holds `marker` (a program's leftovers)."""
    found = []
    for name in os.listdir("/proc"):
        if name.isdigit() and int(name) != os.getpid():
            try:
                with open(f"/proc/{name}/cmdline", "rb") as f:
                    if marker.encode() in f.read():
                        found.append(int(name))
            except OSError:
                pass
    return found


def kill_all(pids: list[int]) -> None:
    for pid in pids:
        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass


# ---------------------------------------------------------------- honest work


def test_an_honest_program_runs_normally(run_brick):
    """Not a trick: imports, threads, files in the scratch folder, randomness, a socket pair,
    /dev/null and a child interpreter must all still work inside."""
    brick = run_brick(
        """
        import os, subprocess, sys, tempfile
        fresh = [m for m in ("statistics", "fractions", "csv", "zoneinfo", "decimal") if m not in sys.modules]
        attempt("fresh stdlib imports", lambda: [__import__(m).__name__ for m in fresh])
        attempt("everyday imports", lambda: [__import__(m).__name__ for m in ("json", "collections", "random", "math", "threading")])

        def threads():
            import threading
            done = []
            workers = [threading.Thread(target=done.append, args=(i,)) for i in range(8)]
            for worker in workers:
                worker.start()
            for worker in workers:
                worker.join()
            assert len(done) == 8
        attempt("threads", threads)

        def scratch_files():
            folder = os.path.join(ARGS["scratch"], "notes")
            os.makedirs(folder)
            with open(os.path.join(folder, "a.txt"), "w") as f:
                f.write("hello")
            os.rename(os.path.join(folder, "a.txt"), os.path.join(folder, "b.txt"))
            with open(os.path.join(folder, "b.txt")) as f:
                assert f.read() == "hello"
            os.remove(os.path.join(folder, "b.txt"))
            os.rmdir(folder)
        attempt("scratch files", scratch_files)
        attempt("tempfile", lambda: os.close(tempfile.mkstemp()[0]))
        attempt("urandom", lambda: len(os.urandom(16)))
        attempt("socketpair", lambda: [s.close() for s in __import__("socket").socketpair()])
        attempt("devnull", lambda: open(os.devnull, "w").write("x"))
        attempt("child interpreter", lambda: subprocess.run([sys.executable, "-c", "print(6 * 7)"], capture_output=True, text=True, check=True).stdout)
        """
    )
    names = ["fresh stdlib imports", "everyday imports", "threads", "scratch files", "tempfile", "urandom"]
    honest(brick, [*names, "socketpair", "devnull", "child interpreter"])
    assert brick.results["child interpreter"]["value"] == repr("42\n")
    assert brick.returncode == 0, brick.describe()


def test_entering_leaves_the_runs_random_seed_alone(run_brick):
    """Not a trick: the sandbox's own forks (Python reseeds `random` after a fork) must not undo
    the seed the brick's runtime set, or a run would not be the same twice."""
    import random

    brick = run_brick("import random\nattempt('draw', random.random)", seed=1234)
    assert brick.results["draw"]["value"] == repr(random.Random(1234).random())


@pytest.mark.skipif(
    not (importlib.util.find_spec("numpy") and importlib.util.find_spec("PIL")),
    reason="numpy or Pillow missing",
)
def test_numpy_and_pillow_import_inside(run_brick):
    """Not a trick: the site-packages a program may use are readable, though ev3sim2d's own package is not."""
    brick = run_brick(
        """
        import os
        def use_numpy():
            import numpy
            return float(numpy.random.default_rng(1).random(3).sum())
        def use_pillow():
            from PIL import Image
            Image.new("RGB", (8, 8), "red").save(os.path.join(ARGS["scratch"], "red.png"))
        attempt("numpy", use_numpy)
        attempt("pillow", use_pillow)
        attempt("ev3sim2d's grader", lambda: __import__("ev3sim2d.grading.grader"))
        """
    )
    honest(brick, ["numpy", "pillow"])
    stopped(brick, ["ev3sim2d's grader"], ("landlock",))


def test_a_child_interpreter_inherits_the_sandbox(run_brick, outside):
    """Trick: start a new interpreter in the hope that it runs outside the sandbox."""
    brick = run_brick(
        """
        import subprocess, sys
        def child(code):
            done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
            if done.returncode:
                raise OSError(done.stderr.strip().splitlines()[-1])
            return done.stdout
        attempt("child reads the hidden file", lambda: child(f"print(open({ARGS['hidden']!r}).read())"))
        attempt("child opens a socket", lambda: child("import socket; socket.socket()"))
        attempt("child says hello", lambda: child("print('hello')"))
        attempt("system python3", lambda: subprocess.run(["python3", "-c", "print(1)"], capture_output=True, check=True))
        attempt("system python3 reads the hidden file", lambda: subprocess.run(["python3", "-c", f"open({ARGS['hidden']!r}).read()"], capture_output=True, check=True))
        """,
        args={"hidden": str(outside / "hidden.yaml")},
    )
    honest(brick, ["child says hello"])
    stopped(brick, ["child reads the hidden file", "system python3 reads the hidden file"], ("landlock",))
    if shutil.which("python3", path="/usr/local/bin:/usr/bin:/bin"):
        honest(brick, ["system python3"])
    stopped(brick, ["child opens a socket"], ("seccomp",))


# ---------------------------------------------------------------- the network


def test_no_tcp_connection_to_the_host(run_brick):
    """Trick: connect to a server on 127.0.0.1 (the grader's, a database, a proxy) to report or fetch answers."""
    with socket.create_server(("127.0.0.1", 0)) as server:
        server.settimeout(0.3)
        brick = run_brick(
            """
            import socket
            attempt("tcp connect", lambda: socket.create_connection(("127.0.0.1", ARGS["port"]), timeout=2))
            attempt("tcp listen", lambda: socket.create_server(("0.0.0.0", 0)))
            attempt("ipv6", lambda: socket.socket(socket.AF_INET6).connect(("::1", ARGS["port"])))
            def pair():
                a, b = socket.socketpair()
                a.send(b"x")
                return b.recv(1)
            attempt("socketpair", pair)
            """,
            args={"port": server.getsockname()[1]},
        )
        assert accepted(server) == brick.worked("tcp connect"), brick.describe()
    honest(brick, ["socketpair"])
    stopped(brick, ["tcp connect", "tcp listen", "ipv6"], ("seccomp", "net_ns", "landlock_net"))


def test_no_udp_datagram_leaves(run_brick):
    """Trick: send the answers out in UDP datagrams (DNS-style exfiltration)."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as receiver:
        receiver.bind(("127.0.0.1", 0))
        receiver.settimeout(0.3)
        brick = run_brick(
            """
            import socket
            def send():
                with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
                    s.sendto(b"answers", ("127.0.0.1", ARGS["port"]))
            attempt("udp send", send)
            """,
            args={"port": receiver.getsockname()[1]},
        )
        try:
            arrived = receiver.recvfrom(100)[0] == b"answers"
        except TimeoutError:
            arrived = False
        assert arrived == brick.worked("udp send"), brick.describe()
    stopped(brick, ["udp send"], ("seccomp", "net_ns"))


def accepted(server: socket.socket) -> bool:
    """Whether a connection came to the listening server (within its timeout)."""
    try:
        server.accept()[0].close()
        return True
    except TimeoutError:
        return False


@pytest.mark.skipif(not hasattr(socket, "AF_UNIX"), reason="no unix sockets on this system")
def test_no_unix_socket_outside_the_scratch_folder(run_brick, outside):
    """Trick: connect to a unix socket on the machine (a daemon, the grader's control socket),
    by path or in the abstract namespace."""
    path = outside / "grader.sock"
    abstract = f"\0ev3sim2d-grader-{uuid.uuid4().hex}"
    with socket.socket(socket.AF_UNIX) as by_path, socket.socket(socket.AF_UNIX) as by_name:
        by_path.bind(str(path))
        path.chmod(0o777)
        by_path.listen()
        by_path.settimeout(0.2)
        by_name.bind(abstract)
        by_name.listen()
        by_name.settimeout(0.2)
        brick = run_brick(
            """
            import socket
            attempt("unix path", lambda: socket.socket(socket.AF_UNIX).connect(ARGS["path"]))
            attempt("abstract unix", lambda: socket.socket(socket.AF_UNIX).connect("\\0" + ARGS["name"]))
            """,
            args={"path": str(path), "name": abstract[1:]},
        )
        assert accepted(by_path) == brick.worked("unix path"), brick.describe()
        assert accepted(by_name) == brick.worked("abstract unix"), brick.describe()
    stopped(brick, ["unix path"], ("seccomp",))
    stopped(brick, ["abstract unix"], ("seccomp", "net_ns", "landlock_scope"))


# ---------------------------------------------------------------- files


def test_hidden_files_cannot_be_read_or_listed(run_brick, outside, tmp_path):
    """Trick: read the hidden variants (a teacher's folder, the lessons/ folder), the grader's code,
    or list folders to find them."""
    lessons = REPO / "lessons"
    variant = next(lessons.glob("*/hidden/*.yaml"), None) or next(lessons.rglob("*.yaml"))
    own = tmp_path / "program"
    own.mkdir()
    (own / "data.txt").write_text("mine")
    own.chmod(0o755)
    (own / "data.txt").chmod(0o644)
    brick = run_brick(
        """
        import os
        read = lambda path: open(path).read()
        attempt("read outside", lambda: read(ARGS["hidden"]))
        attempt("list outside", lambda: os.listdir(ARGS["outside"]))
        attempt("list lessons", lambda: os.listdir(ARGS["lessons"]))
        attempt("read a hidden variant", lambda: read(ARGS["variant"]))
        attempt("read the grader", lambda: read(ARGS["grader"]))
        attempt("read /etc/passwd", lambda: read("/etc/passwd"))
        attempt("read its own folder", lambda: read(ARGS["own"]))
        """,
        args={
            "hidden": str(outside / "hidden.yaml"),
            "outside": str(outside),
            "lessons": str(lessons),
            "variant": str(variant),
            "grader": str(REPO / "ev3sim2d" / "grading" / "grader.py"),
            "own": str(own / "data.txt"),
        },
        read=[own],
    )
    honest(brick, ["read its own folder"])
    tricks = ["read outside", "list outside", "list lessons", "read a hidden variant", "read the grader"]
    stopped(brick, [*tricks, "read /etc/passwd"], ("landlock",))


def test_nothing_can_be_written_outside_the_scratch_folder(run_brick, outside):
    """Trick: leave something behind for later runs or other students (a .pth or usercustomize.py
    in site-packages, a file in $HOME, a poisoned __pycache__), or write into the grader's output."""
    tag = uuid.uuid4().hex[:8]
    targets = {
        "site-packages .pth": Path(SITE_PACKAGES[0]) / f"ev3sim2d_evil_{tag}.pth",
        "site-packages usercustomize": Path(SITE_PACKAGES[0]) / "usercustomize.py",
        "home": Path.home() / f"ev3sim2d-evil-{tag}",
        "user site usercustomize": Path(site.getusersitepackages()) / "usercustomize.py",
        "repository __pycache__": REPO / "ev3sim2d" / "__pycache__" / f"evil-{tag}.cpython-311.pyc",
        "test output folder": outside / "drop" / f"evil-{tag}",
        "temporary folder": Path(tempfile.gettempdir()) / f"ev3sim2d-evil-{tag}",
        "shared memory folder": Path("/dev/shm") / f"ev3sim2d-evil-{tag}",
    }
    if run_brick.elsewhere:  # writes get through there: nothing that would change this machine's Python
        targets = {name: targets[name] for name in ("test output folder", "temporary folder", "home")}
    targets = {name: path for name, path in targets.items() if not path.exists()}
    brick = run_brick(
        """
        import os
        def write(path):
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w") as f:
                f.write("import os; os.system('echo pwned')\\n")
        for name, path in ARGS["targets"].items():
            attempt(name, lambda: write(path))
        attempt("scratch", lambda: write(os.path.join(ARGS["scratch"], "mine.txt")))
        """,
        args={"targets": {name: str(path) for name, path in targets.items()}},
    )
    written = [name for name, path in targets.items() if path.exists()]
    for name in written:
        targets[name].unlink()
    assert written == [name for name in targets if brick.worked(name)], brick.describe()
    honest(brick, ["scratch"])
    stopped(brick, list(targets), ("landlock",))


# ---------------------------------------------------------------- other processes


def test_other_processes_cannot_be_seen(run_brick, stand_in):
    """Trick: look at the grader's process (its command line, its environment with tokens, its
    memory) or find other students' bricks in /proc."""
    grader = stand_in.pid if run_brick.elsewhere else os.getpid()
    brick = run_brick(
        """
        import os
        pid = ARGS["grader"]
        def see_in_proc():
            assert str(pid) in os.listdir("/proc"), "not listed"
        attempt("list /proc", see_in_proc)
        attempt("kill 0", lambda: os.kill(pid, 0))
        for part in ("cmdline", "environ", "mem", "status"):
            attempt(part, lambda: open(f"/proc/{pid}/{part}", "rb").read(100))
        attempt("itself", lambda: os.kill(os.getpid(), 0))
        """,
        args={"grader": grader},
    )
    honest(brick, ["itself"])
    stopped(brick, ["list /proc", "kill 0", "cmdline", "environ", "mem", "status"], ("pid_ns", "landlock"))


def test_the_grader_and_other_bricks_cannot_be_signalled(run_brick, stand_in):
    """Trick: kill or stop the grader, or another student's brick running as the same user
    (kill by pid, kill(-1) for everything in reach, the parent).  Where the walls are missing
    (another system) the grader is a stand-in, and kill(-1) and the parent (this test) are left out."""
    sleep = shutil.which("sleep")  # (a program the brick's user may run; Windows has none)
    other_brick = subprocess.Popen(
        [sleep, "60"] if sleep else [sys.executable, "-c", "import time; time.sleep(60)"],
        **({"start_new_session": True} if hasattr(os, "setsid") else {}),
        **({"user": BRICK_UID, "group": BRICK_UID, "extra_groups": []} if AS_ROOT else {}),
    )
    grader = stand_in.pid if run_brick.elsewhere else os.getpid()
    try:
        brick = run_brick(
            """
            import os, signal
            test, other = ARGS["grader"], ARGS["other"]
            kill = lambda pid, name: os.kill(pid, getattr(signal, name, signal.SIGTERM))
            attempt("SIGTERM to the grader", lambda: kill(test, "SIGTERM"))
            attempt("SIGKILL to the grader", lambda: kill(test, "SIGKILL"))
            attempt("SIGSTOP to the grader", lambda: kill(test, "SIGSTOP"))
            attempt("SIGKILL to another brick", lambda: kill(other, "SIGKILL"))
            attempt("SIGKILL to its group", lambda: os.killpg(other, signal.SIGKILL))
            if ARGS["everything"]:
                attempt("kill(-1)", lambda: os.kill(-1, signal.SIGKILL))
                parent = os.getppid()
                attempt("its parent", lambda: parent > 1 and os.kill(parent, signal.SIGKILL))
            if hasattr(os, "fork"):
                child = os.fork()
                if child == 0:
                    signal.pause()
                attempt("its own child", lambda: os.kill(child, signal.SIGKILL))
                os.waitpid(child, 0)
            """,
            args={"other": other_brick.pid, "grader": grader, "everything": not run_brick.elsewhere},
        )
        time.sleep(0.1)
        assert (other_brick.poll() is not None) == brick.worked("SIGKILL to another brick"), brick.describe()
        if run_brick.elsewhere:
            assert (stand_in.poll() is not None) == brick.worked("SIGKILL to the grader"), brick.describe()
    finally:
        other_brick.kill()
        other_brick.wait()
    if brick.system != "windows":  # (no fork there)
        honest(brick, ["its own child"])
    tricks = ["SIGTERM to the grader", "SIGKILL to the grader", "SIGSTOP to the grader"]
    tricks += ["SIGKILL to another brick", "SIGKILL to its group"]
    stopped(brick, tricks, ("pid_ns", "landlock_scope"))
    if "its parent" in brick.results and brick.results["its parent"]["value"] != "False":
        stopped(brick, ["its parent"], ("landlock_scope",))  # no PID namespace: the parent is the grader


def test_no_ptrace_or_reading_another_process_memory(run_brick, stand_in):
    """Trick: attach with ptrace (via ctypes) to the grader, or to a child that would then be steered,
    or read another process's memory with process_vm_readv (where the walls are missing, the grader
    is a stand-in)."""
    grader = stand_in.pid if run_brick.elsewhere else os.getpid()
    brick = run_brick(
        """
        import ctypes, os, signal
        try:
            libc = ctypes.CDLL(None, use_errno=True)
            ptrace, readv = libc.ptrace, libc.process_vm_readv
        except (OSError, TypeError, AttributeError) as err:  # no such C library here: nothing to try
            for name in ("attach to the grader", "attach to its own child", "traceme", "process_vm_readv"):
                attempt(name, lambda: (_ for _ in ()).throw(err))
            raise SystemExit
        def call(result):
            if result == -1:
                err = ctypes.get_errno()
                raise OSError(err, os.strerror(err))
            return result
        PTRACE_TRACEME, PTRACE_ATTACH, PTRACE_SEIZE = 0, 16, 0x4206
        attempt("attach to the grader", lambda: call(ptrace(PTRACE_ATTACH, ARGS["grader"], None, None)))
        child = os.fork()
        if child == 0:
            signal.pause()
        attempt("attach to its own child", lambda: call(ptrace(PTRACE_SEIZE, child, None, None)))
        os.kill(child, signal.SIGKILL)
        os.waitpid(child, 0)
        attempt("traceme", lambda: call(ptrace(PTRACE_TRACEME, 0, None, None)))
        buffer = ctypes.create_string_buffer(64)
        local = (ctypes.c_void_p * 2)(ctypes.addressof(buffer), 64)
        remote = (ctypes.c_void_p * 2)(0x400000, 64)
        attempt("process_vm_readv", lambda: call(readv(ARGS["grader"], local, 1, remote, 1, 0)))
        """,
        args={"grader": grader},
    )
    tricks = ["attach to the grader", "attach to its own child", "traceme", "process_vm_readv"]
    stopped(brick, tricks, ("seccomp",))


# ---------------------------------------------------------------- privileges and limits


def report_of(run_brick, **options) -> dict:
    """The report of a brick that plays no trick: what it says it has, before a trick that would harm
    this machine where the wall against it is missing."""
    return run_brick("pass", **options).report


def test_limits_cannot_be_raised(run_brick):
    """Trick: raise the CPU, memory, file size, process or open-file limits back up."""
    if run_brick.system == "windows":
        assert report_of(run_brick)["rlimits"].startswith("off: "), "no resource limits to raise there"
        return
    brick = run_brick(
        """
        import resource
        names = ("RLIMIT_CPU", "RLIMIT_AS", "RLIMIT_FSIZE", "RLIMIT_NPROC", "RLIMIT_NOFILE", "RLIMIT_CORE")
        limits = {name: resource.getrlimit(getattr(resource, name)) for name in names}
        attempt("limits", lambda: limits)
        for name, (soft, hard) in limits.items():
            which = getattr(resource, name)
            attempt(f"raise {name}", lambda: resource.setrlimit(which, (resource.RLIM_INFINITY, resource.RLIM_INFINITY)))
            attempt(f"raise {name} by one", lambda: resource.setrlimit(which, (hard + 1, hard + 1)))
        soft, hard = limits["RLIMIT_NOFILE"]
        attempt("lower a limit", lambda: resource.setrlimit(resource.RLIMIT_NOFILE, (soft - 1, hard)))
        """,
        limits={"cpu_s": 30, "file_mb": 8, "open_files": 100},
    )
    honest(brick, ["limits", "lower a limit"])
    limits = eval(brick.results["limits"]["value"])
    assert limits["RLIMIT_CPU"] == (30, 31)
    assert limits["RLIMIT_FSIZE"] == (8 * 2**20, 8 * 2**20)
    assert limits["RLIMIT_NOFILE"] == (100, 100)
    assert limits["RLIMIT_CORE"] == (0, 0)
    names = ("RLIMIT_CPU", "RLIMIT_AS", "RLIMIT_FSIZE", "RLIMIT_NPROC", "RLIMIT_NOFILE", "RLIMIT_CORE")
    stopped(brick, [f"raise {name}{by}" for name in names for by in ("", " by one")], ("capabilities",))


def test_no_capabilities_left_even_when_started_as_root(run_brick):
    """Trick: use what root (CI and containers run as root) or a user namespace's owner could do:
    become uid 0 again, chown, change groups, hold any capability."""
    if run_brick.elsewhere:  # capabilities are Linux's; elsewhere the report must not claim them
        report = report_of(run_brick)
        assert report["capabilities"] == sandbox.NOT_HERE, report
        assert not report["root_dropped"].startswith("on"), report
        return
    brick = run_brick(
        """
        import ctypes, os, struct
        libc = ctypes.CDLL(None, use_errno=True)
        def capabilities():
            header = ctypes.create_string_buffer(struct.pack("Ii", 0x20080522, 0))
            data = ctypes.create_string_buffer(24)
            assert libc.capget(header, data) == 0
            sets = struct.unpack("6I", data.raw)
            bounding = [c for c in range(64) if libc.prctl(23, ctypes.c_ulong(c), 0, 0, 0) == 1]
            ambient = [c for c in range(64) if libc.prctl(47, 1, ctypes.c_ulong(c), 0, 0) == 1]
            return {"sets": sets, "bounding": bounding, "ambient": ambient, "uids": os.getresuid()}
        attempt("capabilities", capabilities)
        attempt("setuid 0", lambda: os.setuid(0))
        attempt("setgroups", lambda: os.setgroups([0]))
        path = os.path.join(ARGS["scratch"], "mine")
        open(path, "w").close()
        attempt("chown to root", lambda: os.chown(path, 0, 0))
        attempt("chmod setuid", lambda: os.chmod(path, 0o4755) or os.stat(path).st_mode & 0o4000 or None)
        """
    )
    held = eval(brick.results["capabilities"]["value"])
    assert held["sets"] == (0,) * 6 and held["ambient"] == [], held
    if brick.report.get("root_dropped", "").startswith("on") or brick.report.get("user_ns") == "on":
        assert held["bounding"] == [], held
    if os.geteuid() == 0 and not AS_ROOT:  # a rootless container's root stays uid 0, without capabilities
        stopped(brick, ["setgroups"], ("capabilities",))
        return
    assert 0 not in held["uids"], held
    if AS_ROOT:
        require(brick, "root_dropped")
    stopped(brick, ["setuid 0", "setgroups", "chown to root"], ("capabilities",))


@pytest.mark.needs_linux("proc")  # (processes_with: what is left, found in /proc)
def test_nothing_the_program_starts_outlives_it(run_brick, scratch):
    """Trick: setsid() and fork a grandchild that sleeps through the end of the run and then
    writes a file (or rewrites the reports)."""
    if run_brick.system == "windows":  # no fork there; a Job Object ends the brick's processes
        assert report_of(run_brick)["pid_ns"] == sandbox.NOT_HERE  # (tests/portable: the brick's end)
        return
    marker = f"ev3sim2d-outlive-{uuid.uuid4().hex}"
    late = scratch / "late"
    try:
        brick = run_brick(
            """
            import os, sys, time
            grandchild = "import sys, time; open(sys.argv[1] + '.started', 'w').close(); time.sleep(2); open(sys.argv[1], 'w').close()"
            def setsid_in_a_child():  # refused by the sandbox: a brick's processes stay in its session
                child = os.fork()
                if child == 0:
                    try:
                        os.setsid()
                        os._exit(0)
                    except OSError:
                        os._exit(1)
                return os.waitstatus_to_exitcode(os.waitpid(child, 0)[1]) == 0 or 1 / 0
            attempt("setsid", setsid_in_a_child)
            pid = os.fork()
            if pid == 0:
                try:
                    os.setsid()
                except OSError:
                    pass
                if os.fork() == 0:
                    quiet = os.open(os.devnull, os.O_RDWR)
                    for fd in (0, 1, 2):
                        os.dup2(quiet, fd)
                    os.execv(sys.executable, [sys.executable, "-c", grandchild, ARGS["late"], ARGS["marker"]])
                os._exit(0)
            os.waitpid(pid, 0)
            for _ in range(100):
                if os.path.exists(ARGS["late"] + ".started"):
                    break
                time.sleep(0.05)
            attempt("grandchild started", lambda: os.path.exists(ARGS["late"] + ".started") or 1 / 0)
            """,
            args={"late": str(late), "marker": marker},
        )
        honest(brick, ["grandchild started"])
        stopped(brick, ["setsid"], ("seccomp",))
        left = processes_with(marker)
        if left:
            require(brick, "pid_ns")
        assert left == [], "a process of the program outlived it"
        time.sleep(2.5)
        assert not late.exists(), "the grandchild wrote its file after the run"
    finally:
        kill_all(processes_with(marker))


def test_a_fork_bomb_is_limited(run_brick):
    """Trick: fork without end to starve the machine (and the other students' runs)."""
    if run_brick.elsewhere:  # not played where nothing limits it: the report must say so
        report = report_of(run_brick, limits={"processes": 16})
        assert (
            report["rlimits"].startswith("off: ") or "processes" in report["rlimits"].split("not limited")[-1]
        )
        return
    marker = f"ev3sim2d-bomb-{uuid.uuid4().hex}"
    try:
        brick = run_brick(
            """
            import os, time
            def bomb():
                children = 0
                try:
                    while children < 2000:
                        if os.fork() == 0:
                            time.sleep(30)
                            os._exit(0)
                        children += 1
                except OSError as err:
                    return children, type(err).__name__
                return children, None
            attempt("bomb", bomb)
            """,
            limits={"processes": 16},
            args={"marker": marker},
        )
        children, error = eval(brick.results["bomb"]["value"])
        assert error == "BlockingIOError" and children <= 16, (children, error)
        assert brick.seconds < 10
        assert processes_with(marker) == [] or brick.report["pid_ns"] != "on"
    finally:
        kill_all(processes_with(marker))


def test_a_memory_hog_gets_memory_error(run_brick):
    """Trick: allocate memory without end to make the machine swap or the grader die of OOM."""
    if run_brick.elsewhere:  # a brick's own limit where the system has one; the report says which
        report = report_of(run_brick, limits={"memory_mb": 128})
        if report["rlimits"].startswith("off: ") or "memory" in report["rlimits"].split("not limited")[-1]:
            return  # (a Job Object limits the brick's memory from outside on Windows: tests/simulator)
    brick = run_brick(
        """
        attempt("one big block", lambda: len(bytearray(1024 * 2**20)))
        def grow():
            blocks = []
            while len(blocks) < 4096:
                blocks.append(bytearray(2**20))
            return len(blocks)
        attempt("growing", grow)
        attempt("16 MB", lambda: len(bytearray(16 * 2**20)))
        """,
        limits={"memory_mb": 128},
    )
    honest(brick, ["16 MB"])
    for name in ("one big block", "growing"):
        assert brick.results[name]["error"].startswith("MemoryError"), brick.results[name]
    stopped(brick, ["one big block", "growing"], ("rlimits",))


def test_an_endless_writer_is_stopped_at_the_file_limit(run_brick, scratch):
    """Trick: write a file without end to fill the grader's disk."""
    if run_brick.system == "windows":
        assert report_of(run_brick)["rlimits"].startswith("off: ")  # (no file size limit there)
        return
    brick = run_brick(
        """
        import os
        with open(os.path.join(ARGS["scratch"], "big"), "wb") as f:
            while True:
                f.write(b"x" * 65536)
        """,
        limits={"file_mb": 2},
    )
    assert brick.returncode == -signal.SIGXFSZ, brick.describe()
    assert (scratch / "big").stat().st_size == 2 * 2**20


def test_a_cpu_hog_is_stopped_at_the_cpu_limit(run_brick):
    """Trick: spin in a loop the simulator's clock never sees (an endless busy loop of real CPU)."""
    if run_brick.system == "windows":  # a Job Object's CPU time limit ends it there (tests/simulator)
        assert report_of(run_brick)["rlimits"].startswith("off: ")
        return
    brick = run_brick("while True:\n    pass\n", limits={"cpu_s": 1})
    assert brick.returncode in (-signal.SIGXCPU, -signal.SIGKILL), brick.describe()
    assert brick.seconds < 8


# ---------------------------------------------------------------- the report, the probe and the doctor


def test_every_layer_is_reported_and_on(run_brick):
    """Not a trick: the report names every layer, and on this machine (in CI: all) they are on.
    Elsewhere Linux's layers are reported as not this system's, and what the system has is on."""
    brick = run_brick("pass")
    assert set(LAYERS) <= set(brick.report), brick.report
    assert brick.returncode == 0
    if brick.elsewhere:
        assert {
            layer: brick.report[layer] for layer in sandbox.LINUX_LAYERS if layer != "root_dropped"
        } == dict.fromkeys(set(sandbox.LINUX_LAYERS) - {"root_dropped"}, sandbox.NOT_HERE)
        assert brick.report["fds"].startswith("on")
        posix = brick.system == "macos"
        assert brick.report["session"].startswith("on" if posix else "off: "), brick.report
        assert brick.report["rlimits"].startswith("on (cpu" if posix else "off: "), brick.report
        return
    layers = [layer for layer in LAYERS if layer != "root_dropped"]
    require(brick, *layers)
    if AS_ROOT:
        assert brick.report["root_dropped"].startswith("on"), brick.report
    elif os.geteuid() == 0:  # root of a rootless container
        assert brick.report["root_dropped"].startswith("off: uid 65534 does not exist"), brick.report
    else:
        assert brick.report["root_dropped"] == "not root", brick.report


@pytest.mark.needs_linux("proc")  # (NoNewPrivs read in /proc/self/status)
def test_probe_says_what_the_kernel_offers():
    """Not a trick: probe() tells, without entering anything, what a brick would get here."""
    before = _status_line("NoNewPrivs")
    facts = sandbox.probe()
    assert _status_line("NoNewPrivs") == before, "probing changed this process"
    for key in (
        "kernel",
        "machine",
        "root",
        "landlock_abi",
        "landlock",
        "user_ns",
        "seccomp",
        "no_new_privs",
    ):
        assert key in facts, facts
    assert isinstance(facts["landlock_abi"], int)
    assert facts["landlock"] == (
        f"on (ABI {facts['landlock_abi']})" if facts["landlock_abi"] else facts["landlock"]
    )
    for key in ("landlock", "user_ns", "seccomp", "namespaces_as_root"):
        assert facts[key].startswith(("on", "off: ", "not root")), facts[key]
    assert sandbox.seccomp_program() is None or len(sandbox.seccomp_program()) % 8 == 0


def _status_line(key: str) -> str:
    with open("/proc/self/status") as f:
        return next(line for line in f if line.startswith(key + ":"))


@pytest.mark.needs_linux("linux_kernel")  # (elsewhere the doctor lists Linux's layers as others')
def test_doctor_prints_a_line_per_layer():
    """Not a trick: `ev3sim2d doctor` says, layer by layer, what a brick gets here; exit 0."""
    from ev3sim2d.commands import doctor

    done = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "doctor"], capture_output=True, text=True, timeout=60, cwd=REPO
    )
    assert done.returncode == 0, done.stderr
    lines = [line for line in done.stdout.splitlines() if line.startswith(("  on ", "  OFF "))]
    others = next((line for line in done.stdout.splitlines() if line.startswith("other systems' layers")), "")
    here = [layer for layer in doctor.LAYERS if layer.key not in doctor.OUTSIDE]
    assert len(lines) == len(here), done.stdout  # every layer of this system, a line each
    for layer, line in zip(here, lines, strict=True):
        assert layer.title in line, (layer.title, line)
    for layer in doctor.LAYERS:
        if layer not in here:
            assert layer.title in others, done.stdout  # the others are named once
    version = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "--version"], capture_output=True, text=True, timeout=60, cwd=REPO
    )
    assert version.returncode == 0, version.stderr
    assert version.stdout.startswith("ev3sim2d ")
    assert version.stdout.splitlines()[1].startswith("isolation: ")


@pytest.mark.skipif(
    not AS_ROOT or not os.access("/usr/bin/python3", os.X_OK), reason="needs root and /usr/bin/python3"
)
def test_a_user_with_many_processes_still_gets_its_own_process_limit(run_brick, outside):
    """Not a trick: a teacher's own account (not root) already runs many processes; the program
    must still get its `processes`, since its brick has a user namespace of its own, and every
    wall must stand as well as for root."""
    if run_brick.elsewhere:
        pytest.skip("a setup of Linux's (user namespaces, other users): nothing like it elsewhere")
    uid = 54321
    scratch = outside / "teacher-scratch"  # pytest's own temporary folder is closed to other users
    scratch.mkdir()
    shutil.chown(scratch, uid, uid)
    crowd = [
        subprocess.Popen(["sleep", "30"], user=uid, group=uid, extra_groups=[], start_new_session=True)
        for _ in range(40)
    ]
    try:
        brick = run_brick(
            """
            import os, threading, time
            def threads():
                workers = [threading.Thread(target=time.sleep, args=(0.2,)) for _ in range(6)]
                for worker in workers:
                    worker.start()
                for worker in workers:
                    worker.join()
            attempt("threads", threads)
            attempt("read outside", lambda: open(ARGS["hidden"]).read())
            attempt("signal the crowd", lambda: os.kill(ARGS["crowd"], 9))
            """,
            limits={"processes": 8},
            args={"hidden": str(outside / "hidden.yaml"), "crowd": crowd[0].pid},
            python="/usr/bin/python3",
            user=uid,
            scratch=scratch,
        )
        assert all(p.poll() is None for p in crowd)
    finally:
        for p in crowd:
            p.kill()
            p.wait()
    require(brick, "user_ns", "pid_ns")
    assert brick.report["root_dropped"] == "not root"
    honest(brick, ["threads"])
    stopped(brick, ["read outside", "signal the crowd"], ("landlock", "pid_ns"))


@pytest.mark.skipif(shutil.which("unshare") is None, reason="needs unshare(1)")
def test_root_of_a_rootless_container_is_treated_as_the_user_it_is(run_brick, outside):
    """Not a trick: in a rootless container, root is an ordinary user of the host that cannot
    become uid 65534; the brick must still put up every other wall, and say root stayed."""
    if run_brick.elsewhere:
        pytest.skip("a setup of Linux's (user namespaces, other users): nothing like it elsewhere")
    if os.geteuid() == 0:  # be an ordinary user of the host first, as a rootless container's root is
        if not os.access("/usr/bin/python3", os.X_OK):
            pytest.skip("needs /usr/bin/python3 to run as an ordinary user")
        scratch = outside / "rootless-scratch"
        scratch.mkdir()
        shutil.chown(scratch, 54321, 54321)
        become = ("setpriv", "--reuid=54321", "--regid=54321", "--clear-groups")
        python = "/usr/bin/python3"
    else:
        scratch, become, python = None, (), sys.executable
    wrapper = (*become, "unshare", "--user", "--map-root-user")
    trial = subprocess.run([*wrapper, "true"], capture_output=True)
    if trial.returncode != 0:
        if IN_CI:
            pytest.fail(f"CI machines must allow user namespaces: {trial.stderr!r}")
        pytest.skip(f"no user namespace here: {trial.stderr.decode().strip()}")
    brick = run_brick(
        """
        import os
        attempt("read outside", lambda: open(ARGS["hidden"]).read())
        attempt("uid", lambda: os.getresuid())
        attempt("json", lambda: __import__("json").dumps([1]))
        """,
        args={"hidden": str(outside / "hidden.yaml")},
        wrapper=wrapper,
        python=python,
        **({"scratch": scratch} if scratch else {}),
    )
    assert brick.report["root_dropped"].startswith("off: uid 65534 does not exist"), brick.report
    require(brick, "user_ns", "pid_ns", "net_ns", "capabilities", "landlock", "seccomp")
    honest(brick, ["uid", "json"])
    stopped(brick, ["read outside"], ("landlock",))


@pytest.mark.skipif(not AS_ROOT or shutil.which("unshare") is None, reason="needs root and unshare(1)")
def test_the_machines_root_behind_a_user_namespace_is_refused(run_brick):
    """Not a trick of the student's, but a setup to refuse: root seen through a user namespace
    that cannot become uid 65534 is still the machine's root (owner of its files, exempt from the
    process limit); the brick must not run the program at all."""
    if run_brick.elsewhere:
        pytest.skip("a setup of Linux's (user namespaces, other users): nothing like it elsewhere")
    with pytest.raises(AssertionError, match="root here is the machine's root"):
        run_brick("attempt('ran', lambda: 1)", wrapper=("unshare", "--user", "--map-root-user"))
