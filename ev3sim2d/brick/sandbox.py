"""The brick's sandbox: the walls a student's program runs inside (docs/grading-security.md).

A student's program is an adversary: it may try to read hidden variants, reach the simulator,
signal or outlive the grader, use the network, or leave something behind for later runs.
The brick's boot imports everything trusted, then calls `enter(policy)` once, with no other
thread running; when it returns, this process (or its grandchild, see 6. and 15.) runs the
program.  The forks are invisible to the program: the global `random` state is kept.
Only the standard library is used: this module is imported inside the brick.

The order of the layers, and why
 1. Refuse to go on if another thread runs: Landlock and seccomp bind only the calling thread.
 2. Session: a session and process group of its own, core dumps off (RLIMIT_CORE 0).
 3. Close every fd but 0, 1, 2 and keep_fds (the connection), before anything is forked.
 4. Namespaces, while the process still may make them:
    - root makes mount+net+ipc+pid namespaces with its own power (no user namespace needed,
      so this works where unprivileged user namespaces are off), makes every mount private,
      gives the write paths to `unprivileged_uid`, and shapes the view so that this uid can
      reach what it is allowed: a folder it could not pass through (a Python under /root) or
      an allowed folder it could not list (a program's folder made by mkdtemp) is covered
      with a tmpfs holding only the allowed entries, bound back in;
    - anyone else first makes a user namespace (its own uid and gid only, setgroups denied),
      then the same four inside it.
 5. The Landlock ruleset is built now, while every path may still be opened, and after the
    mount view, since its rules hold the inodes the program will meet.
 6. Fork, since a new PID namespace only holds children.  The outer process, the one the
    simulator knows, gives up everything and only waits, then ends as the program's process
    ended (the same exit code, or the same signal).  The child is PID 1 ("init") of the
    namespace, in a session of its own: when it ends the kernel kills every process left in
    it, so nothing a program forks, even after setsid, outlives the run.
 7. The child mounts a fresh /proc showing only the brick's processes (or hides /proc).
 8. Root is given up: bounding set emptied, groups cleared, gid and uid set to
    `unprivileged_uid`; hard limits can no longer be raised.  Root's brick then makes a
    user namespace of its own, so that RLIMIT_NPROC counts only this brick's processes.
 9. Capabilities: none left (bounding, permitted, effective, inheritable, ambient), checked.
10. PDEATHSIG(SIGKILL) and not dumpable, after the credential changes, which reset both.
11. no_new_privs: nothing executed later can gain privileges (set-uid files, file caps).
12. rlimits: CPU, AS (measured now: what the process uses + memory_mb), FSIZE (and SIGXFSZ
    back to its default, so an endless writer dies), NOFILE, CORE, NPROC; one malloc arena.
13. Landlock enforced: files (read+execute beneath read paths, names only in list paths,
    everything beneath write paths), TCP (ABI >= 4: no bind, no connect) and scope (ABI >= 6:
    no signal and no abstract unix socket outside this brick's own domain).
14. seccomp last: it forbids unshare, mount and the other calls used above.
15. The init forks once more: the grandchild returns from `enter` and runs the program;
    the init reaps every orphan and, when the program's process ends, reports its status
    to the outer process and exits, which ends the namespace.

On a system without the Linux kernel's interfaces (macOS, Windows: `linux_kernel()` is false)
none of the above is tried (its system call numbers would be other calls there): the brick puts up
what such a system lets an ordinary user put up (a session of its own that ends with its simulator,
no inherited files, the resource limits it has) and reports Linux's layers as not this system's;
the simulator adds what the system offers from outside (docs/platforms.md).

A layer the kernel lacks is "off: <why>" in the report; `enter` still succeeds.  What must
not fail (giving up root, dropping capabilities, a reachable scratch folder) raises
SandboxError instead, and so does the machine's root seen through a user namespace that has
no `unprivileged_uid`; a rootless container's root (an ordinary user of the host) is treated
as the ordinary user it is.
RLIMIT_NPROC counts processes per real uid in a user namespace, so a brick in its own user
namespace is limited to its own `processes`, whatever else its uid runs elsewhere.  Without
a user namespace the limit is `processes` plus what the uid already runs (counted in /proc):
give concurrent bricks different `unprivileged_uid`s then.
"""

from __future__ import annotations

import _thread
import ctypes
import errno
import os
import platform
import signal
import stat
import struct
import sys
import time

_MIB = 1024 * 1024
_M_ARENA_MAX = -8  # mallopt(3), glibc
_EXIT_SANDBOX_BROKEN = 70  # the outer process or the init failed in a way that has no child status

# prctl(2)
_PR_SET_PDEATHSIG, _PR_SET_DUMPABLE, _PR_GET_SECCOMP, _PR_SET_SECCOMP = 1, 4, 21, 22
_PR_CAPBSET_READ, _PR_CAPBSET_DROP, _PR_SET_NO_NEW_PRIVS, _PR_GET_NO_NEW_PRIVS = 23, 24, 38, 39
_PR_CAP_AMBIENT, _PR_CAP_AMBIENT_IS_SET, _PR_CAP_AMBIENT_CLEAR_ALL = 47, 1, 4
_SECCOMP_MODE_FILTER = 2
_CAP_SETPCAP = 8

# clone(2) / unshare(2)
_CLONE_NEWTIME, _CLONE_NEWNS, _CLONE_NEWCGROUP, _CLONE_NEWUTS = 0x80, 0x20000, 0x02000000, 0x04000000
_CLONE_NEWIPC, _CLONE_NEWUSER, _CLONE_NEWPID, _CLONE_NEWNET = 0x08000000, 0x10000000, 0x20000000, 0x40000000
_CLONE_ANY_NAMESPACE = (
    _CLONE_NEWTIME
    | _CLONE_NEWNS
    | _CLONE_NEWCGROUP
    | _CLONE_NEWUTS
    | _CLONE_NEWIPC
    | _CLONE_NEWUSER
    | _CLONE_NEWPID
    | _CLONE_NEWNET
)
_BRICK_NAMESPACES = _CLONE_NEWNS | _CLONE_NEWNET | _CLONE_NEWIPC | _CLONE_NEWPID

# mount(2)
_MS_NOSUID, _MS_NODEV, _MS_NOEXEC = 2, 4, 8
_MS_BIND, _MS_REC, _MS_PRIVATE = 4096, 16384, 1 << 18

# Landlock (include/uapi/linux/landlock.h); the syscall numbers are the same on every architecture but alpha
_LANDLOCK_CREATE_RULESET, _LANDLOCK_ADD_RULE, _LANDLOCK_RESTRICT_SELF = 444, 445, 446
_LANDLOCK_CREATE_RULESET_VERSION = 1
_LANDLOCK_RULE_PATH_BENEATH = 1
_FS_EXECUTE, _FS_WRITE_FILE, _FS_READ_FILE, _FS_READ_DIR = 1 << 0, 1 << 1, 1 << 2, 1 << 3
_FS_REFER, _FS_TRUNCATE, _FS_IOCTL_DEV = 1 << 13, 1 << 14, 1 << 15
_FS_ABI1 = (1 << 13) - 1  # execute .. make_sym
_FS_FILE_ONLY = _FS_EXECUTE | _FS_WRITE_FILE | _FS_READ_FILE | _FS_TRUNCATE | _FS_IOCTL_DEV
_NET_BIND_TCP, _NET_CONNECT_TCP = 1 << 0, 1 << 1
_SCOPE_ABSTRACT_UNIX_SOCKET, _SCOPE_SIGNAL = 1 << 0, 1 << 1

