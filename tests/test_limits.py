"""The wall-clock limit stops code that runs on, even code that catches the first alarm."""

import time

import pytest

from scanviz.limits import wall_clock_limit


class Stop(BaseException):
    pass


def test_a_loop_that_catches_the_first_alarm_is_stopped_anyway():
    caught = 0
    started = time.monotonic()
    with pytest.raises(Stop, match="too long"), wall_clock_limit(0.05, Stop, "too long"):
        while True:
            try:
                while True:
                    pass
            except Stop:
                caught += 1
                if caught > 3:
                    raise
    assert caught == 4 and time.monotonic() - started < 5


def test_nothing_is_raised_after_the_block():
    with wall_clock_limit(0.05, Stop, "late"):
        pass
    time.sleep(0.1)  # the timer was cancelled: no Stop arrives here
