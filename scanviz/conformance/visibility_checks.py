"""Conformance of the classic visibility algorithms: the z-buffer's picture wherever it is unique.

Every algorithm of `scanviz.visibility.ALGORITHMS` that claims exactness
(all but the z-buffer itself and the painter's algorithm, the foil) must
show the z-buffer's polygon at every sample where the nearest covering
surface is nearer than any other by more than the bench's tolerance, on
seeded random slanted triangles (which interpenetrate now and then) and
on the slides' scenes, in both sample modes, and its traced reference must
paint what its compiled path paints.
"""

from __future__ import annotations

import numpy as np

from ..bench.visibility import TOLERANCE, random_triangles, unique_nearest
from ..visibility import ALGORITHMS, examples, solve
from .cases import Outcome, Tally, first_difference, thousands

FOILS = ("zbuffer", "painter")  # the reference, and the algorithm that is wrong on purpose
SCENES = 24
TRACED = 3  # scenes per algorithm also run traced


def _scenes(rng: np.random.Generator):
    yield "slides_zbuffer", examples.slides_zbuffer(), 10, 9, "corner"
    yield "cyclic_overlap", examples.cyclic_overlap(), 24, 24, "center"
    yield "interpenetrating", examples.interpenetrating(), 16, 12, "corner"
    for k in range(SCENES):
        count, size = int(rng.integers(2, 60)), int(rng.integers(8, 40))
        seed = int(rng.integers(2**31))
        scene = random_triangles(count, size, size + k % 3, seed)
        yield (
            f"random_triangles({count}, {size}, {size + k % 3}, seed={seed})",
            scene,
            size,
            size + k % 3,
            ("corner", "center")[k % 2],
        )


def visibility_vs_zbuffer(rng: np.random.Generator) -> Outcome:
    """Each exact visibility algorithm against the z-buffer where the nearest is unique."""
    tally, samples, runs = Tally(), 0, 0
    names = [name for name in ALGORITHMS if name not in FOILS]
    for index, (label, scene, width, height, sample) in enumerate(_scenes(rng)):
        reference = solve("zbuffer", scene, width, height, sample=sample)
        unique = unique_nearest(scene, width, height, TOLERANCE, sample=sample)
        for name in names:
            runs += 1
            result = solve(name, scene, width, height, sample=sample)
            wrong = unique & (result.polygon != reference.polygon)
            samples += int(unique.sum())
            tally.check(
                not wrong.any(),
                f"{name} on {label} ({sample}): {int(wrong.sum())} samples differ from the z-buffer "
                f"where the nearest is unique, first at (x, y) = "
                f"{tuple(np.argwhere(wrong)[0][::-1].tolist()) if wrong.any() else ()}",
            )
            if index < TRACED:
                traced = solve(name, scene, width, height, sample=sample, trace=True)
                tally.same(traced.polygon, result.polygon, f"{name} on {label}: traced ids")
                tally.check(
                    np.array_equal(traced.depth, result.depth)
                    and np.array_equal(traced.values, result.values),
                    f"{name} on {label}: traced depth or values differ from compiled "
                    f"({first_difference(traced.depth, result.depth)})",
                )
    return tally.outcome(
        f"{thousands(samples)} samples checked / {thousands(runs)} runs of {len(names)} algorithms"
    )
