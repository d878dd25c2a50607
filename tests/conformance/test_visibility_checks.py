"""The category "visibility agrees with the z-buffer" passes on the algorithms and fails on wrong ones."""

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from scanviz.conformance.visibility_checks import agreement, visibility_agrees
from scanviz.visibility import ALGORITHMS, BSP


@dataclass(frozen=True)
class Backwards(BSP):
    """BSP painted in reverse, keeping BSP's promise: farther polygons shown where two overlap."""

    name: ClassVar[str] = "backwards"

    def decide(self, surfaces, tracer):
        decision = super().decide(surfaces, tracer)
        return type(decision)(decision.stats, decision.pieces[::-1], "over")


@dataclass(frozen=True)
class Leaky(BSP):
    """BSP that loses the second half of every split polygon's pieces: holes."""

    name: ClassVar[str] = "leaky"

    def decide(self, surfaces, tracer):
        decision = super().decide(surfaces, tracer)
        kept = tuple(piece for piece in decision.pieces if not piece.label.endswith("b"))
        return type(decision)(decision.stats, kept, "over")


def test_it_passes_on_the_algorithms():
    outcome = visibility_agrees(np.random.default_rng(0), 16)
    assert outcome.passed, outcome.failure
    assert "runs of 5 algorithms on 21 scenes" in outcome.counts


def test_it_names_an_algorithm_that_shows_farther_polygons(monkeypatch):
    monkeypatch.setitem(ALGORITHMS, "backwards", Backwards)
    outcome = visibility_agrees(np.random.default_rng(0), 4)
    assert not outcome.passed and outcome.failure.startswith("backwards on slides_zbuffer")
    assert (
        "9 samples farther than the nearest by more than 1.8e-08" in outcome.failure
    )  # 2 x 1e-9 x 9


def test_it_names_an_algorithm_that_leaves_holes(monkeypatch):
    monkeypatch.setitem(ALGORITHMS, "leaky", Leaky)
    outcome = visibility_agrees(np.random.default_rng(0), 4)
    assert not outcome.passed and outcome.failure.startswith("leaky on ")
    assert " holes, " in outcome.failure and "missed by the pieces" in outcome.failure


def test_agreement_counts_what_went_wrong(monkeypatch):
    monkeypatch.setitem(ALGORITHMS, "leaky", Leaky)
    from scanviz.visibility.examples import split_hole

    found = agreement("leaky", split_hole(), 32, 32)
    assert found.holes == found.missed > 0 and found.double == 0  # 1b's samples are lost
    assert not found.coverage_exact
    assert agreement("bsp", split_hole(), 32, 32).coverage_exact