# seccomp: struct seccomp_data is {int nr; u32 arch; u64 ip; u64 args[6]}
_SECCOMP_RET_KILL_PROCESS, _SECCOMP_RET_ERRNO, _SECCOMP_RET_ALLOW = 0x80000000, 0x00050000, 0x7FFF0000
_BPF_LD_W_ABS, _BPF_JEQ_K, _BPF_JGE_K, _BPF_JSET_K, _BPF_RET_K = 0x20, 0x15, 0x35, 0x45, 0x06
_X32_SYSCALL_BIT = 0x40000000

# Calls a program never needs and that would reach past the walls: other processes' memory
# (ptrace, process_vm_*, pidfd_getfd, process_madvise, kcmp), the kernel's attack surface
# (bpf, perf_event_open, userfaultfd, io_uring which would also run calls past this filter,
# keyrings, personality), the namespaces and mounts made above, and the machine (modules,
# kexec, reboot, swap, accounting, quotas, file handles that bypass paths, syslog).
# Numbers: arch/x86/entry/syscalls/syscall_64.tbl and include/uapi/asm-generic/unistd.h.
_SYSCALLS = """
    name               x86_64 aarch64
    socket                 41     198
    ptrace                101     117
    process_vm_readv      310     270
    process_vm_writev     311     271
    pidfd_getfd           438     438
    process_madvise       440     440
    kcmp                  312     272
    bpf                   321     280
    perf_event_open       298     241
    userfaultfd           323     282
    io_uring_setup        425     425
    io_uring_enter        426     426
    io_uring_register     427     427
    mount                 165      40
    umount2               166      39
    pivot_root            155      41
    chroot                161      51
    open_tree             428     428
    move_mount            429     429
    fsopen                430     430
    fsconfig              431     431
    fsmount               432     432
    fspick                433     433
    mount_setattr         442     442
    unshare               272      97
    setsid                112     157
    setpgid               109     154
    setns                 308     268
    keyctl                250     219
    add_key               248     217
    request_key           249     218
    personality           135      92
    init_module           175     105
    finit_module          313     273
    delete_module         176     106
    kexec_load            246     104
    kexec_file_load       320     294
    reboot                169     142
    swapon                167     224
    swapoff               168     225
    acct                  163      89
    quotactl              179      60
    quotactl_fd           443     443
    open_by_handle_at     304     265
    name_to_handle_at     303     264
    syslog                103     116
    clone                  56     220
    clone3                435     435
"""
_NOT_DENIED = ("clone", "clone3")  # looked at, not denied outright (see seccomp_program)


def _syscall_table() -> dict[str, dict[str, int]]:
    """{architecture: {call: number}} from _SYSCALLS."""
    header, *rows = (line.split() for line in _SYSCALLS.strip().splitlines())
    return {arch: {row[0]: int(row[1 + i]) for row in rows} for i, arch in enumerate(header[1:])}


# The AUDIT_ARCH value seccomp sees for each architecture, and whether it has an x32 ABI to refuse.
_SECCOMP_ARCHES = {"x86_64": (0xC000003E, True), "aarch64": (0xC00000B7, False)}
_MACHINE_ALIASES = {"amd64": "x86_64", "arm64": "aarch64"}

_libraries: dict = {}


def _c_library():
    """This process's C library (None where it cannot be loaded by name None, as on Windows)."""
    if "c" not in _libraries:
        try:
            _libraries["c"] = ctypes.CDLL(None, use_errno=True)
        except (OSError, TypeError):
            _libraries["c"] = None
    return _libraries["c"]


def linux_kernel() -> bool:
    """Whether this kernel offers the Linux interfaces the full sandbox is built of: prctl and unshare
    in its C library, and so the Linux system call numbers Landlock and seccomp are reached by (on
    another kernel those numbers are other calls, which must never be made)."""
    libc = _c_library()
    if libc is None or not hasattr(os, "getresuid"):
        return False
    return all(getattr(libc, name, None) is not None for name in ("prctl", "unshare", "capget"))


def _resource():
    """The resource module where this system has it (not on Windows)."""
    try:
        import resource
    except ImportError:
        return None
    return resource


class SandboxError(RuntimeError):
    """The sandbox could not be entered safely (e.g. root could not be given up): run nothing."""


class SandboxPolicy:
    """What the program may touch once inside; everything else it may not.  (A plain class: the brick
    imports this module at every start, and `dataclasses` alone costs it 10 ms.)"""

    def __init__(
        self,
        read_paths: list[
            str
        ],  # files or folders the program may read (and execute); everything else unreadable
        write_paths: list[str],  # folders it may read, create, write, delete in (its scratch folder)
        keep_fds: list[
            int
        ],  # inherited fds that must stay open (the connection); every other fd >= 3 is closed
        cpu_s: int = 60,  # RLIMIT_CPU (soft; hard = soft + 1)
        memory_mb: int = 512,  # RLIMIT_AS on top of what the process already uses
        file_mb: int = 16,  # RLIMIT_FSIZE
        processes: int = 64,  # processes and threads the program may create besides itself (RLIMIT_NPROC)
        open_files: int = 256,  # RLIMIT_NOFILE
        unprivileged_uid: int = 65534,  # uid and gid used when running as root
        # Folders whose names may be listed but whose files are not readable: the site-packages
        # folders, so that imports find packages there while ev3sim2d's own package stays closed.
        list_paths: list[str] | None = None,
    ) -> None:
        self.read_paths = read_paths
        self.write_paths = write_paths
        self.keep_fds = keep_fds
        self.cpu_s = cpu_s
        self.memory_mb = memory_mb
        self.file_mb = file_mb
        self.processes = processes
        self.open_files = open_files
        self.unprivileged_uid = unprivileged_uid
        self.list_paths = default_list_paths() if list_paths is None else list_paths


# ---------------------------------------------------------------- what a program may read


def default_read_paths() -> list[str]:
    """What any Python program needs to read: this Python's standard library and executable (and
    the `python3` on PATH, whose library is under /usr/lib), the site-packages entries except ev3sim2d itself (its lessons and grader stay closed), the
    system's shared libraries and locales, the time zones, and the two files of /etc it reads."""
    import site
    import sysconfig

    paths: list[str] = []
    base_paths = sysconfig.get_paths(vars={"base": sys.base_prefix, "platbase": sys.base_exec_prefix})
    paths += [base_paths["stdlib"], base_paths["platstdlib"]]
    bases = tuple(os.path.join(p, "") for p in {sys.base_prefix, sys.base_exec_prefix})
    paths += [p for p in sys.path if p and p.startswith(bases) and not _is_site_packages(p)]
    paths += [sys.executable, os.path.realpath(sys.executable)]
    for folder in os.environ.get("PATH", "").split(os.pathsep):  # the `python3` a program may start
        candidate = os.path.join(folder, "python3")
        if folder and os.access(candidate, os.X_OK):
            paths += [candidate, os.path.realpath(candidate)]
            break
    if sysconfig.get_config_var("Py_ENABLE_SHARED"):
        libdir, soname = sysconfig.get_config_var("LIBDIR"), sysconfig.get_config_var("INSTSONAME")
        if libdir and soname:
            paths.append(os.path.join(libdir, soname))
    here = os.path.dirname(os.path.abspath(sys.executable))
    paths += [os.path.join(here, "pyvenv.cfg"), os.path.join(os.path.dirname(here), "pyvenv.cfg")]
    for folder in _site_packages_folders(site):
        paths += [os.path.join(folder, name) for name in sorted(os.listdir(folder)) if not _is_ev3sim2d(name)]
    paths += ["/usr/lib", "/lib", "/lib64", "/usr/lib64", "/usr/share/zoneinfo"]
    paths += ["/etc/ld.so.cache", "/etc/localtime"]
    return _unique(p for p in paths if os.path.exists(p))


