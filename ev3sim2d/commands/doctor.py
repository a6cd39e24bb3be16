"""`ev3sim2d doctor`: what isolation a student's program (its brick) gets on this machine, layer by layer.

It asks the kernel what it offers (sandbox.probe()), then really enters the sandbox in a
throw-away brick-like child (`python -I -S`, a temporary scratch folder) and prints that
child's report: one line per layer, on or off and why, and for a layer that is off what a
teacher loses without it (docs/grading-security.md).  Exit status 0 when the report could be
made, whether every layer is on or some are off (those are warnings: programs still run, with
less isolation); 1 when the throw-away brick could not enter the sandbox at all (grading would
fail the same way).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

from ..brick import sandbox
from ..simulator import job_object, sandbox_exec
from .exit_codes import EXIT_OK, EXIT_PROGRAM_ERROR

NAME = "doctor"
HELP = "show what isolation a student's program gets on this machine, and what is missing"
PACKAGE_PARENT = Path(__file__).resolve().parents[2]


@dataclass(frozen=True)
class Layer:
    """A layer of a brick's sandbox: its key in the report, its name here, what is lost without it."""

    key: str
    title: str
    without: str


LAYERS = (
    Layer(
        "session", "own session, dies with simulator", "a program could outlive a simulator that was killed"
    ),
    Layer(
        "root_dropped",
        "root given up",
        "run as root, a program could change any file and kill any process the other layers miss",
    ),
    Layer("capabilities", "no capabilities", "a program could use privileges the other layers do not cover"),
    Layer(
        "user_ns",
        "user namespace",
        "the process limit counts every process of the brick's user on this machine, other bricks' too",
    ),
    Layer(
        "mount_ns", "mount namespace, own /proc", "/proc shows the machine's processes where Landlock is off"
    ),
    Layer("net_ns", "network namespace", "where seccomp is off, a program reaches the machine's network"),
    Layer(
        "pid_ns",
        "PID namespace",
        "a program sees other processes, and what it starts after setsid() outlives the run "
        "unless the simulator (a child subreaper) finds and kills it",
    ),
    Layer("ipc_ns", "IPC namespace", "bricks could talk through System V and POSIX message queues"),
    Layer("no_new_privs", "no new privileges", "a set-uid program started by the student would gain rights"),
    Layer(
        "rlimits",
        "CPU, memory, file, process limits",
        "a program could exhaust the machine's CPU, memory or disk",
    ),
    Layer(
        "landlock",
        "Landlock files",
        "a program reads whatever its user may read (the lessons' hidden variants, classmates' "
        "programs) and writes wherever its user may write",
    ),
    Layer("landlock_net", "Landlock TCP", "where the network namespace is missing, TCP goes out unchecked"),
    Layer(
        "landlock_scope",
        "Landlock signal and socket scope",
        "where the PID namespace is missing, a program may signal the grader or other bricks of its user",
    ),
    Layer(
        "seccomp",
        "seccomp filter",
        "a program may open sockets (unix sockets of daemons too), ptrace, and use rarely used kernel "
        "interfaces (io_uring, bpf, perf_event_open) that are common ways into the kernel",
    ),
    Layer("fds", "inherited files closed", "a program could use files the simulator had open"),
    Layer(
        "sandbox_exec",
        "sandbox-exec: no network, writes only in scratch",
        "a program reaches the network and writes wherever its user may write",
    ),
    Layer(
        "job_object",
        "Job Object: limits, ends with the simulator",
        "what a program starts outlives the run, and its memory and processes are not limited together",
    ),
)
OUTSIDE = ("sandbox_exec", "job_object")  # layers the simulator puts around a brick where the system has them
GUARANTEES = {
    "file confinement": "a program may read (and, without sandbox-exec, write) whatever its user may: "
    "the lessons' hidden variants, classmates' programs",
    "network": "a program may use the network",
    "orphan clean-up": "what a program starts may outlive the run",
}

_TRIAL = """
import json, sys
sys.path.insert(0, sys.argv[1])
sys.path.extend(json.loads(sys.argv[2]))
from ev3sim2d.brick import sandbox
policy = sandbox.SandboxPolicy(read_paths=sandbox.default_read_paths(), write_paths=[sys.argv[3]], keep_fds=[])
report = sandbox.enter(policy)
print(json.dumps(report), flush=True)
"""


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--json", action="store_true", help="print the probe and the report as JSON instead")


def trial_report() -> tuple[dict | None, str]:
    """Enter the sandbox in a throw-away brick-like child; (its report, "") or (None, why not)."""
    scratch = tempfile.mkdtemp(prefix="ev3sim2d-doctor-")
    site_packages = [p for p in sys.path if p.rstrip("/").endswith("-packages") and os.path.isdir(p)]
    environment = {"PATH": "/usr/bin:/bin", "HOME": scratch, "TMPDIR": scratch, "LANG": "C.UTF-8"}
    try:
        done = subprocess.run(
            [
                sys.executable,
                "-I",
                "-S",
                "-c",
                _TRIAL,
                str(PACKAGE_PARENT),
                json.dumps(site_packages),
                scratch,
            ],
            stdin=subprocess.DEVNULL,
            capture_output=True,
            text=True,
            env=environment,
            cwd=scratch,
            timeout=60,
            **({"start_new_session": True} if hasattr(os, "setsid") else {}),
        )
    except subprocess.TimeoutExpired:
        return None, "the trial brick did not answer within 60 s"
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    try:
        return json.loads(done.stdout.strip().splitlines()[-1]), ""
    except (IndexError, ValueError):
        lines = done.stderr.strip().splitlines()
        return None, lines[-1] if lines else f"the trial brick ended with status {done.returncode}"


