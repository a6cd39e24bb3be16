"""A brick's Job Object: the module imports everywhere, its structures have the layout of Microsoft's
headers, and on Windows the job holds the brick and all it starts to their limits and ends them with
the simulator.  The tests that start processes run only where Job Objects exist (the Windows CI)."""

import ctypes
import subprocess
import sys
import textwrap
import types

import pytest

from ev3sim2d.simulator import job_object
from ev3sim2d.simulator.job_object import CPU_LIMIT_EXIT_CODE, JobObject, available, limit_structures

windows_only = pytest.mark.skipif(not available(), reason="Job Objects are Windows'")

# The real interpreter: in a venv, Windows' python.exe is a redirector that runs it as a child
# process of its own, which would be one process more in the job.
PYTHON = getattr(sys, "_base_executable", None) or sys.executable
WAIT_S = 60


def offsets(structure):
    return {name: getattr(structure, name).offset for name, _ in structure._fields_}


def test_the_module_imports_everywhere_and_says_whether_it_can_make_jobs():
    assert isinstance(available(), bool)
    assert available() == (getattr(ctypes, "WinDLL", None) is not None)


@pytest.mark.skipif(available(), reason="here Job Objects can be made")
def test_where_there_is_no_kernel32_a_job_cannot_be_made():
    assert not available()
    with pytest.raises(OSError):
        JobObject(memory_mb=100, processes=2, cpu_s=1)


def test_the_structures_have_the_64_bit_layout_of_winnt_h():
    basic, io_counters, extended = limit_structures(ctypes.c_uint64)
    assert ctypes.sizeof(basic) == 64
    assert offsets(basic) == {
        "PerProcessUserTimeLimit": 0,
        "PerJobUserTimeLimit": 8,
        "LimitFlags": 16,
        "MinimumWorkingSetSize": 24,
        "MaximumWorkingSetSize": 32,
        "ActiveProcessLimit": 40,
        "Affinity": 48,
        "PriorityClass": 56,
        "SchedulingClass": 60,
    }
    assert ctypes.sizeof(io_counters) == 48
    assert list(offsets(io_counters).values()) == [0, 8, 16, 24, 32, 40]
    assert ctypes.sizeof(extended) == 144
    assert offsets(extended) == {
        "BasicLimitInformation": 0,
        "IoInfo": 64,
        "ProcessMemoryLimit": 112,
        "JobMemoryLimit": 120,
        "PeakProcessMemoryUsed": 128,
        "PeakJobMemoryUsed": 136,
    }


@pytest.mark.skipif(ctypes.alignment(ctypes.c_int64) != 8, reason="this machine aligns 64-bit integers to 4")
def test_the_structures_have_the_32_bit_layout_of_winnt_h():
    basic, io_counters, extended = limit_structures(ctypes.c_uint32)
    assert ctypes.sizeof(basic) == 48  # 44 bytes of fields, padded to the 8 of its LARGE_INTEGERs
    assert offsets(basic) == {
        "PerProcessUserTimeLimit": 0,
        "PerJobUserTimeLimit": 8,
        "LimitFlags": 16,
        "MinimumWorkingSetSize": 20,
        "MaximumWorkingSetSize": 24,
        "ActiveProcessLimit": 28,
        "Affinity": 32,
        "PriorityClass": 36,
        "SchedulingClass": 40,
    }
    assert ctypes.sizeof(io_counters) == 48
    assert ctypes.sizeof(extended) == 112
    assert offsets(extended) == {
        "BasicLimitInformation": 0,
        "IoInfo": 48,
        "ProcessMemoryLimit": 96,
        "JobMemoryLimit": 100,
        "PeakProcessMemoryUsed": 104,
        "PeakJobMemoryUsed": 108,
    }


def test_this_interpreters_structures_are_those_of_its_pointer_width():
    size_t = ctypes.c_uint64 if ctypes.sizeof(ctypes.c_void_p) == 8 else ctypes.c_uint32
    ours = (job_object.JOBOBJECT_BASIC_LIMIT_INFORMATION, job_object.IO_COUNTERS)
    ours += (job_object.JOBOBJECT_EXTENDED_LIMIT_INFORMATION,)
    for structure, reference in zip(ours, limit_structures(size_t), strict=True):
        assert ctypes.sizeof(structure) == ctypes.sizeof(reference)
        assert offsets(structure) == offsets(reference)


