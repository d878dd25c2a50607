"""The course key: a fresh secret, commented TOML, strict loading (scanviz.exercises.key)."""

import dataclasses
import os
import tomllib

import pytest

from scanviz.exercises.catalog import exercises, get
from scanviz.exercises.key import CourseKey, ExerciseKey, key_text, load_key, new_key, write_key

SECRET = "0123456789abcdef" * 4


def _write(tmp_path, text):
    path = tmp_path / "key.toml"
    path.write_text(text)
    return path


def _valid(**changes):
    fields = {
        "secret": f'"{SECRET}"',
        "reveal": '"never"',
        "per_student": "false",
        "limits": "cpu_seconds = 30\nmemory_mb = 800\ncase_seconds = 2.5",
        "exercise": "points = 3\nhidden_cases = 5",
    }
    fields.update(changes)
    return (
        f"secret = {fields['secret']}\nreveal = {fields['reveal']}\n"
        f"per_student = {fields['per_student']}\n[limits]\n{fields['limits']}\n"
        f"[exercises.span_rule]\n{fields['exercise']}\n"
    )


def test_new_key_has_a_fresh_secret_and_the_catalogs_points():
    first, second = new_key(), new_key()
    assert first.secret != second.secret
    assert len(first.secret) == 64 and int(first.secret, 16) >= 0
    assert first.exercises == {e.id: ExerciseKey(e.points, 8) for e in exercises()}
    only = new_key(["span_rule"])
    assert only.exercises == {"span_rule": ExerciseKey(get("span_rule").points, 8)}
    with pytest.raises(ValueError, match="did you mean 'span_rule'"):
        new_key(["span_rul"])


def test_a_written_key_reads_back_equal_and_is_commented_toml(tmp_path):
    key = dataclasses.replace(new_key(), reveal="after_due", per_student=True, case_seconds=2.5)
    path = tmp_path / "course.toml"
    write_key(key, path)
    assert load_key(path) == key
    text = path.read_text()
    assert text.startswith("# scanviz course key: keep this file private")
    assert tomllib.loads(text)["limits"]["case_seconds"] == 2.5
    assert os.stat(path).st_mode & 0o077 == 0


def test_write_key_never_overwrites(tmp_path):
    path = tmp_path / "course.toml"
    path.write_text("precious")
    with pytest.raises(FileExistsError, match="course.toml"):
        write_key(new_key(), path)
    assert path.read_text() == "precious"


def test_exercise_ids_that_are_not_bare_toml_keys_are_quoted():
    key = CourseKey(SECRET, "never", False, 1.0, 512, 1.0, {"odd id.x": ExerciseKey(1, 2)})
    assert tomllib.loads(key_text(key))["exercises"]["odd id.x"] == {"points": 1, "hidden_cases": 2}


def test_load_key_reads_every_field(tmp_path):
    key = load_key(_write(tmp_path, _valid()))
    assert key == CourseKey(
        SECRET, "never", False, 30.0, 800, 2.5, {"span_rule": ExerciseKey(3, 5)}
    )


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"secret": '"abc"'}, "'secret' must be a string of at least 32 hex characters"),
        ({"secret": '"' + "z" * 40 + '"'}, "'secret' must be a string of at least 32 hex"),
        ({"reveal": '"sometimes"'}, "'reveal' must be one of ('never', 'after_due', 'always')"),
        ({"per_student": '"yes"'}, "'per_student' must be true or false"),
        ({"limits": "cpu_seconds = -1"}, "'limits.cpu_seconds' must be > 0"),
        ({"limits": "cpu_seconds = true"}, "'limits.cpu_seconds' must be a number"),
        ({"limits": "memory_mb = 100"}, "'limits.memory_mb' must be >= 512"),
        ({"limits": "memory_mb = 1024.5"}, "'limits.memory_mb' must be an integer"),
        ({"limits": "cpu_second = 3"}, "unknown field 'limits.cpu_second' (did you mean"),
        ({"exercise": "points = -1"}, "'exercises.span_rule.points' must be >= 0"),
        ({"exercise": "hidden_cases = 100000"}, "'exercises.span_rule.hidden_cases' must be <="),
        ({"exercise": "pionts = 3"}, "unknown field 'exercises.span_rule.pionts' (did you mean"),
    ],
)
def test_a_wrong_field_is_named_with_its_rule(tmp_path, change, message):
    with pytest.raises(ValueError, match="key.toml") as error:
        load_key(_write(tmp_path, _valid(**change)))
    assert message in str(error.value)


def test_unknown_exercises_fields_and_bad_toml_are_refused(tmp_path):
    text = _valid().replace("[exercises.span_rule]", "[exercises.span_rules]")
    with pytest.raises(
        ValueError, match=r"unknown exercise 'span_rules' \(did you mean 'span_rule'"
    ):
        load_key(_write(tmp_path, text))
    with pytest.raises(ValueError, match=r"unknown field 'revael' \(did you mean 'reveal'"):
        load_key(_write(tmp_path, "revael = 1\n" + _valid()))
    with pytest.raises(ValueError, match="is not valid TOML"):
        load_key(_write(tmp_path, "secret = "))
    with pytest.raises(ValueError, match="grades no exercise"):
        load_key(_write(tmp_path, f'secret = "{SECRET}"\n'))