def default_list_paths() -> list[str]:
    """The site-packages folders: listable (for the import system), their entries readable
    only as default_read_paths() allows."""
    import site

    return _site_packages_folders(site)


def _site_packages_folders(site) -> list[str]:
    folders = [*site.getsitepackages(), *(p for p in sys.path if _is_site_packages(p))]
    return _unique(p for p in folders if os.path.isdir(p))


def _is_site_packages(path: str) -> bool:
    return os.path.basename(os.path.normpath(path)) in ("site-packages", "dist-packages")


def _is_ev3sim2d(name: str) -> bool:
    return "ev3sim2d" in name.lower()


def _unique(paths) -> list[str]:
    seen: dict[str, None] = {}
    for path in paths:
        seen.setdefault(path, None)
    return list(seen)


# ---------------------------------------------------------------- entering


def enter(policy: SandboxPolicy) -> dict:
    """Put this process in the sandbox; returns a report {layer: "on ..." | "off: why" | "not root"}.

    Call once, with no other thread running.  With a PID namespace the process that called
    `enter` never returns from it: it waits for its child, which returns, and exits as that
    child exits.  Raises SandboxError when a layer that cannot be missing (giving up root,
    dropping capabilities) fails, or when the policy has no reachable scratch folder."""
    if not policy.write_paths:
        raise SandboxError("a sandbox needs a scratch folder in write_paths")
    _only_thread()
    if not linux_kernel():
        return _enter_elsewhere(policy)
    report: dict[str, str] = {}
    original_parent = os.getppid()
    random_state = _random_state()
    as_root = 0 in os.getresuid() and _root_can_become(policy.unprivileged_uid, report)
    uid = policy.unprivileged_uid if as_root else os.getuid()

    _own_session(report)
    _close_fds_except(policy.keep_fds)
    read_paths = _real_paths(policy.read_paths)
    write_paths = _real_paths(policy.write_paths)
    if len(write_paths) < len(set(policy.write_paths)):
        raise SandboxError(f"a write path does not exist or cannot be reached: {policy.write_paths}")
    list_paths = _real_paths(policy.list_paths)
    if as_root:
        for path in write_paths:
            _give_tree(path, uid)

    made_by_root = as_root and _namespaces_as_root(report, read_paths, write_paths, list_paths, uid)
    # Landlock's rules hold inodes: made after the mount view, while every path may still be opened.
    landlock = _Landlock.prepare(read_paths, write_paths, list_paths)
    namespaced = made_by_root
    user_ns_tasks = 0  # the tasks its user namespace holds once the program's process exists
    if not made_by_root:
        if as_root:
            _give_up_root(uid, report)
        namespaced = _namespaces_in_user_namespace(report)
        if report["user_ns"] == "on":
            user_ns_tasks = 3 if namespaced else 1

    alive_fd = host_proc = None
    if namespaced:
        status_r, status_w = os.pipe()
        alive_r, alive_w = os.pipe()
        init_pid = os.fork()
        if init_pid:
            _outer_process(init_pid, status_r, alive_w, uid if made_by_root else None, original_parent)
        os.close(status_r)
        os.close(alive_w)
        alive_fd = alive_r
        os.setsid()  # a group of its own: kill(0, ...) by the program cannot reach the outer process
        host_proc = _open_host_proc()
        _fresh_proc(report)
        if made_by_root:
            _give_up_root(uid, report)
            user_ns_tasks = 2 if _user_namespace_after_root(report, uid) else 0
    if as_root:
        _check_reachable(read_paths, write_paths, report)
    _drop_capabilities(report)
    _die_with_parent(report, original_parent, alive_fd)
    _no_new_privs(report)
    tasks = user_ns_tasks or _tasks_of_uid(uid, host_proc) + 2
    if host_proc is not None:
        os.close(host_proc)
    _set_rlimits(policy, tasks, report)
    _stay_inside(read_paths + write_paths, write_paths[0])
    landlock.restrict(report)
    _seccomp(report)
    report["fds"] = f"on (kept 0, 1, 2{''.join(f', {fd}' for fd in sorted(policy.keep_fds))})"
    if namespaced:
        _become_init(status_w)
        _restore_random_state(random_state)
    return report


# ---------------------------------------------------------------- on other systems

LINUX_LAYERS = (
    "root_dropped",
    "capabilities",
    "user_ns",
    "mount_ns",
    "net_ns",
    "pid_ns",
    "ipc_ns",
    "no_new_privs",
    "landlock",
    "landlock_net",
    "landlock_scope",
    "seccomp",
)
NOT_HERE = "off: a layer of the Linux kernel, which this system does not have"
PARENT_CHECK_S = 0.2  # how often a brick without PDEATHSIG looks whether its simulator is still there
# the real thread and sleep: a brick makes both virtual before it enters (boot.py imports this first)
_real_start_new_thread = _thread.start_new_thread
_real_sleep = time.sleep


def _enter_elsewhere(policy: SandboxPolicy) -> dict:
    """What a brick can put up from inside on a system without the Linux kernel's interfaces (macOS,
    Windows): a session of its own that ends with its simulator, no inherited files, resource limits.
    What the simulator adds from outside (a Job Object, sandbox-exec) it reports itself."""
    report = dict.fromkeys(LINUX_LAYERS, NOT_HERE)
    if hasattr(os, "getuid"):
        report["root_dropped"] = (
            "not root" if os.getuid() != 0 else "off: root is not given up on this system"
        )
    _session_elsewhere(report)
    if hasattr(os, "fork"):  # (a new process on a system without fork inherits no files but 0, 1, 2)
        _close_fds_except(policy.keep_fds)
    _rlimits_elsewhere(policy, report)
    _stay_inside(_real_paths(policy.read_paths) + _real_paths(policy.write_paths), policy.write_paths[0])
    report["fds"] = f"on (kept 0, 1, 2{''.join(f', {fd}' for fd in sorted(policy.keep_fds))})"
    return report


def _session_elsewhere(report: dict) -> None:
    """A session of its own (the simulator started the brick with one where the system has them), and
    an end when the simulator ends: without PDEATHSIG, a thread looks every PARENT_CHECK_S whether the
    parent is still the one that started it, and ends the brick's whole process group if not."""
    if not hasattr(os, "setsid"):
        report["session"] = (
            "off: this system has no sessions (a Job Object ends the brick with its simulator)"
        )
        return
    if os.getsid(0) != os.getpid():
        try:
            os.setsid()
        except OSError as err:
            report["session"] = f"off: setsid: {err.strerror}"
            return
    parent = os.getppid()

    def watch() -> None:
        while os.getppid() == parent:
            _real_sleep(PARENT_CHECK_S)
        try:
            os.killpg(0, signal.SIGKILL)
        finally:
            os._exit(_EXIT_SANDBOX_BROKEN)

    _real_start_new_thread(watch, ())
    report["session"] = f"on (ends within {PARENT_CHECK_S:g} s of its simulator)"


