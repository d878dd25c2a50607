"""The conformance category of the visibility algorithms fails on an algorithm that is wrong."""

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from scanviz.conformance.visibility_checks import visibility_vs_zbuffer
from scanviz.visibility import ALGORITHMS, Painter


@dataclass(frozen=True)
class Backwards(Painter):
    """The painter's algorithm nearest first: wrong wherever two polygons overlap."""

    name: ClassVar[str] = "backwards"

    def decide(self, surfaces, tracer):
        decision = super().decide(surfaces, tracer)
        return type(decision)(decision.stats, decision.pieces[::-1], "over")


def test_it_passes_on_the_algorithms_and_names_a_wrong_one(monkeypatch):
    assert visibility_vs_zbuffer(np.random.default_rng(0)).passed
    monkeypatch.setitem(ALGORITHMS, "backwards", Backwards)
    outcome = visibility_vs_zbuffer(np.random.default_rng(0))
    assert not outcome.passed and outcome.failure.startswith("backwards on slides_zbuffer")
    assert "samples differ from the z-buffer where the nearest is unique" in outcome.failure
