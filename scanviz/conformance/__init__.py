"""The conformance suite and the fuzz campaign: ``python -m scanviz conformance [--fuzz N]``.

`main` runs every category of `scanviz.conformance.suite` (one PASS/FAIL line
each), then, with ``fuzz > 0``, N hostile and random inputs spread over the
public entry points (`scanviz.conformance.fuzz`, needs hypothesis). See
``docs/conformance.md``.
"""

from __future__ import annotations

from .suite import CATEGORIES, Outcome, run_category, run_suite
from .visibility_checks import SCENES


def main(fuzz: int = 0, seed: int = 0, scenes: int | None = None) -> int:
    """Run the suite, then `fuzz` fuzz inputs; return 0 only when everything passes.

    Parameters
    ----------
    fuzz : int
        How many fuzz inputs to try after the suite (0: none).
    seed : int
        Seed of the suite's generators and of hypothesis.
    scenes : int or None
        Random scenes of the category "visibility agrees with the z-buffer"
        (None: `SCENES`).

    Returns
    -------
    int
        Exit status: 0 when every category passes and no fuzz input gave
        "anything else", 1 otherwise.
    """
    passed = run_suite(seed, scenes=SCENES if scenes is None else scenes)
    if fuzz > 0:
        try:
            from .fuzz import run_campaign
        except ImportError as error:
            print(f"fuzz: cannot run {fuzz} inputs: {error} (pip install hypothesis)")
            return 1
        passed = run_campaign(fuzz, seed) and passed
    return 0 if passed else 1


__all__ = ["CATEGORIES", "Outcome", "main", "run_category", "run_suite"]