def test_the_flags_and_codes_have_their_documented_values():
    assert job_object.JOB_OBJECT_LIMIT_JOB_TIME == 0x4
    assert job_object.JOB_OBJECT_LIMIT_ACTIVE_PROCESS == 0x8
    assert job_object.JOB_OBJECT_LIMIT_JOB_MEMORY == 0x200
    assert job_object.JOB_OBJECT_LIMIT_DIE_ON_UNHANDLED_EXCEPTION == 0x400
    assert job_object.JOB_OBJECT_LIMIT_KILL_ON_JOB_CLOSE == 0x2000
    assert job_object.JOB_OBJECT_EXTENDED_LIMIT_INFORMATION_CLASS == 9
    assert job_object.PROCESS_TERMINATE == 0x1
    assert job_object.PROCESS_SET_QUOTA == 0x100
    assert CPU_LIMIT_EXIT_CODE == job_object.ERROR_NOT_ENOUGH_QUOTA == 1816


def test_limits_that_are_not_positive_are_our_bug():
    with pytest.raises(ValueError):
        JobObject(memory_mb=0, processes=2, cpu_s=None)
    with pytest.raises(ValueError):
        JobObject(memory_mb=100, processes=2, cpu_s=0)


# ---- anywhere: what a JobObject asks of kernel32, seen through a stand-in ----


class RecordingKernel32:
    """Stands in for kernel32: takes the calls JobObject makes and keeps what it was given."""

    JOB = 0x40
    OPENED = 0x80

    def __init__(self):
        self.limits = None
        self.info_class = None
        self.info_size = None
        self.set_information_works = True
        self.assigned = []
        self.opened = []
        self.terminated = []
        self.closed = []

    def CreateJobObjectW(self, attributes, name):
        assert attributes is None and name is None
        return self.JOB

    def SetInformationJobObject(self, job, info_class, info, size):
        assert job == self.JOB
        self.info_class, self.info_size = info_class, size
        self.limits = job_object.JOBOBJECT_EXTENDED_LIMIT_INFORMATION.from_buffer_copy(info._obj)
        return int(self.set_information_works)

    def AssignProcessToJobObject(self, job, process):
        assert job == self.JOB
        self.assigned.append(process)
        return 1

    def OpenProcess(self, access, inherit, pid):
        self.opened.append((access, inherit, pid))
        return self.OPENED

    def TerminateJobObject(self, job, exit_code):
        self.terminated.append((job, exit_code))
        return 1

    def CloseHandle(self, handle):
        self.closed.append(handle)
        return 1


@pytest.fixture
def kernel32(monkeypatch):
    recording = RecordingKernel32()
    monkeypatch.setattr(job_object, "_kernel32", lambda: recording)
    monkeypatch.setattr(ctypes, "get_last_error", lambda: 5, raising=False)
    monkeypatch.setattr(ctypes, "WinError", lambda code: OSError(code, "Access is denied"), raising=False)
    return recording


def test_a_job_asks_for_its_limits_in_one_extended_limit_information(kernel32):
    job = JobObject(memory_mb=100, processes=2, cpu_s=3)
    assert kernel32.info_class == 9
    assert kernel32.info_size == ctypes.sizeof(job_object.JOBOBJECT_EXTENDED_LIMIT_INFORMATION)
    basic = kernel32.limits.BasicLimitInformation
    assert basic.LimitFlags == 0x2000 | 0x200 | 0x8 | 0x400 | 0x4
    assert kernel32.limits.JobMemoryLimit == 100 * 1024 * 1024
    assert basic.ActiveProcessLimit == 2
    assert basic.PerJobUserTimeLimit == 3 * 10_000_000  # 100 ns ticks
    assert basic.PerProcessUserTimeLimit == 0 and kernel32.limits.ProcessMemoryLimit == 0
    assert job.describe() == "on (memory 100 MB, 2 processes, cpu 3 s, killed with the simulator)"


