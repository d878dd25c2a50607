"""Classroom exercises graded at the level of the algorithm's state (docs/exercises.md).

In a student notebook: ``check("span_rule")`` runs the public cases of the
answer defined in the notebook. For teachers: ``python -m scanviz exercises
list|release|key new``, ``python -m scanviz grade``. Writing an exercise:
`scanviz.exercises.core.Exercise`, registered in `scanviz.exercises.catalog`.
"""

from .catalog import exercises, get
from .check import check, public_inputs
from .core import Case, Exercise, Variant

__all__ = [
    "Case",
    "Exercise",
    "Variant",
    "check",
    "exercises",
    "get",
    "public_inputs",
]
