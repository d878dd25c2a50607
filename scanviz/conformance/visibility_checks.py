"""Conformance of the classic visibility algorithms: the z-buffer's samples, at the z-buffer's depth.

On seeded random scenes of every kind that stresses splitting
(`scanviz.visibility.examples.RANDOM_KINDS`: corners not coplanar,
near-coplanar, interpenetrating, cyclic, slivers, steep planes, integer
grids), random slanted triangles and the slides' scenes, in both sample
modes, every algorithm of `scanviz.visibility.ALGORITHMS` must

- cover exactly the samples the z-buffer covers (no hole, nothing extra);
- split without holes or double cover: the pieces of every polygon it cut
  cover exactly the polygon's samples, each once (painted one by one);
- show at each sample a polygon at most its own ``depth_slack`` farther
  than the nearest one (`Visibility.depth_slack`: the rule each algorithm
  promises, docs/visibility.md); every algorithm but the painter's foil
  must promise one (a depth sort that left a pair unresolved does not);

and its traced reference must paint what its compiled path paints.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass

import numpy as np

from ..bench.visibility import random_triangles
from ..visibility import ALGORITHMS, draw_decisions, examples, solve
from ..visibility.screen_polygons import Surfaces
from .cases import Outcome, Tally, first_difference, thousands

FOIL = "painter"  # wrong on purpose: its coverage is checked, not its depths
SCENES = 64  # random scenes in the suite (8 of each kind); --scenes changes it
TRACED = 3  # scenes per algorithm also run traced
SIZE = 32


@dataclass(frozen=True)
class Agreement:
    """One algorithm on one scene against the z-buffer: samples counted by what went wrong.

    ``holes`` the z-buffer covers and the algorithm leaves empty, ``extra``
    the reverse; ``double`` covered by two pieces of one polygon, ``missed``
    of a split polygon that none of its pieces covers; ``beyond`` shown more
    than ``depth_slack`` farther than the nearest (``worst`` the largest
    excess, 0 when none is farther); ``depth_slack`` None: no promise.
    """

    samples: int
    holes: int
    extra: int
    double: int
    missed: int
    beyond: int
    worst: float
    depth_slack: float | None

    @property
    def coverage_exact(self) -> bool:
        return not (self.holes or self.extra or self.double or self.missed)


def agreement(name: str, scene, width: int, height: int, sample: str = "corner") -> Agreement:
    """Run `name` and the z-buffer on `scene` and count every disagreement (see `Agreement`).

    >>> from scanviz.visibility.examples import split_hole
    >>> found = agreement("bsp", split_hole(), 32, 32)
    >>> found.samples, found.holes, found.double, found.beyond
    (211, 0, 0, 0)
    """
    reference = solve("zbuffer", scene, width, height, sample=sample)
    result = solve(name, scene, width, height, sample=sample)
    covered, shown = reference.polygon >= 0, result.polygon >= 0
    both = covered & shown
    excess = result.depth[both] - reference.depth[both]
    slack = result.depth_slack
    double, missed = _split_coverage(scene, width, height, sample, result.order)
    return Agreement(
        samples=int(covered.sum()),
        holes=int((covered & ~shown).sum()),
        extra=int((shown & ~covered).sum()),
        double=double,
        missed=missed,
        beyond=0 if slack is None else int((excess > slack).sum()),
        worst=float(max(excess.max(initial=0.0), 0.0)),
        depth_slack=slack,
    )


def _split_coverage(scene, width, height, sample, order) -> tuple[int, int]:
    """(samples covered twice by pieces of one polygon, samples of a cut polygon none covers)."""
    cut = sorted({piece.polygon for piece in order if piece.cuts})
    if not cut:
        return 0, 0
    surfaces = Surfaces.of(scene, width, height, sample=sample)
    whole = {piece.polygon: piece for piece in surfaces.pieces()}
    double = missed = 0
    for polygon in cut:
        counts = sum(
            draw_decisions.samples(surfaces, piece).astype(int)
            for piece in order
            if piece.polygon == polygon
        )
        original = draw_decisions.samples(surfaces, whole[polygon])
        double += int((counts > 1).sum())
        missed += int((original & (counts == 0)).sum())
    return double, missed


def scenes(rng: np.random.Generator, count: int = SCENES):
    """(label, scene, width, height, sample): the slides' scenes, then `count` random ones."""
    yield "slides_zbuffer", examples.slides_zbuffer(), 10, 9, "corner"
    yield "cyclic_overlap", examples.cyclic_overlap(), 24, 24, "center"
    yield "interpenetrating", examples.interpenetrating(), 16, 12, "corner"
    yield "slides_bsp", examples.slides_bsp(), 32, 24, "center"
    yield "split_hole", examples.split_hole(), 32, 32, "corner"
    kinds = (*examples.RANDOM_KINDS, "random_triangles")
    for k in range(count):
        kind, seed, sample = (
            kinds[k % len(kinds)],
            int(rng.integers(2**31)),
            ("corner", "center")[k % 2],
        )
        if kind == "random_triangles":
            size = int(rng.integers(8, 40))
            scene = random_triangles(int(rng.integers(2, 60)), size, size, seed)
        else:
            size, scene = SIZE, examples.random_scene(kind, seed, SIZE)
        yield f"{kind}(seed={seed})", scene, size, size, sample