def _rlimits_elsewhere(policy: SandboxPolicy, report: dict) -> None:
    """The resource limits this system lets a process set on itself, each tried on its own."""
    resource = _resource()
    if resource is None:
        report["rlimits"] = "off: this system has no resource limits (a Job Object sets them from outside)"
        return
    wanted = [
        ("RLIMIT_CPU", (policy.cpu_s, policy.cpu_s + 1), f"cpu {policy.cpu_s} s"),
        ("RLIMIT_FSIZE", (policy.file_mb * _MIB,) * 2, f"files {policy.file_mb} MB"),
        ("RLIMIT_NOFILE", (policy.open_files,) * 2, f"{policy.open_files} open files"),
        ("RLIMIT_CORE", (0, 0), "no core"),
        (
            "RLIMIT_AS",
            (_address_space_bytes() + policy.memory_mb * _MIB,) * 2,
            f"memory +{policy.memory_mb} MB",
        ),
    ]
    done, missing = [], []
    for name, (soft, hard), said in wanted:
        which = getattr(resource, name, None)
        try:
            _, old_hard = resource.getrlimit(which)
            if old_hard != resource.RLIM_INFINITY:
                soft, hard = min(soft, old_hard), min(hard, old_hard)
            resource.setrlimit(which, (soft, hard))
            done.append(said)
        except (TypeError, ValueError, OSError):  # no such limit here, or the system refuses it
            missing.append(said.split(" +")[0].split(" ")[0])
    if hasattr(signal, "SIGXFSZ"):
        signal.signal(signal.SIGXFSZ, signal.SIG_DFL)  # a writer past the file limit must die
    # RLIMIT_NPROC counts every process of the user here, and without /proc they cannot be counted
    missing.append("processes")
    report["rlimits"] = f"on ({', '.join(done)}; not limited here: {', '.join(missing)})"


def _random_state():
    """The global generator's state: Python reseeds it after every fork (random.py registers
    os.register_at_fork), which would undo a run's seed; enter's own forks must not show."""
    module = sys.modules.get("random")
    return (module, module.getstate()) if module is not None else None


def _restore_random_state(saved) -> None:
    if saved is not None:
        module, state = saved
        module.setstate(state)


def _only_thread() -> None:
    try:
        threads = len(os.listdir("/proc/self/task"))
    except OSError:
        import threading

        threads = threading.active_count()
    if threads > 1:
        raise SandboxError(
            f"enter() needs this process to have one thread, it has {threads}: Landlock and seccomp "
            "would bind only the calling thread; call it before starting any thread"
        )


def _root_can_become(uid: int, report: dict) -> bool:
    """Root can become `uid` unless it is root of a user namespace that does not map it: a
    rootless container, whose root is an ordinary user of the host and is treated as one.
    Refuses when that root is the host's root (mapped to the parent namespace's uid 0)."""
    for kind in ("uid", "gid"):
        try:
            with open(f"/proc/self/{kind}_map") as f:
                ranges = [tuple(map(int, line.split())) for line in f if line.strip()]
        except OSError:
            continue
        if not any(inside <= uid < inside + count for inside, _, count in ranges):
            if kind == "uid" and any(inside == outside == 0 for inside, outside, _ in ranges):
                raise SandboxError(
                    f"root here is the machine's root seen through a user namespace without uid {uid}: "
                    "the program would run as the machine's root (owner of its files, exempt from the "
                    f"process limit); map uid {uid} into the namespace, or run as an ordinary user"
                )
            report["root_dropped"] = (
                f"off: {kind} {uid} does not exist in this user namespace (a rootless container, "
                "whose root is an unprivileged user of the host: the brick runs as that user)"
            )
            return False
    return True


def _real_paths(paths: list[str]) -> list[str]:
    """The existing paths, symbolic links resolved (each folder once: site-packages has many entries)."""
    folders: dict[str, str] = {}
    real = []
    for path in paths:
        folder, name = os.path.split(os.path.abspath(path))
        if folder not in folders:
            folders[folder] = os.path.realpath(folder)
        resolved = os.path.join(folders[folder], name)
        if os.path.islink(resolved):
            resolved = os.path.realpath(resolved)
        if os.path.exists(resolved):
            real.append(resolved)
    return _unique(real)


def _own_session(report: dict) -> None:
    import resource

    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    if os.getsid(0) == os.getpid():
        report["session"] = "on (already a session leader)"
        return
    try:
        os.setsid()
        report["session"] = "on"
    except OSError as err:  # a process-group leader cannot make a session
        report["session"] = f"off: setsid: {err.strerror} (start the brick with start_new_session=True)"


def _close_fds_except(keep: list[int]) -> None:
    """Close every fd above 2 but `keep`: those this process has open, where the system lists them
    (/proc/self/fd, /dev/fd), else every number below the open-files limit."""
    kept = {fd for fd in keep if fd >= 3}
    listed = _open_fds()
    if listed is not None:
        for fd in sorted(set(listed) - kept):
            if fd >= 3:
                try:
                    os.close(fd)
                except OSError:
                    pass  # the listing's own fd, gone already
        return
    resource = _resource()
    top = resource.getrlimit(resource.RLIMIT_NOFILE)[0] if resource is not None else 8192
    top = 65536 if top == getattr(resource, "RLIM_INFINITY", -1) or top > 1 << 20 else top
    start = 3
    for fd in sorted(kept):
        os.closerange(start, fd)
        start = fd + 1
    os.closerange(start, max(top, start))


def _open_fds() -> list[int] | None:
    for folder in ("/proc/self/fd", "/dev/fd"):
        try:
            return [int(name) for name in os.listdir(folder) if name.isdigit()]
        except OSError:
            continue
    return None


# ---------------------------------------------------------------- namespaces


def _namespaces_as_root(report: dict, read_paths, write_paths, list_paths, uid: int) -> bool:
    """Mount, net, ipc and pid namespaces made with root's own power; the mount namespace made
    private and shaped so that `uid` can reach the paths it is allowed."""
    try:
        _unshare(_BRICK_NAMESPACES)
    except OSError as err:
        reason = f"off: unshare as root: {err.strerror}"
        for layer in ("mount_ns", "net_ns", "pid_ns", "ipc_ns"):
            report[layer] = reason
        return False
    report.update(net_ns="on", pid_ns="on", ipc_ns="on")
    _mount(None, "/", None, _MS_REC | _MS_PRIVATE)
    _reachable_for(uid, read_paths + write_paths + list_paths, read_paths + list_paths)
    report["mount_ns"] = "on"
    return True


def _namespaces_in_user_namespace(report: dict) -> bool:
    """A user namespace of this uid only, then mount, net, ipc and pid namespaces owned by it."""
    uid, gid = os.getuid(), os.getgid()
    try:
        _unshare(_CLONE_NEWUSER)
    except OSError as err:
        reason = f"off: {_user_namespace_refusal(err)}"
        for layer in ("user_ns", "mount_ns", "net_ns", "pid_ns", "ipc_ns"):
            report.setdefault(layer, reason)
        return False
    _map_ids(uid, gid)
    report["user_ns"] = "on"
    try:
        _unshare(_BRICK_NAMESPACES)
    except OSError as err:
        reason = f"off: unshare in the user namespace: {err.strerror}"
        for layer in ("mount_ns", "net_ns", "pid_ns", "ipc_ns"):
            report.setdefault(layer, reason)
        return False
    _mount(None, "/", None, _MS_REC | _MS_PRIVATE)
    report.update(mount_ns="on", net_ns="on", pid_ns="on", ipc_ns="on")
    return True


