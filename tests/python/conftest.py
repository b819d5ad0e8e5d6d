# SPDX-License-Identifier: Apache-2.0
"""Shared settings of the pytest suite of the Python package ``isect``."""

from __future__ import annotations

import os
from pathlib import Path

from hypothesis import HealthCheck, settings

ROOT = Path(__file__).resolve().parents[2]

# Property tests: deterministic (derandomize) so CI runs are reproducible,
# with enough examples to be useful and a run time of seconds. Set
# HYPOTHESIS_PROFILE=thorough for a long exploratory run.
settings.register_profile(
    "ci",
    max_examples=150,
    deadline=None,
    derandomize=True,
    database=None,
    print_blob=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)
settings.register_profile(
    "thorough",
    max_examples=5000,
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))
