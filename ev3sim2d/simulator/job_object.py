"""A Windows Job Object for one brick: its limits, and its end with the simulator's.

Windows has no process groups, rlimits or PID namespaces; a Job Object does their work.  The
simulator makes one per brick and assigns the brick to it right after it starts it; every process
the brick's program starts is in the job too.  The job caps the memory all of them commit together,
how many of them run at once and the user-mode CPU time they use together; an unhandled exception
ends a process at once (no error-report dialog hangs a class run); and when the simulator's handle
closes (it closes the job, ends or is killed) Windows kills every process still in the job.

Only `ctypes` and the standard library; the module imports everywhere, and `available()` says
whether kernel32 and its job functions are here.
"""

from __future__ import annotations

import ctypes
import functools
import subprocess

# LimitFlags of JOBOBJECT_BASIC_LIMIT_INFORMATION (winnt.h)
JOB_OBJECT_LIMIT_JOB_TIME = 0x00000004
JOB_OBJECT_LIMIT_ACTIVE_PROCESS = 0x00000008
JOB_OBJECT_LIMIT_JOB_MEMORY = 0x00000200
JOB_OBJECT_LIMIT_DIE_ON_UNHANDLED_EXCEPTION = 0x00000400
JOB_OBJECT_LIMIT_KILL_ON_JOB_CLOSE = 0x00002000
JOB_OBJECT_EXTENDED_LIMIT_INFORMATION_CLASS = 9  # JOBOBJECTINFOCLASS JobObjectExtendedLimitInformation

PROCESS_TERMINATE = 0x0001  # the rights AssignProcessToJobObject needs on a process handle
PROCESS_SET_QUOTA = 0x0100

ERROR_NOT_ENOUGH_QUOTA = 1816
# At the job's CPU-time limit (PerJobUserTimeLimit) Windows ends every process of the job with this
# exit code (JOB_OBJECT_TERMINATE_AT_END_OF_JOB, the default EndOfJobTimeAction).
CPU_LIMIT_EXIT_CODE = ERROR_NOT_ENOUGH_QUOTA

TICKS_PER_SECOND = 10_000_000  # job times are in 100 ns ticks


def limit_structures(size_t: type) -> tuple[type, type, type]:
    """JOBOBJECT_BASIC_LIMIT_INFORMATION, IO_COUNTERS and JOBOBJECT_EXTENDED_LIMIT_INFORMATION for a
    Windows whose SIZE_T (and ULONG_PTR) is `size_t`: ctypes.c_uint64 on 64-bit Windows, c_uint32 on
    32-bit.  Fixed-width types throughout (a DWORD is 32 bits; ctypes' c_ulong is 64 on Linux), so the
    layout of either Windows can be built, and checked, on any machine."""
    dword = ctypes.c_uint32
    large_integer = ctypes.c_int64  # LARGE_INTEGER: its QuadPart, 8-byte aligned on x86 and x64

    class JOBOBJECT_BASIC_LIMIT_INFORMATION(ctypes.Structure):
        _fields_ = [
            ("PerProcessUserTimeLimit", large_integer),
            ("PerJobUserTimeLimit", large_integer),
            ("LimitFlags", dword),
            ("MinimumWorkingSetSize", size_t),
            ("MaximumWorkingSetSize", size_t),
            ("ActiveProcessLimit", dword),
            ("Affinity", size_t),  # ULONG_PTR
            ("PriorityClass", dword),
            ("SchedulingClass", dword),
        ]

    class IO_COUNTERS(ctypes.Structure):
        _fields_ = [
            ("ReadOperationCount", ctypes.c_uint64),
            ("WriteOperationCount", ctypes.c_uint64),
            ("OtherOperationCount", ctypes.c_uint64),
            ("ReadTransferCount", ctypes.c_uint64),
            ("WriteTransferCount", ctypes.c_uint64),
            ("OtherTransferCount", ctypes.c_uint64),
        ]

    class JOBOBJECT_EXTENDED_LIMIT_INFORMATION(ctypes.Structure):
        _fields_ = [
            ("BasicLimitInformation", JOBOBJECT_BASIC_LIMIT_INFORMATION),
            ("IoInfo", IO_COUNTERS),
            ("ProcessMemoryLimit", size_t),
            ("JobMemoryLimit", size_t),
            ("PeakProcessMemoryUsed", size_t),
            ("PeakJobMemoryUsed", size_t),
        ]

    return JOBOBJECT_BASIC_LIMIT_INFORMATION, IO_COUNTERS, JOBOBJECT_EXTENDED_LIMIT_INFORMATION


# This interpreter's own: SIZE_T is as wide as a pointer on Windows.
JOBOBJECT_BASIC_LIMIT_INFORMATION, IO_COUNTERS, JOBOBJECT_EXTENDED_LIMIT_INFORMATION = limit_structures(
    ctypes.c_size_t
)


