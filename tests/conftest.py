"""Shared test setup: a deterministic hypothesis profile.

Property tests are derandomized (fixed seeds, DESIGN: no test depends on
luck or timing) and have no deadline. ``SCANVIZ_MAX_EXAMPLES=N`` scales every
property test: tests ask for multiples of ``settings.default.max_examples``.
"""

import os

from hypothesis import settings

settings.register_profile(
    "scanviz",
    derandomize=True,
    deadline=None,
    max_examples=int(os.environ.get("SCANVIZ_MAX_EXAMPLES", "100")),
)
settings.load_profile("scanviz")
