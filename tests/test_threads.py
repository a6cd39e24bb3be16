"""A program's threads run in virtual time, deterministically."""

import pytest

THREADED = """
    import threading, time, queue
    log = []
    lock = threading.Lock()
    done = threading.Event()
    q = queue.Queue()

    def worker(name, period):
        for i in range(3):
            with lock:
                log.append((round(time.time() % 1000, 3), name, i))
            time.sleep(period)
        q.put(name)

    a = threading.Thread(target=worker, args=("a", 0.1))
    b = threading.Thread(target=worker, args=("b", 0.15), daemon=True)
    a.start(); b.start()
    a.join()
    print("a joined at", round(time.monotonic() - 1000, 3), a.is_alive())
    print("first done", q.get(timeout=1))
    print("second done", q.get(timeout=1))
    b.join()
    print(log)
"""


def test_threads_interleave_in_virtual_time_the_same_way_every_run(run):
    first = run(THREADED)
    second = run(THREADED)
    assert first.status == "finished", first.reason
    lines = [o.text for o in first.trace.output]
    assert lines[0] == "a joined at 0.3 False"
    assert lines[1] == "first done a" and lines[2] == "second done b"
    assert [o.text for o in second.trace.output] == lines
    assert first.trace.fingerprint() == second.trace.fingerprint()


def test_event_wait_with_timeout_and_timer(run):
    result = run("""
        import threading, time
        e = threading.Event()
        t0 = time.time()
        print(e.wait(0.25), round(time.time() - t0, 3))
        threading.Timer(0.5, e.set).start()
        print(e.wait(5), round(time.time() - t0, 3))
    """)
    assert [o.text for o in result.trace.output] == ["False 0.25", "True 0.751"]  # printing takes 1 ms


def test_condition_and_semaphore(run):
    result = run("""
        import threading, time
        cond = threading.Condition()
        items = []
        def producer():
            for i in range(3):
                time.sleep(0.1)
                with cond:
                    items.append(i)
                    cond.notify()
        threading.Thread(target=producer).start()
        got = []
        with cond:
            while len(got) < 3:
                cond.wait_for(lambda: items)
                got.append((items.pop(0), round(time.perf_counter(), 2)))
        print(got)
        sem = threading.BoundedSemaphore(1)
        sem.acquire()
        print(sem.acquire(timeout=0.2), round(time.perf_counter(), 2))
    """)
    assert result.status == "finished", result.reason
    assert result.trace.output[0].text == "[(0, 0.1), (1, 0.2), (2, 0.3)]"
    assert result.trace.output[1].text == "False 0.5"


def test_a_non_daemon_thread_keeps_the_program_running_after_main_ends(run):
    result = run("""
        import threading, time
        def later():
            time.sleep(2)
            print("still here")
        threading.Thread(target=later).start()
    """)
    assert result.status == "finished"
    assert [o.text for o in result.trace.output] == ["still here"]
    assert result.sim_time_s == pytest.approx(2.0, abs=0.01)


def test_a_daemon_thread_ends_with_the_program(run):
    result = run("""
        import threading, time
        def forever():
            while True:
                time.sleep(0.1)
        threading.Thread(target=forever, daemon=True).start()
        time.sleep(1)
    """)
    assert result.status == "finished"
    assert result.sim_time_s == pytest.approx(1.0, abs=0.01)


def test_a_deadlock_is_reported(run):
    result = run("""
        import threading
        a, b = threading.Lock(), threading.Lock()
        def other():
            with b:
                threading.Event().wait(0.1)
                a.acquire()
        threading.Thread(target=other).start()
        with a:
            threading.Event().wait(0.2)
            b.acquire()
    """)
    assert result.status == "hung"
    assert "deadlock" in result.reason


def test_motors_from_two_threads(run):
    result = run("""
        import threading
        from ev3dev2.motor import LargeMotor, MediumMotor, OUTPUT_A, OUTPUT_B
        arm = MediumMotor(OUTPUT_A)
        wheel = LargeMotor(OUTPUT_B)
        t = threading.Thread(target=lambda: arm.on_for_degrees(50, 720))
        t.start()
        wheel.on_for_degrees(50, 360)
        t.join()
        print(arm.position, wheel.position)
    """)
    assert result.status == "finished", result.reason
    assert result.trace.output[0].text == "720 360"


def test_a_thread_pool_works_in_virtual_time(run):
    """concurrent.futures' ThreadPoolExecutor, as on a brick (Python 3.5 has it): its module takes a lock's
    _at_fork_reinit when imported, and its workers wait on a queue.SimpleQueue, which is C's and waits on
    a real lock.  Both failed: an AttributeError on import, then a pool stopped as hung."""
    result = run("""
        import concurrent.futures, queue, time
        def work(n):
            time.sleep(0.1 * n)
            return n * n
        with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
            print(list(pool.map(work, [1, 2, 3])), round(time.monotonic() % 1000, 2))
        q = queue.SimpleQueue()
        q.put("x")
        print(q.get(timeout=1), q.empty())
    """)
    assert result.status == "finished", result.reason
    # two workers: 1 on the first (until 0.1 s), 2 on the second (until 0.2 s), then 3 on the first
    assert [line.text for line in result.trace.output] == ["[1, 4, 9] 0.4", "x True"]