def _user_namespace_after_root(report: dict, uid: int) -> bool:
    """Root's brick, now `uid`, takes a user namespace of its own: RLIMIT_NPROC then counts
    this brick's processes, not every process of `uid` on the machine."""
    try:
        _unshare(_CLONE_NEWUSER)
    except OSError as err:
        report["user_ns"] = f"off: {_user_namespace_refusal(err)}"
        return False
    _map_ids(uid, uid)
    report["user_ns"] = "on"
    return True


def _map_ids(uid: int, gid: int) -> None:
    # The map files belong to root unless the process is dumpable (credential changes reset it).
    _prctl(_PR_SET_DUMPABLE, 1)
    with open("/proc/self/setgroups", "w") as f:
        f.write("deny")
    with open("/proc/self/gid_map", "w") as f:
        f.write(f"{gid} {gid} 1")
    with open("/proc/self/uid_map", "w") as f:
        f.write(f"{uid} {uid} 1")
    _prctl(_PR_SET_DUMPABLE, 0)


def _user_namespace_refusal(err: OSError) -> str:
    settings = {
        "/proc/sys/kernel/apparmor_restrict_unprivileged_userns": ("1", "AppArmor forbids them"),
        "/proc/sys/kernel/unprivileged_userns_clone": ("0", "kernel.unprivileged_userns_clone=0"),
        "/proc/sys/user/max_user_namespaces": ("0", "user.max_user_namespaces=0"),
    }
    for path, (value, why) in settings.items():
        try:
            with open(path) as f:
                if f.read().strip() == value:
                    return f"unprivileged user namespaces: {why} ({path})"
        except OSError:
            pass
    return f"unprivileged user namespaces: {err.strerror}"


def _reachable_for(uid: int, paths: list[str], open_folders) -> None:
    """Let `uid` reach every allowed path: a folder it may not pass through on the way (e.g.
    /root, 0700, holding a pyenv Python) is covered with a tmpfs holding only the allowed paths,
    bound back in; an allowed folder it may not list (a program's folder made by mkdtemp, 0700)
    in `open_folders` is covered likewise, its entries bound back.  Only in this brick's private
    mount namespace, shallow folders first; everything else in such folders stays hidden."""
    covered: dict[str, set[str]] = {}
    passable: dict[str, bool] = {}
    open_folders = set(open_folders)
    for path in paths:
        parts = path.split("/")[1:-1]
        for depth in range(1, len(parts) + 1):
            folder = "/" + "/".join(parts[:depth])
            if folder not in passable:
                passable[folder] = _allows(folder, uid, stat.S_IXOTH)
            if not passable[folder]:
                covered.setdefault(folder, set()).add(path)
                break
        if (
            path in open_folders
            and os.path.isdir(path)
            and not _allows(path, uid, stat.S_IROTH | stat.S_IXOTH)
        ):
            covered.setdefault(path, set()).update(os.path.join(path, name) for name in os.listdir(path))
    for folder in sorted(covered, key=lambda f: f.count("/")):
        inside = covered[folder]
        outermost = sorted(p for p in inside if not any(p.startswith(q + "/") for q in inside))
        held = [(path, _hold(path)) for path in outermost]
        _mount("tmpfs", folder, "tmpfs", _MS_NOSUID | _MS_NODEV | _MS_NOEXEC, "mode=0755,size=64k")
        for path, (kind, what) in held:
            _make_mount_point(folder, path, kind == "dir")
            if kind == "link":
                os.symlink(what, path)
            elif kind in ("dir", "file"):
                _mount(f"/proc/self/fd/{what}", path, None, _MS_BIND | _MS_REC)
                os.close(what)


def _hold(path: str) -> tuple[str, object]:
    """What to bring back at `path` after its folder is covered: ("dir"|"file", an O_PATH fd), ("link", target)."""
    info = os.lstat(path)
    if stat.S_ISLNK(info.st_mode):
        return "link", os.readlink(path)
    if stat.S_ISDIR(info.st_mode) or stat.S_ISREG(info.st_mode):
        kind = "dir" if stat.S_ISDIR(info.st_mode) else "file"
        return kind, os.open(path, os.O_PATH | os.O_NOFOLLOW | os.O_CLOEXEC)
    return "other", None  # sockets, fifos, devices: left out


def _allows(path: str, uid: int, other_bits: int) -> bool:
    """May `uid` (gid `uid`, no other groups) do what `other_bits` (S_IROTH, S_IXOTH) say on `path`?"""
    info = os.stat(path)
    shift = 6 if info.st_uid == uid else 3 if info.st_gid == uid else 0
    wanted = other_bits << shift
    return info.st_mode & wanted == wanted


def _make_mount_point(top: str, path: str, is_dir: bool) -> None:
    folder = path if is_dir else os.path.dirname(path)
    current = top
    for part in os.path.relpath(folder, top).split("/"):
        if part in ("", "."):
            continue
        current = os.path.join(current, part)
        if not os.path.isdir(current):
            os.mkdir(current)
            os.chmod(current, 0o755)
    if not is_dir and not os.path.lexists(path):
        os.close(os.open(path, os.O_CREAT | os.O_WRONLY | os.O_CLOEXEC, 0o644))


def _give_tree(path: str, uid: int) -> None:
    """The scratch folder becomes the unprivileged uid's (root made it, e.g. with mkdtemp, 0700)."""
    os.lchown(path, uid, uid)
    for folder, dirs, files in os.walk(path):
        for name in dirs + files:
            os.lchown(os.path.join(folder, name), uid, uid)


def _open_host_proc() -> int | None:
    try:
        return os.open("/proc", os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC)
    except OSError:
        return None


def _fresh_proc(report: dict) -> None:
    """In the new PID namespace: a /proc that shows only the brick's own processes."""
    flags = _MS_NOSUID | _MS_NODEV | _MS_NOEXEC
    try:
        _mount("proc", "/proc", "proc", flags)
        report["mount_ns"] = "on (fresh /proc)"
    except OSError as err:  # a container's /proc with masked paths cannot be mounted again
        try:
            _mount("tmpfs", "/proc", "tmpfs", flags, "mode=0555,size=4k")
            report["mount_ns"] = f"on (/proc hidden: a fresh one was refused, {err.strerror})"
        except OSError as err2:
            report["mount_ns"] = f"on (/proc not replaced: {err2.strerror}; Landlock keeps it closed)"


# ---------------------------------------------------------------- the three processes


