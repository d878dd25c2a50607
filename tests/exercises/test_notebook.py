"""Reading notebooks and finding answers by their marker lines (scanviz.exercises.notebook)."""

import json

import nbformat
import pytest
from nbformat import v4

from scanviz import limits
from scanviz.exercises.notebook import (
    ANSWER_MARKER,
    Answers,
    NotebookError,
    find_answers,
    merge_answers,
    read_notebook,
)

BODY = "def span_rule(crossings, rule):\n    return []\n"


def _notebook(*cells):
    return v4.new_notebook(cells=list(cells))


def test_an_answer_is_the_whole_source_of_the_cell_that_starts_with_the_marker():
    source = f"{ANSWER_MARKER}span_rule\n{BODY}"
    found = find_answers(_notebook(v4.new_markdown_cell("intro"), v4.new_code_cell(source)))
    assert found.answers == {"span_rule": source}
    assert found.notes == {} and found.problems == {}


def test_trailing_whitespace_after_the_marker_is_tolerated_and_list_sources_are_joined():
    cell = v4.new_code_cell("")
    cell["source"] = [f"{ANSWER_MARKER}span_rule  \t\n", BODY]
    assert find_answers(_notebook(cell)).answers["span_rule"].endswith(BODY)


def test_position_and_metadata_do_not_matter():
    answer = v4.new_code_cell(f"{ANSWER_MARKER}span_rule\n{BODY}")
    moved = v4.new_code_cell(
        answer["source"], metadata={"tags": ["x"], "nbgrader": {"grade": True}}
    )
    first = find_answers(_notebook(answer, v4.new_code_cell("x = 1")))
    second = find_answers(_notebook(v4.new_code_cell("x = 1"), v4.new_markdown_cell("m"), moved))
    assert first.answers == second.answers == {"span_rule": answer["source"]}


def test_a_marker_in_a_markdown_cell_or_not_on_the_first_line_is_not_an_answer():
    found = find_answers(
        _notebook(
            v4.new_markdown_cell(f"{ANSWER_MARKER}span_rule\n{BODY}"),
            v4.new_code_cell(f"x = 1\n{ANSWER_MARKER}span_rule\n{BODY}"),
        )
    )
    assert found.answers == {} and found.problems == {}


def test_a_duplicated_marker_grades_the_last_cell_and_says_so():
    # Students copy cells (nbgrader #1083, #981): the last attempt is graded, not none.
    cells = [v4.new_code_cell(f"{ANSWER_MARKER}span_rule\n{BODY}# attempt {k}\n") for k in range(2)]
    found = find_answers(_notebook(v4.new_markdown_cell("a"), v4.new_code_cell("x = 1"), *cells))
    assert found.answers["span_rule"] == cells[1]["source"]
    assert found.notes["span_rule"] == (
        "2 cells start with '# scanviz: answer span_rule' (cells 3 and 4): "
        "the last one, cell 4, was graded"
    )


def test_merged_notebooks_grade_the_released_notebooks_answer_and_say_so():
    scratch = Answers({"span_rule": "scratch"})
    released = Answers({"span_rule": "released"})
    merged = merge_answers([("05_span_rule.ipynb", released), ("zz scratch.ipynb", scratch)])
    assert merged.answers == {"span_rule": "released"}
    assert merged.notes["span_rule"].endswith("the one in 05_span_rule.ipynb was graded")
    merged = merge_answers([("a.ipynb", released), ("b.ipynb", scratch)])
    assert merged.answers == {"span_rule": "scratch"}
    assert "answered in 2 notebooks (a.ipynb, b.ipynb)" in merged.notes["span_rule"]


def test_an_unknown_exercise_id_gets_a_suggestion():
    found = find_answers(_notebook(v4.new_code_cell(f"{ANSWER_MARKER}spanrule\n{BODY}")))
    assert found.answers == {}
    assert "unknown exercise 'spanrule' (did you mean 'span_rule'?)" in found.problems["spanrule"]


def test_an_almost_marker_is_reported_but_an_exact_one_elsewhere_wins():
    near = v4.new_code_cell(f"#scanviz:answer span_rule\n{BODY}")
    found = find_answers(_notebook(near))
    assert found.answers == {}
    assert "must be exactly '# scanviz: answer span_rule'" in found.problems["span_rule"]
    exact = v4.new_code_cell(f"{ANSWER_MARKER}span_rule\n{BODY}")
    assert find_answers(_notebook(near, exact)).problems == {}


def test_read_notebook_reads_what_nbformat_writes(tmp_path):
    path = tmp_path / "alice.ipynb"
    nbformat.write(_notebook(v4.new_code_cell(f"{ANSWER_MARKER}span_rule\n{BODY}")), path)
    notebook = read_notebook(path)
    assert isinstance(notebook, nbformat.NotebookNode)
    assert find_answers(notebook).answers["span_rule"] == f"{ANSWER_MARKER}span_rule\n{BODY}"


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ('{"cells": [', "is not valid JSON: Expecting value at line 1 column 12"),
        ("[1, 2]", "the top level is not a JSON object"),
        ('{"cells": []}', "no 'nbformat' version number"),
        ('{"nbformat": 4, "cells": {}}', "'cells' must be a list"),
        ('{"nbformat": 4, "cells": [{"source": "x"}]}', "cell 1 has no 'cell_type'"),
        (
            '{"nbformat": 4, "cells": [{"cell_type": "code", "source": 3}]}',
            "cell 1: 'source' must be a string or a list of strings",
        ),
        ("[" * 200 + "]" * 200, "nested over 100 levels"),
    ],
)
def test_a_file_that_is_not_a_notebook_is_a_notebook_error_naming_it(tmp_path, text, expected):
    path = tmp_path / "bob.ipynb"
    path.write_text(text)
    with pytest.raises(NotebookError, match="bob.ipynb") as error:
        read_notebook(path)
    assert expected in str(error.value)
    assert isinstance(error.value, ValueError)


def test_reading_is_bounded_by_the_file_limit(tmp_path):
    path = tmp_path / "big.ipynb"
    cell = {"cell_type": "code", "source": "x" * 5000, "metadata": {}}
    path.write_text(json.dumps({"nbformat": 4, "nbformat_minor": 5, "cells": [cell]}))
    with limits.file_limit("1K"), pytest.raises(NotebookError, match="larger than the file limit"):
        read_notebook(path)
    with pytest.raises(NotebookError, match="cannot be read"):
        read_notebook(tmp_path / "missing.ipynb")
