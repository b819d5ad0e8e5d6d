# SPDX-License-Identifier: Apache-2.0
"""``python -m tests.accuracy``: see run.py."""
import sys

from .run import main

sys.exit(main())
