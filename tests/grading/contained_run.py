"""A throwaway machine for `ev3sim2d grade` runs of hostile programs: a PID and a mount namespace, and what they left.

test_cheating.py grades programs that kill every process they can see, write into site-packages,
the home folder and the lesson, and leave processes behind to rewrite the reports.  Until ev3sim2d
contains them itself they succeed, so they are never run on the machine as it is:
- in a PID namespace whose first process is this script (`unshare --pid --fork --mount-proc`):
  `kill(-1)` reaches only the run, an orphan is handed to this script (so it is found), and
  everything in the namespace ends when this script does;
- in a mount namespace where the Python installation, the code under test, the home folder and
  /etc are overlays: a write lands in an upper folder the test reads, never in the real files;
- optionally in a pids cgroup, so that a fork bomb stops at its limit.
The network is the machine's: the test listens on 127.0.0.1 for what the programs send.

Each step of a plan is one command (a grading): it runs to its end, its timeout, or until it has
been stopped (SIGSTOP) for STOPPED_S; its output files are copied as it ends, before its pid is
free (a process waiting for the grader to go sees it there until then); after `settle_s` they are
copied again, and the step's leftovers are recorded (processes still alive, files left in its
TMPDIR) and the processes killed.  The report says all that.

The test's side: `isolation_problem()`, `overlay_dirs()`, `PidsCgroup`, `start()` and `finish()`.
This file is also the script: `python contained_run.py PLAN.json`, as the namespace's first process.
"""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import time
import uuid
from pathlib import Path

POLL_S = 0.02
STOPPED_S = 3.0


# -- the test's side --------------------------------------------------------------------------------


def isolation_problem() -> str | None:
    """Why hostile programs cannot be contained here (None when they can)."""
    if not sys.platform.startswith("linux"):
        return "needs Linux namespaces"
    if shutil.which("unshare") is None or shutil.which("mount") is None:
        return "needs unshare and mount (util-linux)"
    probe = subprocess.run(
        [*_unshare(), "sh", "-c", "mount -t tmpfs probe /mnt && umount /mnt"],
        capture_output=True,
        text=True,
        timeout=30,
    )
    if probe.returncode != 0:
        return f"cannot make a PID and mount namespace with overlays here: {probe.stderr.strip()}"
    return None


def _unshare() -> list[str]:
    user = [] if os.geteuid() == 0 else ["--user", "--map-root-user"]
    return [
        "unshare",
        *user,
        "--pid",
        "--fork",
        "--kill-child",
        "--mount",
        "--mount-proc",
        "--propagation",
        "private",
    ]


_WHERE_PYTHON_LOOKS = """
import importlib.util, json, os, sys
found = [sys.prefix, sys.base_prefix, *sys.path]
for name in ("ev3sim2d", "ev3dev2"):
    spec = importlib.util.find_spec(name)
    if spec and spec.origin:
        found.append(os.path.dirname(os.path.dirname(spec.origin)))
print(json.dumps(found))
"""


def overlay_dirs(python: str, env: dict) -> list[str]:
    """Folders a program run by `python` could write to change a later run: its installation, every
    folder on its sys.path, the code of ev3sim2d and its shim, the home folder and /etc; without folders
    inside others.  The temporary folder (where the test keeps its own files) must be outside them all."""
    found = subprocess.run(
        [python, "-c", _WHERE_PYTHON_LOOKS],
        capture_output=True,
        text=True,
        env=env,
        check=True,
    )
    import pwd
    import tempfile

    candidates = {str(Path(p).resolve()) for p in json.loads(found.stdout) if p}
    candidates |= {pwd.getpwuid(os.getuid()).pw_dir, "/etc"}
    keep_out = str(Path(tempfile.gettempdir()).resolve())
    dirs = []
    for candidate in sorted(candidates):
        path = Path(candidate)
        while not path.is_dir():  # a zip file on sys.path, or a missing entry: its folder
            path = path.parent
        if str(path) == "/":
            continue
        if keep_out == str(path) or keep_out.startswith(str(path) + "/"):
            raise RuntimeError(f"the temporary folder {keep_out} is inside {path}, which must be an overlay")
        dirs.append(str(path))
    top = []
    for d in sorted(set(dirs)):
        if not any(d == t or d.startswith(t + "/") for t in top):
            top.append(d)
    return top


