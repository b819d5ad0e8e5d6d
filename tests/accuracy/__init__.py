# SPDX-License-Identifier: Apache-2.0
"""Accuracy harness of libisect: errors in ulps against an exact reference.

Modules: ``reference`` (the golden solvers of tests/golden deciding exactly),
``primitives`` (random instances), ``rays`` (the ray classes), ``surface``
(exact point-to-surface distances), ``textbook`` (plain double-precision
formulas for comparison), ``metrics`` (ulps, matching, tallies), ``harness``
(runs everything), ``contract`` (the thresholds), ``report`` and ``run``
(the table and the command line).  See README.md.
"""