def test_a_job_without_a_cpu_limit_sets_none(kernel32):
    job = JobObject(memory_mb=1024, processes=64, cpu_s=None)
    basic = kernel32.limits.BasicLimitInformation
    assert not basic.LimitFlags & 0x4 and basic.PerJobUserTimeLimit == 0
    assert job.describe() == "on (memory 1024 MB, 64 processes, no cpu limit, killed with the simulator)"


def test_a_process_is_assigned_through_popens_handle_or_one_opened_on_its_pid(kernel32):
    job = JobObject(memory_mb=100, processes=2, cpu_s=None)
    job.assign(types.SimpleNamespace(pid=1234, _handle=0x99))
    assert kernel32.assigned == [0x99] and kernel32.opened == []
    job.assign(types.SimpleNamespace(pid=1234))
    assert kernel32.opened == [(0x100 | 0x1, False, 1234)]  # PROCESS_SET_QUOTA | PROCESS_TERMINATE
    assert kernel32.assigned == [0x99, kernel32.OPENED]
    assert kernel32.closed == [kernel32.OPENED]  # the handle it opened, not the job's


def test_terminate_then_close_once(kernel32):
    job = JobObject(memory_mb=100, processes=2, cpu_s=None)
    job.terminate()
    job.terminate(exit_code=7)
    assert kernel32.terminated == [(kernel32.JOB, 1), (kernel32.JOB, 7)]
    job.close()
    job.close()
    job.terminate()
    assert kernel32.closed == [kernel32.JOB]
    assert len(kernel32.terminated) == 2
    with pytest.raises(ValueError):
        job.assign(types.SimpleNamespace(pid=1234))


def test_a_job_whose_limits_windows_refuses_is_closed_and_says_why(kernel32):
    kernel32.set_information_works = False
    with pytest.raises(OSError, match="Access is denied"):
        JobObject(memory_mb=100, processes=2, cpu_s=None)
    assert kernel32.closed == [kernel32.JOB]


# ---- on Windows: real processes in a real job ----


class ProcessHandles:
    """The few kernel32 calls the tests make themselves, to look at a process from outside its job."""

    SYNCHRONIZE = 0x00100000
    PROCESS_QUERY_LIMITED_INFORMATION = 0x1000
    STILL_ACTIVE = 259
    WAIT_OBJECT_0 = 0

    def __init__(self):
        k = ctypes.WinDLL("kernel32", use_last_error=True)
        k.OpenProcess.argtypes = [ctypes.c_uint32, ctypes.c_int, ctypes.c_uint32]
        k.OpenProcess.restype = ctypes.c_void_p
        k.GetExitCodeProcess.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_uint32)]
        k.GetExitCodeProcess.restype = ctypes.c_int
        k.WaitForSingleObject.argtypes = [ctypes.c_void_p, ctypes.c_uint32]
        k.WaitForSingleObject.restype = ctypes.c_uint32
        k.CloseHandle.argtypes = [ctypes.c_void_p]
        k.CloseHandle.restype = ctypes.c_int
        self.k = k

    def open(self, pid: int) -> int:
        handle = self.k.OpenProcess(self.SYNCHRONIZE | self.PROCESS_QUERY_LIMITED_INFORMATION, False, pid)
        if not handle:
            raise ctypes.WinError(ctypes.get_last_error())
        return handle

    def running(self, handle: int) -> bool:
        code = ctypes.c_uint32()
        assert self.k.GetExitCodeProcess(handle, ctypes.byref(code))
        return code.value == self.STILL_ACTIVE

    def ends_within(self, handle: int, seconds: float) -> bool:
        return self.k.WaitForSingleObject(handle, int(seconds * 1000)) == self.WAIT_OBJECT_0

    def close(self, handle: int) -> None:
        self.k.CloseHandle(handle)


@pytest.fixture
def jobs():
    """jobs(memory_mb, processes, cpu_s) -> a JobObject, closed (its processes killed) after the test."""
    made = []

    def make(memory_mb=256, processes=8, cpu_s=None):
        job = JobObject(memory_mb=memory_mb, processes=processes, cpu_s=cpu_s)
        made.append(job)
        return job

    yield make
    for job in made:
        job.close()