class PidsCgroup:
    """A pids cgroup (v1 or v2) with a limit, for one contained run; `None` from `make` where there is none."""

    def __init__(self, folder: Path) -> None:
        self.folder = folder

    @classmethod
    def make(cls, limit: int) -> PidsCgroup | None:
        name = f"ev3sim2d-cheats-{uuid.uuid4().hex[:8]}"
        for parent in (Path("/sys/fs/cgroup/pids"), Path("/sys/fs/cgroup")):
            if not (parent / "cgroup.procs").exists():
                continue
            try:
                if parent == Path("/sys/fs/cgroup"):
                    controllers = (parent / "cgroup.subtree_control").read_text().split()
                    if "pids" not in controllers:
                        continue
                folder = parent / name
                folder.mkdir()
                (folder / "pids.max").write_text(str(limit))
                return cls(folder)
            except OSError:
                continue
        return None

    def join(self) -> None:
        """Put the calling process in the cgroup (from a preexec_fn: the run and all it starts)."""
        (self.folder / "cgroup.procs").write_text(str(os.getpid()))

    def remove(self) -> None:
        for _ in range(100):
            try:
                self.folder.rmdir()
                return
            except OSError:
                time.sleep(0.05)


def start(plan: dict, folder: Path, cgroup: PidsCgroup | None = None) -> subprocess.Popen:
    """Start the contained run of a plan (see `main`); its report will be `folder/report.json`."""
    folder.mkdir(parents=True, exist_ok=True)
    plan = {**plan, "report": str(folder / "report.json")}
    for i, (lower, *_) in enumerate(plan.get("overlays", [])):
        upper, work = folder / "overlay" / f"{i}-upper", folder / "overlay" / f"{i}-work"
        upper.mkdir(parents=True, exist_ok=True)
        work.mkdir(parents=True, exist_ok=True)
        plan["overlays"][i] = [lower, str(upper), str(work)]
    (folder / "plan.json").write_text(json.dumps(plan, indent=2))
    return subprocess.Popen(
        [*_unshare(), sys.executable, __file__, str(folder / "plan.json")],
        stdout=open(folder / "contained.out", "w"),  # noqa: SIM115 - closed with the process
        stderr=subprocess.STDOUT,
        preexec_fn=cgroup.join if cgroup else None,
    )


def finish(process: subprocess.Popen, folder: Path, timeout_s: float) -> dict:
    """Wait for the contained run and return its report (raises if it left none)."""
    try:
        process.wait(timeout_s)
    except subprocess.TimeoutExpired:
        process.kill()  # unshare --kill-child ends the namespace with it
        process.wait()
    if process.stdout:
        process.stdout.close()
    report = folder / "report.json"
    if not report.is_file():
        raise RuntimeError(
            f"the contained run left no report: {(folder / 'contained.out').read_text()[-3000:]}"
        )
    return json.loads(report.read_text())


def upper_files(report: dict) -> list[tuple[str, Path]]:
    """(the folder it would have changed, the file in the overlay's upper folder) for every file written."""
    found = []
    for lower, upper, _ in report["overlays"]:
        for path in Path(upper).rglob("*"):
            if path.is_file() or path.is_symlink():
                found.append((lower, path))
    return found


# -- the namespace's first process ----------------------------------------------------------------------


def _mount_overlays(overlays: list[list[str]]) -> None:
    for lower, upper, work in overlays:
        subprocess.run(
            [
                "mount",
                "-t",
                "overlay",
                "overlay",
                "-o",
                f"lowerdir={lower},upperdir={upper},workdir={work}",
                lower,
            ],
            check=True,
        )


class _Reaper:
    """Reaps every child that has ended (as the namespace's init) and keeps their exit status."""

    def __init__(self) -> None:
        self.status: dict[int, int] = {}

    def reap(self, keep: int | None = None) -> None:
        """Reap the ended children, but `keep` (its pid, still taken, tells whoever waits for it that it is there)."""
        for entry in os.listdir("/proc"):
            if entry.isdigit() and int(entry) != keep and _state(int(entry)) == "Z":
                try:
                    pid, status = os.waitpid(int(entry), os.WNOHANG)
                except ChildProcessError:
                    continue
                if pid:
                    self.status[pid] = os.waitstatus_to_exitcode(status)

    def wait(self, seconds: float) -> None:
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            self.reap()
            time.sleep(POLL_S)


def _state(pid: int) -> str:
    """The process's state letter (R, S, T, Z, ...), '' if it is gone."""
    stat = _read(f"/proc/{pid}/stat").decode(errors="replace")
    return stat.rsplit(")", 1)[-1].split()[0] if stat else ""


def _exited(pid: int) -> bool:
    """Whether the child has ended (without reaping it: while it is a zombie its pid stays taken)."""
    return os.waitid(os.P_PID, pid, os.WEXITED | os.WNOHANG | os.WNOWAIT) is not None


def _read(path: str) -> bytes:
    try:
        with open(path, "rb") as f:
            return f.read()
    except OSError:
        return b""