def _outer_process(
    init_pid: int, status_fd: int, alive_fd: int, root_for: int | None, original_parent: int
) -> None:
    """The process the simulator started: it gives up everything (root for `root_for` when it
    is still root), waits for the namespace's init and ends as the program's process ended
    (exit code or signal).  It never returns."""
    code = _EXIT_SANDBOX_BROKEN
    try:
        signal.signal(signal.SIGINT, signal.SIG_DFL)
        if root_for is not None:
            _give_up_root(root_for, {})
        _drop_capabilities({})
        _prctl(_PR_SET_NO_NEW_PRIVS, 1)
        _prctl(_PR_SET_PDEATHSIG, signal.SIGKILL)
        _prctl(_PR_SET_DUMPABLE, 0)
        if os.getppid() != original_parent:
            return
        _close_fds_except([status_fd, alive_fd])
        _, init_status = os.waitpid(init_pid, 0)
        reported = os.read(status_fd, 4)
        status = struct.unpack("i", reported)[0] if len(reported) == 4 else init_status
        if os.WIFSIGNALED(status):
            sig = os.WTERMSIG(status)
            code = 128 + sig
            if sig not in (signal.SIGKILL, signal.SIGSTOP):
                signal.signal(sig, signal.SIG_DFL)
            signal.pthread_sigmask(signal.SIG_UNBLOCK, [sig])
            os.kill(os.getpid(), sig)
        elif os.WIFEXITED(status):
            code = os.WEXITSTATUS(status)
    except BaseException as err:
        _say_why(err)
    finally:
        os._exit(code)


def _become_init(status_fd: int) -> None:
    """PID 1 of the brick's namespace: fork the program's process (which returns from `enter`),
    reap every orphan, and when the program's process ends report its status and exit; the
    kernel then kills whatever the program left running."""
    program_pid = os.fork()
    if program_pid == 0:
        os.close(status_fd)
        return
    code = _EXIT_SANDBOX_BROKEN
    try:
        # An init receives from inside its namespace only the signals it handles: handle none.
        signal.signal(signal.SIGINT, signal.SIG_DFL)
        _close_fds_except([status_fd])
        while True:
            pid, status = os.waitpid(-1, 0)
            if pid == program_pid:
                os.write(status_fd, struct.pack("i", status))
                code = os.WEXITSTATUS(status) if os.WIFEXITED(status) else 128 + os.WTERMSIG(status)
                break
    except BaseException as err:
        _say_why(err)
    finally:
        os._exit(code)


def _say_why(err: BaseException) -> None:
    """The outer process and the init have no caller to raise to: they say it on stderr."""
    try:
        os.write(2, f"ev3sim2d sandbox: {type(err).__name__}: {err}\n".encode(errors="replace"))
    except OSError:
        pass


def _die_with_parent(report: dict, original_parent: int, alive_fd: int | None) -> None:
    """SIGKILL when the parent dies; a parent already gone means the program must not run."""
    _prctl(_PR_SET_PDEATHSIG, signal.SIGKILL)
    _prctl(_PR_SET_DUMPABLE, 0)
    if alive_fd is None:
        gone = os.getppid() != original_parent
    else:  # the parent is outside the PID namespace (getppid() is 0): its pipe's end says
        os.set_blocking(alive_fd, False)
        try:
            gone = os.read(alive_fd, 1) == b""
        except BlockingIOError:
            gone = False
        os.close(alive_fd)
    if gone:
        os._exit(_EXIT_SANDBOX_BROKEN)
    report["session"] += ", dies with its parent, not dumpable"


# ---------------------------------------------------------------- credentials


def _give_up_root(uid: int, report: dict) -> None:
    """Bounding set emptied, then groups, gid and uid: every capability goes with uid 0."""
    try:
        _empty_bounding_set()
        _prctl(_PR_CAP_AMBIENT, _PR_CAP_AMBIENT_CLEAR_ALL)
        os.setgroups([])
        os.setresgid(uid, uid, uid)
        os.setresuid(uid, uid, uid)
    except OSError as err:
        raise SandboxError(f"could not give up root for uid {uid}: {err}") from err
    if os.getresuid() != (uid, uid, uid) or os.getresgid() != (uid, uid, uid) or os.getgroups():
        raise SandboxError(f"root was not fully given up: uids {os.getresuid()}, gids {os.getresgid()}")
    report["root_dropped"] = f"on (uid {uid})"


def _check_reachable(read_paths: list[str], write_paths: list[str], report: dict) -> None:
    """Say which allowed paths the unprivileged uid cannot use (a Python under /root without a
    mount namespace, a program's file of mode 0600): the program will fail where it needs them."""
    closed = [p for p in read_paths if not os.access(p, os.R_OK | (os.X_OK if os.path.isdir(p) else 0))]
    closed += [p for p in write_paths if not os.access(p, os.R_OK | os.W_OK | os.X_OK)]
    if closed:
        more = f" and {len(closed) - 3} more" if len(closed) > 3 else ""
        report["root_dropped"] += f"; closed to it: {', '.join(closed[:3])}{more}"


def _drop_capabilities(report: dict) -> None:
    """No capability left in any set, checked with capget and PR_CAPBSET_READ."""
    report.setdefault("root_dropped", "not root")
    effective, permitted, inheritable = _capget()
    bounding_kept = ""
    if effective & (1 << _CAP_SETPCAP):
        _empty_bounding_set()
    elif _bounding_set():
        bounding_kept = " (bounding set kept: no CAP_SETPCAP to empty it; no_new_privs makes it moot)"
    _prctl(_PR_CAP_AMBIENT, _PR_CAP_AMBIENT_CLEAR_ALL)
    header = struct.pack("Ii", 0x20080522, 0)  # _LINUX_CAPABILITY_VERSION_3
    data = bytes(24)
    if _c_library().capset(header, data) != 0:
        err = ctypes.get_errno()
        raise SandboxError(f"capset: {os.strerror(err)}")
    left = _capget()
    ambient = [c for c in range(64) if _prctl_value(_PR_CAP_AMBIENT, _PR_CAP_AMBIENT_IS_SET, c) == 1]
    if any(left) or ambient or (not bounding_kept and _bounding_set()):
        raise SandboxError(f"capabilities left after dropping them: {left}, ambient {ambient}")
    report["capabilities"] = "on (none left)" + bounding_kept


def _capget() -> tuple[int, int, int]:
    header = ctypes.create_string_buffer(struct.pack("Ii", 0x20080522, 0))
    data = ctypes.create_string_buffer(24)
    if _c_library().capget(header, data) != 0:
        raise SandboxError(f"capget: {os.strerror(ctypes.get_errno())}")
    e0, p0, i0, e1, p1, i1 = struct.unpack("6I", data.raw)
    return e0 | e1 << 32, p0 | p1 << 32, i0 | i1 << 32


def _bounding_set() -> list[int]:
    caps = []
    for cap in range(64):
        held = _prctl_value(_PR_CAPBSET_READ, cap)
        if held < 0:
            break
        if held:
            caps.append(cap)
    return caps


def _empty_bounding_set() -> None:
    for cap in _bounding_set():
        _prctl(_PR_CAPBSET_DROP, cap)


def _no_new_privs(report: dict) -> None:
    _prctl(_PR_SET_NO_NEW_PRIVS, 1)
    report["no_new_privs"] = "on" if _prctl_value(_PR_GET_NO_NEW_PRIVS) == 1 else "off: not set"


# ---------------------------------------------------------------- limits