@pytest.fixture
def children():
    """children(source) -> a child python that does nothing until it reads a line (so that it is in
    its job before it acts), then runs `source`; what it prints comes back on its stdout.  Killed
    after the test if it still runs."""
    started = []

    def start(source: str) -> subprocess.Popen:
        program = "import sys\nsys.stdin.readline()\n" + textwrap.dedent(source)
        child = subprocess.Popen(
            [PYTHON, "-I", "-c", program],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        started.append(child)
        return child

    yield start
    for child in started:
        if child.poll() is None:
            child.kill()
        try:
            child.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            pass


def go(child: subprocess.Popen) -> None:
    """Let a waiting child run its source."""
    try:
        child.stdin.write("go\n")
        child.stdin.flush()
    except OSError:
        pass  # it has ended already


@windows_only
def test_the_memory_of_the_job_is_limited(jobs, children):
    job = jobs(memory_mb=100)
    child = children(
        """
        small = bytearray(20 * 1024 * 1024)  # within the limit
        print("small ok", flush=True)
        try:
            big = bytearray(500 * 1024 * 1024)
            print("big ok")
        except MemoryError:
            print("MemoryError")
        """
    )
    job.assign(child)
    go(child)
    out, err = child.communicate(timeout=WAIT_S)
    assert out.split() == ["small", "ok", "MemoryError"], err
    assert child.returncode == 0, err


@windows_only
def test_the_number_of_processes_of_the_job_is_limited(jobs, children):
    job = jobs(processes=2)  # the child and one more
    child = children(
        """
        import subprocess, time
        started, refused = [], 0
        for _ in range(3):
            try:
                started.append(subprocess.Popen(
                    [sys.executable, "-I", "-c", "import time; time.sleep(60)"],
                    stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
            except OSError:
                refused += 1
        time.sleep(1)
        running = sum(p.poll() is None for p in started)
        print(running, refused, flush=True)
        for p in started:
            p.kill()
        """
    )
    job.assign(child)
    go(child)
    out, err = child.communicate(timeout=WAIT_S)
    running, refused = (int(word) for word in out.split())
    # of the 3 it asked for, one runs; Windows refused the others (or ended them at once)
    assert running == 1, f"{running} running, {refused} refused; {err}"


@windows_only
def test_closing_the_job_kills_the_child_and_its_grandchild(jobs, children):
    handles = ProcessHandles()
    job = jobs()
    child = children(
        """
        import subprocess, time
        grandchild = subprocess.Popen(
            [sys.executable, "-I", "-c", "import time; time.sleep(120)"],
            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        print(grandchild.pid, flush=True)
        time.sleep(120)
        """
    )
    job.assign(child)
    go(child)
    grandchild_pid = int(child.stdout.readline())
    grandchild = handles.open(grandchild_pid)  # while the child holds it too: the pid is not reused
    try:
        assert handles.running(grandchild)
        assert child.poll() is None
        job.close()
        assert handles.ends_within(grandchild, 10)
        child.wait(timeout=10)
        job.close()  # again: nothing to do
    finally:
        handles.close(grandchild)


@windows_only
def test_at_the_cpu_limit_windows_ends_the_job_with_its_exit_code(jobs, children):
    job = jobs(cpu_s=1)
    child = children(
        """
        while True:
            pass
        """
    )
    job.assign(child)
    go(child)
    assert child.wait(timeout=WAIT_S) == CPU_LIMIT_EXIT_CODE


@windows_only
def test_terminate_ends_every_process_of_the_job_with_the_code_given(jobs, children):
    job = jobs()
    child = children("import time\ntime.sleep(120)\n")
    job.assign(child)
    job.terminate(exit_code=7)
    assert child.wait(timeout=10) == 7
    job.close()
    job.terminate()  # a closed job has nothing left to end


@windows_only
def test_a_process_known_only_by_its_pid_can_be_assigned(jobs, children):
    job = jobs()
    child = children("import time\ntime.sleep(120)\n")
    job.assign(types.SimpleNamespace(pid=child.pid))  # through OpenProcess, as for a zygote's child
    job.close()
    child.wait(timeout=10)  # killed with the job: it was in it