def _processes(marker: bytes) -> list[dict]:
    """Every process in the namespace but this one."""
    found = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit() or int(entry) == os.getpid():
            continue
        stat = _read(f"/proc/{entry}/stat").decode(errors="replace")
        if not stat:
            continue
        after_name = stat.rsplit(")", 1)[-1].split()
        cmdline = _read(f"/proc/{entry}/cmdline")
        environ = _read(f"/proc/{entry}/environ")
        found.append(
            {
                "pid": int(entry),
                "state": after_name[0] if after_name else "?",
                "ppid": int(after_name[1]) if len(after_name) > 1 else 0,
                "cmdline": cmdline.replace(b"\0", b" ").decode(errors="replace").strip()[:500],
                "marked": marker in cmdline or marker in environ,
            }
        )
    return found


def _end_all(reaper: _Reaper, seconds: float = 10.0) -> None:
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        left = [p for p in _processes(b"\0") if p["state"] != "Z"]
        reaper.reap()
        if not left:
            return
        for p in left:
            try:
                os.kill(p["pid"], signal.SIGKILL)
            except OSError:
                pass
        time.sleep(POLL_S)


def _listing(folder: str) -> list[str]:
    root = Path(folder)
    if not root.is_dir():
        return []
    return sorted(str(p.relative_to(root)) for p in root.rglob("*"))


def _copies(paths: list[str], keep: Path, when: str) -> dict[str, str | None]:
    """A copy of each file as it is now (None for a file that is not there)."""
    copies = {}
    for i, path in enumerate(paths):
        copy = keep / f"{when}-{i}-{Path(path).name}"
        try:
            shutil.copyfile(path, copy)
            copies[path] = str(copy)
        except OSError:
            copies[path] = None
    return copies


def _run_step(step: dict, reaper: _Reaper, settle_s: float, marker: bytes) -> dict:
    keep = Path(step["keep"])
    keep.mkdir(parents=True, exist_ok=True)
    Path(step["env"]["TMPDIR"]).mkdir(parents=True, exist_ok=True)
    started = time.monotonic()
    with open(keep / "stdout.txt", "wb") as out, open(keep / "stderr.txt", "wb") as err:
        grader = subprocess.Popen(
            step["argv"], cwd=step["cwd"], env=step["env"], stdin=subprocess.DEVNULL, stdout=out, stderr=err
        )
    timed_out = was_stopped = False
    stopped_since = None  # a grader stopped (SIGSTOP) would never go on: it is killed after STOPPED_S
    while grader.pid not in reaper.status:
        reaper.reap(keep=grader.pid)
        if _exited(grader.pid):
            break
        now = time.monotonic()
        state = _state(grader.pid)
        stopped_since = (stopped_since or now) if state in ("T", "t") else None
        if not timed_out and (
            now - started > step["timeout_s"] or (stopped_since and now - stopped_since > STOPPED_S)
        ):
            timed_out = True
            was_stopped = stopped_since is not None
            os.kill(grader.pid, signal.SIGKILL)
        time.sleep(POLL_S)
    wall = time.monotonic() - started
    # copied before the grader's pid is free: a process waiting for the grader to go sees it there until then
    at_exit = _copies(step.get("outputs", []), keep, "at-exit")
    if grader.pid not in reaper.status:
        _, status = os.waitpid(grader.pid, 0)
        reaper.status[grader.pid] = os.waitstatus_to_exitcode(status)
    grader.returncode = reaper.status[grader.pid]
    reaper.wait(settle_s)
    after_settle = _copies(step.get("outputs", []), keep, "after-settle")
    left = _processes(marker)
    result = {
        "name": step["name"],
        "rc": grader.returncode,
        "timed_out": timed_out,
        "stopped": timed_out and was_stopped,
        "wall_s": round(wall, 2),
        "stdout": str(keep / "stdout.txt"),
        "stderr": str(keep / "stderr.txt"),
        "at_exit": at_exit,
        "after_settle": after_settle,
        "survivors": [p for p in left if p["state"] != "Z"],
        "tmp_left": _listing(step["env"]["TMPDIR"]),
    }
    _end_all(reaper)
    return result


def main(plan_path: str) -> None:
    plan = json.loads(Path(plan_path).read_text())
    if os.getpid() != 1:
        raise SystemExit("contained_run.py must be the first process of a PID namespace (see start())")
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    _mount_overlays(plan.get("overlays", []))
    reaper = _Reaper()
    marker = plan.get("marker", "").encode()
    report = {"overlays": plan.get("overlays", []), "steps": []}
    for step in plan["steps"]:
        report["steps"].append(_run_step(step, reaper, plan.get("settle_s", 3.0), marker))
        Path(plan["report"]).write_text(json.dumps(report, indent=2))


if __name__ == "__main__":
    main(sys.argv[1])