def this_computer() -> dict:
    """What a brick gets here: what the kernel offers (sandbox.probe()), and the layers the simulator
    adds from outside where the system has them (sandbox-exec, a Job Object)."""
    facts = sandbox.probe()
    facts["sandbox_exec"] = sandbox_exec.describe()
    facts["job_object"] = "on" if job_object.available() else "off: this system has no Job Objects"
    return facts


def _on(facts: dict, key: str) -> bool:
    return str(facts.get(key, "")).startswith("on")


def missing_guarantees(facts: dict) -> list[str]:
    """What a class's programs are not kept from here (keys of GUARANTEES), from this_computer()."""
    namespaces = _on(facts, "user_ns") or _on(facts, "namespaces_as_root")
    missing = []
    if not _on(facts, "landlock"):
        missing.append("file confinement")
    if not (namespaces or _on(facts, "seccomp") or _on(facts, "sandbox_exec")):
        missing.append("network")
    if not (namespaces or _on(facts, "subreaper") or _on(facts, "job_object")):
        missing.append("orphan clean-up")
    return missing


def isolation_summary(facts: dict) -> str:
    """One line: what isolation a brick gets here, from this_computer() (or sandbox.probe())."""
    parts = [f"landlock ABI {facts['landlock_abi']}" if facts["landlock_abi"] else "no landlock"]
    namespaces = []
    if facts["user_ns"] == "on":
        namespaces.append("user")
    if facts["user_ns"] == "on" or facts.get("namespaces_as_root") == "on":
        namespaces += ["mount", "net", "pid", "ipc"]
    parts.append(f"{'+'.join(namespaces)} namespaces" if namespaces else "no namespaces")
    parts.append("seccomp" if facts["seccomp"] == "on" else "no seccomp")
    if facts["root"] and facts.get("linux", True):
        parts.append("root given up for uid 65534")
    if not facts.get("linux", True) and _on(facts, "rlimits"):
        parts.append("resource limits")
    if _on(facts, "sandbox_exec"):
        parts.append("sandbox-exec (no network, writes only in the scratch folder)")
    if _on(facts, "job_object"):
        parts.append("a Job Object (memory, processes, CPU time; ends with the simulator)")
    return ", ".join(parts)


def grading_isolation(facts: dict) -> dict:
    """What a class's programs are kept from here, for grade's JSON and its one line."""
    missing = missing_guarantees(facts)
    return {
        "computer": isolation_summary(facts),
        "missing": missing,
        "without": {name: GUARANTEES[name] for name in missing},
    }


class VersionAction(argparse.Action):
    """`ev3sim2d --version`: the version, and a line on the isolation a brick gets here."""

    def __init__(self, option_strings, dest=argparse.SUPPRESS, default=argparse.SUPPRESS, help=None):
        help = help or "print the version and the isolation a program gets on this machine, then exit"
        super().__init__(option_strings, dest=dest, default=default, nargs=0, help=help)

    def __call__(self, parser, namespace, values, option_string=None):
        facts = this_computer()
        print(f"ev3sim2d {version()}")
        print(f"isolation: {isolation_summary(facts)}")
        missing = missing_guarantees(facts)
        if missing:
            print(
                f"not here: {', '.join(missing)} (grade untrusted classes on Linux or in CI: docs/platforms.md)"
            )
        parser.exit(EXIT_OK)


def version() -> str:
    from importlib.metadata import PackageNotFoundError
    from importlib.metadata import version as installed_version

    try:
        return installed_version("ev3sim2d")
    except PackageNotFoundError:
        return "(not installed)"


def main(args) -> int:
    facts = this_computer()
    report, why = trial_report()
    if report is not None:
        report.update({key: facts[key] for key in OUTSIDE})
    if args.json:
        missing = missing_guarantees(facts)
        print(
            json.dumps({"probe": facts, "report": report, "missing": missing, "error": why or None}, indent=2)
        )
        return EXIT_OK if report is not None else EXIT_PROGRAM_ERROR
    linux = facts.get("linux", True)
    if facts["root"]:
        user = "root (a brick gives it up for uid 65534)" if linux else "root (a brick keeps it here)"
    else:
        user = f"uid {facts['uid']}" if facts["uid"] is not None else "an ordinary user"
    kernel = f"Linux {facts['kernel']}" if linux else facts["kernel"]
    print(f"ev3sim2d {version()} on {kernel} ({facts['machine']}), as {user}")
    print(f"isolation: {isolation_summary(facts)}")
    if report is None:
        print(f"ev3sim2d doctor: error: a brick could not enter its sandbox here: {why}", file=sys.stderr)
        return EXIT_PROGRAM_ERROR
    print("a brick here gets:")
    off = 0
    width = max(len(layer.title) for layer in LAYERS)
    elsewhere = []
    for layer in LAYERS:
        state = report.get(layer.key, "off: not reported")
        if state == sandbox.NOT_HERE or (
            layer.key in OUTSIDE and not _on(facts, layer.key) and "no " in state
        ):
            elsewhere.append(layer.title)  # a layer of another system: listed once, below
            continue
        on = state.startswith("on") or state == "not root"
        off += not on
        print(f"  {'on ' if on else 'OFF'} {layer.title:<{width}}  {state}")
        if not on:
            print(f"      {'':<{width}}  without it: {layer.without}")
    if elsewhere:
        print(f"other systems' layers, not on this one: {', '.join(elsewhere)}")
    if off:
        print(f"{off} layer(s) off: programs still run, with less isolation (docs/grading-security.md)")
    else:
        print("every layer this system has is on")
    for name in missing_guarantees(facts):
        print(f"a class's programs get no {name} here: {GUARANTEES[name]} (docs/platforms.md)")
    return EXIT_OK