def campaign(rng: np.random.Generator, count: int = SCENES, tally: Tally | None = None) -> dict:
    """Every algorithm on `scenes(rng, count)`; per algorithm, the totals of its `Agreement`s.

    Failures (any wrong coverage; a depth beyond the slack or no slack,
    except for the painter's foil; traced != compiled) go to `tally`.
    """
    tally = tally or Tally()
    totals = {name: Counter() for name in ALGORITHMS if name != "zbuffer"}
    for index, (label, scene, width, height, sample) in enumerate(scenes(rng, count)):
        for name, total in totals.items():
            found = agreement(name, scene, width, height, sample)
            total.update(
                runs=1, samples=found.samples, holes=found.holes, extra=found.extra,
                double=found.double, missed=found.missed, beyond=found.beyond,
                unpromised=int(found.depth_slack is None and name != FOIL),
            )  # fmt: skip
            total["worst"] = max(total["worst"], found.worst) if name != FOIL else 0.0
            where = f"{name} on {label} ({sample})"
            tally.check(
                found.coverage_exact,
                f"{where}: {found.holes} holes, {found.extra} extra samples, "
                f"{found.double} covered twice, {found.missed} missed by the pieces",
            )
            if name != FOIL and found.depth_slack is None:
                tally.check(False, f"{where}: no depth promise (a pair left unresolved)")
            elif name != FOIL:
                tally.check(
                    not found.beyond,
                    f"{where}: {found.beyond} samples farther than the nearest by more than "
                    f"{found.depth_slack:g} (worst {found.worst:g})",
                )
            if index < TRACED:
                _traced_equals_compiled(tally, name, scene, width, height, sample, where)
    return totals


def _traced_equals_compiled(tally, name, scene, width, height, sample, where) -> None:
    compiled = solve(name, scene, width, height, sample=sample)
    traced = solve(name, scene, width, height, sample=sample, trace=True)
    tally.same(traced.polygon, compiled.polygon, f"{where}: traced ids")
    tally.check(
        np.array_equal(traced.depth, compiled.depth)
        and np.array_equal(traced.values, compiled.values),
        f"{where}: traced depth or values differ from compiled "
        f"({first_difference(traced.depth, compiled.depth)})",
    )


def visibility_agrees(rng: np.random.Generator, count: int = SCENES) -> Outcome:
    """The category "visibility agrees with the z-buffer" (see the module)."""
    tally = Tally()
    totals = campaign(rng, count, tally)
    samples = sum(total["samples"] for total in totals.values())
    runs = sum(total["runs"] for total in totals.values())
    return tally.outcome(
        f"{thousands(samples)} samples / {thousands(runs)} runs of {len(totals)} algorithms "
        f"on {count + 5} scenes"
    )
