"""The virtual clock: ticks in order, tasks in turn, the time limit."""

import _thread
import time

import pytest

from ev3sim2d.brick.scheduler import RunOver, Scheduler


def run_tasks(scheduler, bodies):
    tasks = [
        scheduler.spawn(f"t{i}", None, body, _thread.start_new_thread, main=True)
        for i, body in enumerate(bodies)
    ]
    scheduler.start()
    assert scheduler.settled.wait(10), "run did not settle"
    return tasks


def test_single_task_spends_time_and_ticks_run_on_the_way():
    ticks = []
    s = Scheduler(10_000, ticks.append, limit_us=None)
    run_tasks(s, [lambda: s.spend(35_000)])
    assert ticks == [10_000, 20_000, 30_000]
    assert s.now_us == 35_000
    assert s.end_reason == "finished"


def test_time_limit_raises_run_over_in_the_task_and_stops_at_the_limit():
    ticks = []
    caught = []

    def body():
        try:
            while True:
                s.spend(3_000)
        except RunOver:
            caught.append(s.now_us)
            raise

    s = Scheduler(10_000, ticks.append, limit_us=50_000)
    run_tasks(s, [body])
    assert caught == [50_000]
    assert ticks[-1] == 50_000
    assert s.end_reason == "time_limit"


def test_two_tasks_interleave_by_virtual_time_deterministically():
    log = []

    def worker(name, step):
        def body():
            for _ in range(3):
                log.append((s.now_us, name))
                s.spend(step)

        return body

    s = Scheduler(10_000, lambda t: None)
    run_tasks(s, [worker("a", 4_000), worker("b", 6_000)])
    assert log == [(0, "a"), (0, "b"), (4_000, "a"), (6_000, "b"), (8_000, "a"), (12_000, "b")]
    assert s.now_us == 18_000


def test_only_one_task_runs_at_a_time():
    running = []
    overlaps = []

    def body():
        for _ in range(20):
            running.append(1)
            if len(running) > 1:
                overlaps.append(s.now_us)
            time.sleep(0.0005)  # real time: another thread would get in here if it could
            running.pop()
            s.spend(1)

    s = Scheduler(10, lambda t: None)
    run_tasks(s, [body, body, body])
    assert overlaps == []
    assert s.now_us == 20


def test_wait_returns_when_the_condition_holds_or_times_out():
    s = Scheduler(10_000, lambda t: None)
    results = []

    def body():
        results.append(s.wait(lambda: s.now_us >= 30_000, None))
        results.append(s.now_us)
        results.append(s.wait(lambda: False, 25_000))
        results.append(s.now_us)

    run_tasks(s, [body])
    assert results == [True, 30_000, False, 55_000]


def test_tick_rate_must_be_positive():
    with pytest.raises(ValueError):
        Scheduler(0, lambda t: None)


def test_a_blocked_task_runs_again_when_woken_at_the_waker_s_time():
    channel = []
    log = []

    def waiter():
        log.append(("wait", s.now_us))
        woken = s.block(channel, None)
        log.append(("woken", s.now_us, woken))

    def waker():
        s.spend(25_000)
        s.wake(channel)
        log.append(("woke", s.now_us))
        s.spend(1_000)

    s = Scheduler(10_000, lambda t: None)
    run_tasks(s, [waiter, waker])
    assert log == [("wait", 0), ("woke", 25_000), ("woken", 25_000, True)]


def test_a_block_with_a_timeout_gives_up_at_the_timeout():
    channel = []
    results = []

    def body():
        results.append(s.block(channel, 30_000))
        results.append(s.now_us)
        results.append(channel)

    s = Scheduler(10_000, lambda t: None)
    run_tasks(s, [body])
    assert results == [False, 30_000, []]


def test_tasks_that_all_wait_for_each_other_end_the_run_as_a_deadlock():
    a, b = [], []
    s = Scheduler(10_000, lambda t: None)
    run_tasks(s, [lambda: s.block(a, None), lambda: s.block(b, None)])
    assert s.end_reason == "deadlock"