def _set_rlimits(policy: SandboxPolicy, tasks_already: int, report: dict) -> None:
    import resource

    cpu = policy.cpu_s
    address_space = _address_space_bytes() + policy.memory_mb * _MIB
    processes = policy.processes + tasks_already
    limits = {
        resource.RLIMIT_CPU: (cpu, cpu + 1),
        resource.RLIMIT_AS: (address_space, address_space),
        resource.RLIMIT_FSIZE: (policy.file_mb * _MIB, policy.file_mb * _MIB),
        resource.RLIMIT_NOFILE: (policy.open_files, policy.open_files),
        resource.RLIMIT_CORE: (0, 0),
        resource.RLIMIT_NPROC: (processes, processes),
    }
    for which, (soft, hard) in limits.items():
        _, old_hard = resource.getrlimit(which)
        if old_hard != resource.RLIM_INFINITY:
            soft, hard = min(soft, old_hard), min(hard, old_hard)
        resource.setrlimit(which, (soft, hard))
    signal.signal(signal.SIGXFSZ, signal.SIG_DFL)  # Python ignores it: a writer past the limit must die
    # Each thread's own malloc arena would reserve 64 MB of address space: 7 threads would use
    # up the memory budget without touching it.  One arena; the GIL serialises Python anyway.
    mallopt = getattr(_c_library(), "mallopt", None)
    if mallopt is not None:
        mallopt(ctypes.c_int(_M_ARENA_MAX), ctypes.c_int(1))
    report["rlimits"] = (
        f"on (cpu {policy.cpu_s} s, memory +{policy.memory_mb} MB, files {policy.file_mb} MB, "
        f"{policy.processes} more processes/threads, {policy.open_files} open files, no core)"
    )


