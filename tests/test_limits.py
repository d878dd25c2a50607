"""The wall-clock limit stops code that runs on; readers refuse special files; bounded scans."""

import os
import time
import tracemalloc
from unittest import mock

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import limits
from scanviz.limits import (
    ResourceLimitError,
    file_limit,
    json_nesting,
    read_bounded,
    wall_clock_limit,
)


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


# --- issue 27: readers refuse what is not a regular file; json_nesting in bounded memory ----------


def test_issue27_read_bounded_refuses_a_fifo_without_blocking(tmp_path):
    fifo = tmp_path / "p.json"
    os.mkfifo(fifo)
    with (
        wall_clock_limit(5, Stop, "read_bounded blocked on a FIFO"),
        pytest.raises(
            ValueError, match=r"'.*p\.json' is a FIFO \(named pipe\), not a regular file"
        ),
    ):
        read_bounded(fifo)


@pytest.mark.parametrize(
    ("path", "kind"), [("/dev/zero", "a character device"), ("/dev/null", "a character device")]
)
def test_issue27_read_bounded_refuses_a_device(path, kind):
    with file_limit("1K"), pytest.raises(ValueError, match=f"^'{path}' is {kind}, not a regular"):
        read_bounded(path)


def test_issue27_read_bounded_refuses_a_directory(tmp_path):
    with pytest.raises(ValueError, match="is a directory, not a regular file"):
        read_bounded(tmp_path)


def test_issue27_read_bounded_still_reads_files_and_bounds_them(tmp_path):
    path = tmp_path / "a.txt"
    path.write_bytes(b"\xef\xbb\xbfabc")
    assert read_bounded(path) == "abc" and read_bounded(path, binary=True) == b"\xef\xbb\xbfabc"
    with file_limit(5), pytest.raises(ResourceLimitError, match="larger than the file limit"):
        read_bounded(path)


def test_issue27_json_nesting_scans_in_bounded_memory():
    text = "[" * 2**24  # 16 MiB: the whole-text scan took 18 bytes a character
    tracemalloc.start()
    try:
        depth, _ = json_nesting(text)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert depth == 2**24
    assert peak < 8 * 2**20, peak  # chunks of 2**18 characters: about 2 MiB


def _naive_nesting(text: str) -> int:
    depth = deepest = 0
    in_string = escaped = False
    for character in text:
        if in_string:
            in_string = escaped or character != '"'
            escaped = not escaped and character == "\\"
        elif character == '"':
            in_string = True
        elif character in "[{":
            depth += 1
            deepest = max(deepest, depth)
        elif character in "]}":
            depth -= 1
    return deepest


@settings(derandomize=True, max_examples=300, deadline=None)
@given(st.text(alphabet='[]{}"\\a ', max_size=60))
def test_issue27_json_nesting_carries_the_depth_across_chunks(text):
    with mock.patch.object(limits, "_NESTING_CHUNK", 3):
        assert json_nesting(text)[0] == _naive_nesting(text)
    assert json_nesting(text)[0] == _naive_nesting(text)
