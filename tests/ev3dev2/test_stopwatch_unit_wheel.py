"""StopWatch (on the virtual clock), distance units and wheels."""

import math

import pytest

from ev3dev2.stopwatch import StopWatch, StopWatchAlreadyStartedException
from ev3dev2.unit import DistanceCentimeters, DistanceFeet, DistanceMillimeters, DistanceStuds
from ev3dev2.wheel import EV3EducationSetTire, EV3Rim, EV3Tire


def test_stopwatch_follows_the_clock(make_brick):
    brick = make_brick()
    watch = StopWatch("lap")
    assert watch.value_ms == 0 and not watch.is_started

    watch.start()
    brick.sleep(1.5)
    assert watch.value_ms == pytest.approx(1500, abs=1)
    assert watch.is_elapsed_secs(1.4) and not watch.is_elapsed_ms(1600) and not watch.is_elapsed_ms(None)
    with pytest.raises(StopWatchAlreadyStartedException):
        watch.start()

    watch.stop()
    brick.sleep(10)
    assert watch.value_secs == pytest.approx(1.5, abs=0.001)
    assert watch.hms_str in ("00:00:01.500", "00:00:01.499")
    assert str(watch).startswith("lap: 00:00:01.")
    watch.restart()
    assert watch.value_ms == 0


def test_distance_units():
    assert DistanceCentimeters(5).mm == 50
    assert DistanceFeet(1).mm == pytest.approx(304.8)
    assert DistanceStuds(16).mm == 128
    assert str(DistanceMillimeters(3)) == "3mm"
    assert (2 * DistanceCentimeters(5)).mm == 100
    assert sorted([DistanceFeet(1), DistanceCentimeters(5)])[0].mm == 50


def test_wheels():
    assert EV3Tire().circumference_mm == pytest.approx(43.2 * math.pi)
    assert EV3Tire().radius_mm == pytest.approx(21.6)
    assert EV3Rim().diameter_mm == 30.0
    assert EV3EducationSetTire().width_mm == 28.0