@functools.cache
def _kernel32():
    """kernel32 with the prototypes of the functions used here, or None where there is none.

    A WinDLL of our own, so these argtypes touch no one else's ctypes.windll.kernel32."""
    win_dll = getattr(ctypes, "WinDLL", None)
    if win_dll is None:
        return None
    try:
        kernel32 = win_dll("kernel32", use_last_error=True)
        handle, bool_, dword, pointer = ctypes.c_void_p, ctypes.c_int, ctypes.c_uint32, ctypes.c_void_p
        prototypes = {
            "CreateJobObjectW": ([pointer, ctypes.c_wchar_p], handle),
            "SetInformationJobObject": ([handle, ctypes.c_int, pointer, dword], bool_),
            "AssignProcessToJobObject": ([handle, handle], bool_),
            "TerminateJobObject": ([handle, ctypes.c_uint], bool_),
            "CloseHandle": ([handle], bool_),
            "OpenProcess": ([dword, bool_, dword], handle),
        }
        for name, (argtypes, restype) in prototypes.items():
            function = getattr(kernel32, name)
            function.argtypes = argtypes
            function.restype = restype
    except (OSError, AttributeError):
        return None
    return kernel32


def available() -> bool:
    """Whether Job Objects can be made here (Windows: kernel32 and its job functions are there)."""
    return _kernel32() is not None


def _last_error() -> OSError:
    return ctypes.WinError(ctypes.get_last_error())


class JobObject:
    """One brick's Job Object, held by the simulator: the brick and everything it starts are in it.

    memory_mb: memory all its processes may commit together; processes: how many may run at once
    (the brick itself is one); cpu_s: user-mode CPU time of all of them together (None: no limit),
    at which Windows ends them all with CPU_LIMIT_EXIT_CODE.  close() it when the brick is stopped."""

    def __init__(self, memory_mb: int, processes: int, cpu_s: int | None) -> None:
        if memory_mb < 1 or processes < 1 or (cpu_s is not None and cpu_s < 1):
            raise ValueError(f"job limits must be positive: {memory_mb} MB, {processes} processes, {cpu_s} s")
        self.memory_mb = memory_mb
        self.processes = processes
        self.cpu_s = cpu_s
        self._handle: int | None = None
        kernel32 = _kernel32()
        if kernel32 is None:
            raise OSError("Job Objects are not available here (no kernel32)")
        self._kernel32 = kernel32
        handle = kernel32.CreateJobObjectW(None, None)
        if not handle:
            raise _last_error()
        self._handle = handle
        info = JOBOBJECT_EXTENDED_LIMIT_INFORMATION()
        basic = info.BasicLimitInformation
        basic.LimitFlags = (
            JOB_OBJECT_LIMIT_KILL_ON_JOB_CLOSE
            | JOB_OBJECT_LIMIT_JOB_MEMORY
            | JOB_OBJECT_LIMIT_ACTIVE_PROCESS
            | JOB_OBJECT_LIMIT_DIE_ON_UNHANDLED_EXCEPTION
        )
        largest = (1 << (8 * ctypes.sizeof(ctypes.c_size_t))) - 1  # more than a 32-bit Windows can address
        info.JobMemoryLimit = min(memory_mb * 1024 * 1024, largest)
        basic.ActiveProcessLimit = processes
        if cpu_s is not None:
            basic.LimitFlags |= JOB_OBJECT_LIMIT_JOB_TIME
            basic.PerJobUserTimeLimit = cpu_s * TICKS_PER_SECOND
        done = kernel32.SetInformationJobObject(
            handle, JOB_OBJECT_EXTENDED_LIMIT_INFORMATION_CLASS, ctypes.byref(info), ctypes.sizeof(info)
        )
        if not done:
            error = _last_error()
            self.close()
            raise error

    def assign(self, popen: subprocess.Popen) -> None:
        """Put a just-started process (and so everything it will start) in the job.

        Popen's own process handle where it has one (Windows' subprocess keeps it in `_handle`, with
        every right); else a handle opened on its pid with the two rights the assignment needs."""
        if self._handle is None:
            raise ValueError("this job is closed")
        kernel32 = self._kernel32
        process = getattr(popen, "_handle", None)
        opened = None
        if process is None:
            opened = kernel32.OpenProcess(PROCESS_SET_QUOTA | PROCESS_TERMINATE, False, popen.pid)
            if not opened:
                raise _last_error()
            process = opened
        try:
            if not kernel32.AssignProcessToJobObject(self._handle, int(process)):
                raise _last_error()
        finally:
            if opened is not None:
                kernel32.CloseHandle(opened)

    def terminate(self, exit_code: int = 1) -> None:
        """End every process in the job now, with this exit code (nothing to do once it is closed)."""
        if self._handle is None:
            return
        if not self._kernel32.TerminateJobObject(self._handle, exit_code):
            raise _last_error()

    def close(self) -> None:
        """Close the simulator's handle: Windows kills whatever is left in the job.  Idempotent."""
        handle, self._handle = self._handle, None
        if handle is not None:
            self._kernel32.CloseHandle(handle)

    def describe(self) -> str:
        """The job's limits, for the isolation report."""
        cpu = f"cpu {self.cpu_s} s" if self.cpu_s is not None else "no cpu limit"
        return (
            f"on (memory {self.memory_mb} MB, {self.processes} processes, {cpu}, killed with the simulator)"
        )