def _address_space_bytes() -> int:
    try:
        with open("/proc/self/statm") as f:
            return int(f.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
    except OSError:
        import resource

        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024 * 4


def _tasks_of_uid(uid: int, proc_fd: int | None) -> int:
    """Tasks (threads count) whose real uid is `uid`: what RLIMIT_NPROC counts without a user namespace."""
    own = proc_fd is None
    if own:
        proc_fd = _open_host_proc()
        if proc_fd is None:
            return 0
    count = 0
    try:
        for name in os.listdir(proc_fd):
            if not name.isdigit():
                continue
            try:
                with open(os.open(f"{name}/status", os.O_RDONLY | os.O_CLOEXEC, dir_fd=proc_fd), "rb") as f:
                    fields = dict(line.partition(b":")[::2] for line in f.read().splitlines())
                if int(fields[b"Uid"].split()[0]) == uid:
                    count += int(fields[b"Threads"])
            except (OSError, KeyError, ValueError):
                continue
    finally:
        if own:
            os.close(proc_fd)
    return count


def _stay_inside(allowed: list[str], scratch: str) -> None:
    """A working folder outside every allowed path would still be reachable by relative paths
    where Landlock is missing: move to the scratch folder then."""
    try:
        here = os.path.realpath(os.getcwd())
    except OSError:
        here = ""
    if not any(here == p or here.startswith(p.rstrip("/") + "/") for p in allowed):
        os.chdir(scratch)


# ---------------------------------------------------------------- Landlock


class _Landlock:
    """A Landlock ruleset built while the paths can still be opened, enforced later by `restrict`."""

    def __init__(self, abi: int, why_off: str, ruleset_fd: int | None = None):
        self.abi, self.why_off, self.ruleset_fd = abi, why_off, ruleset_fd

    @classmethod
    def prepare(cls, read_paths: list[str], write_paths: list[str], list_paths: list[str]) -> _Landlock:
        abi, why_off = landlock_abi()
        if not abi:
            return cls(0, why_off)
        handled = _handled_fs(abi)
        net = _NET_BIND_TCP | _NET_CONNECT_TCP if abi >= 4 else 0  # no rule for any port: no TCP at all
        scoped = _SCOPE_ABSTRACT_UNIX_SOCKET | _SCOPE_SIGNAL if abi >= 6 else 0
        size = 8 if abi < 4 else 16 if abi < 6 else 24
        attr = struct.pack("QQQ", handled, net, scoped)[:size]
        ruleset_fd = _syscall(_LANDLOCK_CREATE_RULESET, attr, size, 0)
        read = _FS_EXECUTE | _FS_READ_FILE | _FS_READ_DIR
        wanted = [(p, _FS_READ_DIR) for p in list_paths] + [(p, read) for p in read_paths]
        wanted += [(p, handled) for p in write_paths]
        wanted.append(("/dev/null", _FS_READ_FILE | _FS_WRITE_FILE | _FS_TRUNCATE))
        for path, rights in wanted:
            try:
                fd = os.open(path, os.O_PATH | os.O_CLOEXEC)
            except OSError:
                continue
            try:
                allowed = rights & handled
                if not stat.S_ISDIR(os.fstat(fd).st_mode):
                    allowed &= _FS_FILE_ONLY
                if allowed:
                    rule = struct.pack("=Qi", allowed, fd)
                    _syscall(_LANDLOCK_ADD_RULE, ruleset_fd, _LANDLOCK_RULE_PATH_BENEATH, rule, 0)
            finally:
                os.close(fd)
        return cls(abi, "", ruleset_fd)

    def keep_fds(self) -> list[int]:
        return [] if self.ruleset_fd is None else [self.ruleset_fd]

    def restrict(self, report: dict) -> None:
        if self.ruleset_fd is None:
            report["landlock"] = f"off: {self.why_off}"
            report["landlock_net"] = report["landlock_scope"] = "off: no Landlock"
            return
        try:
            _syscall(_LANDLOCK_RESTRICT_SELF, self.ruleset_fd, 0)
        finally:
            os.close(self.ruleset_fd)
        abi = self.abi
        report["landlock"] = f"on (ABI {abi})"
        report["landlock_net"] = (
            "on" if abi >= 4 else f"off: needs Landlock ABI 4 (Linux 6.7), this kernel has {abi}"
        )
        report["landlock_scope"] = (
            "on" if abi >= 6 else f"off: needs Landlock ABI 6 (Linux 6.12), this kernel has {abi}"
        )


def landlock_abi() -> tuple[int, str]:
    """(ABI version, "") or (0, why there is none)."""
    if _MACHINE_ALIASES.get(platform.machine(), platform.machine()) == "alpha":
        return 0, "Landlock's calls have other numbers on alpha"
    result = _c_library().syscall(
        ctypes.c_long(_LANDLOCK_CREATE_RULESET), None, ctypes.c_size_t(0), ctypes.c_uint32(1)
    )
    if result >= 0:
        return result, ""
    err = ctypes.get_errno()
    if err == errno.ENOSYS:
        return 0, "this kernel has no Landlock (needs Linux 5.13 built with it)"
    if err == errno.EOPNOTSUPP:
        return 0, "Landlock is built in but not enabled at boot (add landlock to the lsm= kernel parameter)"
    return 0, f"Landlock: {os.strerror(err)}"


def _handled_fs(abi: int) -> int:
    rights = _FS_ABI1
    if abi >= 2:
        rights |= _FS_REFER
    if abi >= 3:
        rights |= _FS_TRUNCATE
    if abi >= 5:
        rights |= _FS_IOCTL_DEV
    return rights


# ---------------------------------------------------------------- seccomp


def _seccomp(report: dict) -> None:
    program = seccomp_program()
    if program is None:
        report["seccomp"] = f"off: no filter for the {platform.machine()} architecture"
        return
    if _prctl_value(_PR_GET_SECCOMP) < 0 and ctypes.get_errno() == errno.EINVAL:
        report["seccomp"] = "off: this kernel has no seccomp"
        return
    filters = ctypes.create_string_buffer(program)
    prog = _SockFprog(len(program) // 8, ctypes.addressof(filters))
    result = _c_library().prctl(
        ctypes.c_int(_PR_SET_SECCOMP), ctypes.c_ulong(_SECCOMP_MODE_FILTER), ctypes.byref(prog), 0, 0
    )
    if result != 0:
        err = ctypes.get_errno()
        report["seccomp"] = f"off: {os.strerror(err)}"
        return
    report["seccomp"] = "on"


class _SockFprog(ctypes.Structure):
    _fields_ = [("len", ctypes.c_ushort), ("filter", ctypes.c_void_p)]


def seccomp_program() -> bytes | None:
    """The BPF filter: a foreign architecture (or x32) kills the process; socket() and the calls
    in _SYSCALLS fail with EPERM; clone with a namespace flag fails with EPERM; clone3 (whose
    flags a filter cannot read) fails with ENOSYS so that the C library falls back to clone.
    socketpair stays allowed: a pair is private to the process, while a new unix socket could
    connect to any daemon's path on the machine, which no namespace here closes."""
    machine = _MACHINE_ALIASES.get(platform.machine(), platform.machine())
    if machine not in _SECCOMP_ARCHES:
        return None
    audit_arch, refuse_x32 = _SECCOMP_ARCHES[machine]
    numbers = _syscall_table()[machine]

    def op(code, k, jt=0, jf=0):
        return struct.pack("=HBBI", code, jt, jf, k)

    kill, allow = op(_BPF_RET_K, _SECCOMP_RET_KILL_PROCESS), op(_BPF_RET_K, _SECCOMP_RET_ALLOW)
    eperm = op(_BPF_RET_K, _SECCOMP_RET_ERRNO | errno.EPERM)
    code = [op(_BPF_LD_W_ABS, 4), op(_BPF_JEQ_K, audit_arch, 1, 0), kill, op(_BPF_LD_W_ABS, 0)]
    if refuse_x32:
        code += [op(_BPF_JGE_K, _X32_SYSCALL_BIT, 0, 1), kill]
    for name, number in numbers.items():
        if name not in _NOT_DENIED:
            code += [op(_BPF_JEQ_K, number, 0, 1), eperm]
    code += [op(_BPF_JEQ_K, numbers["clone3"], 0, 1), op(_BPF_RET_K, _SECCOMP_RET_ERRNO | errno.ENOSYS)]
    code += [
        op(_BPF_JEQ_K, numbers["clone"], 0, 3),
        op(_BPF_LD_W_ABS, 16),  # the low half of args[0], the flags (little-endian)
        op(_BPF_JSET_K, _CLONE_ANY_NAMESPACE, 0, 1),
        eperm,
        allow,
    ]
    return b"".join(code)


# ---------------------------------------------------------------- probing (for `ev3sim2d doctor`)


def probe() -> dict:
    """What this kernel offers a brick, without entering anything here: trials run in forked
    children.  Keys: kernel, machine, root, uid, landlock_abi, landlock, namespaces_as_root,
    user_ns, seccomp, no_new_privs, subreaper."""
    if not linux_kernel():
        return _probe_elsewhere()
    abi, why = landlock_abi()
    as_root = 0 in os.getresuid()
    info: dict = {
        "linux": True,
        "kernel": os.uname().release,
        "machine": platform.machine(),
        "root": as_root,
        "uid": os.getuid(),
        "landlock_abi": abi,
        "landlock": f"on (ABI {abi})" if abi else f"off: {why}",
        "namespaces_as_root": _trial(_try_namespaces_as_root) if as_root else "not root",
        "user_ns": _trial(_try_user_namespace),
        "seccomp": _trial(_try_seccomp),
        "no_new_privs": _trial(lambda: _prctl(_PR_SET_NO_NEW_PRIVS, 1)),
        "subreaper": _trial(lambda: _prctl(36, 1)),  # PR_SET_CHILD_SUBREAPER, for the simulator
    }
    return info


def _probe_elsewhere() -> dict:
    """The same keys on a system without the Linux kernel's interfaces: none of its layers."""
    return {
        "linux": False,
        "kernel": f"{platform.system()} {platform.release()}",
        "machine": platform.machine(),
        "root": hasattr(os, "getuid") and os.getuid() == 0,
        "uid": os.getuid() if hasattr(os, "getuid") else None,
        "landlock_abi": 0,
        "landlock": NOT_HERE,
        "namespaces_as_root": NOT_HERE,
        "user_ns": NOT_HERE,
        "seccomp": NOT_HERE,
        "no_new_privs": NOT_HERE,
        "subreaper": NOT_HERE,
        "rlimits": "on" if _resource() is not None else "off: this system has no resource limits",
    }


def _trial(attempt) -> str:
    """Run `attempt` in a forked child: "on", or "off: <why>" as the child said it."""
    read_end, write_end = os.pipe()
    pid = os.fork()
    if pid == 0:
        code = 1
        try:
            os.close(read_end)
            attempt()
            code = 0
        except BaseException as err:
            os.write(write_end, str(err.strerror if isinstance(err, OSError) else err).encode()[:500])
        finally:
            os._exit(code)
    os.close(write_end)
    with open(read_end, "rb") as pipe:
        why = pipe.read().decode(errors="replace")
    _, status = os.waitpid(pid, 0)
    if os.WIFEXITED(status) and os.WEXITSTATUS(status) == 0:
        return "on"
    return f"off: {why or 'the trial died'}"


def _try_namespaces_as_root() -> None:
    _unshare(_BRICK_NAMESPACES)


def _try_user_namespace() -> None:
    if 0 in os.getresuid():  # as a brick run by root would: as the unprivileged uid
        os.setgroups([])
        os.setresgid(65534, 65534, 65534)
        os.setresuid(65534, 65534, 65534)
    uid, gid = os.getuid(), os.getgid()
    try:
        _unshare(_CLONE_NEWUSER)
    except OSError as err:
        raise OSError(err.errno, _user_namespace_refusal(err)) from err
    _map_ids(uid, gid)
    _unshare(_BRICK_NAMESPACES)


def _try_seccomp() -> None:
    _prctl(_PR_SET_NO_NEW_PRIVS, 1)
    report: dict = {}
    _seccomp(report)
    if report["seccomp"] != "on":
        raise OSError(errno.ENOSYS, report["seccomp"])


# ---------------------------------------------------------------- the C library


def _prctl_value(option: int, *args: int) -> int:
    values = [ctypes.c_ulong(a) for a in (*args, 0, 0, 0, 0)[:4]]
    return _c_library().prctl(ctypes.c_int(option), *values)


def _prctl(option: int, *args: int) -> int:
    result = _prctl_value(option, *args)
    if result < 0:
        err = ctypes.get_errno()
        raise OSError(err, f"prctl({option}): {os.strerror(err)}")
    return result


def _unshare(flags: int) -> None:
    if _c_library().unshare(ctypes.c_int(flags)) != 0:
        err = ctypes.get_errno()
        raise OSError(err, os.strerror(err))


def _mount(source, target, fstype, flags, data=None) -> None:
    def c(text):
        return None if text is None else os.fsencode(text)

    if _c_library().mount(c(source), c(target), c(fstype), ctypes.c_ulong(flags), c(data)) != 0:
        err = ctypes.get_errno()
        raise OSError(err, f"mount {target}: {os.strerror(err)}")


def _syscall(number: int, *args) -> int:
    converted = [ctypes.c_long(a) if isinstance(a, int) else a for a in args]
    result = _c_library().syscall(ctypes.c_long(number), *converted)
    if result < 0:
        err = ctypes.get_errno()
        raise OSError(err, f"syscall {number}: {os.strerror(err)}")
    return result
