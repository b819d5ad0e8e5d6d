#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# The golden corpus is up to date: regenerating tests/cases/*.json from the
# mpmath reference (tests/golden/generate.py) would not change a single byte.
# Uses the project venv when it exists (it has mpmath from requirements.txt).
# Prints one line; exit status 0 when the corpus is current.
cd "$(dirname "$0")/../.." || exit 2
PY=${PYTHON:-.venv/bin/python}
[ -x "$PY" ] || PY=python3
if ! "$PY" -c 'import mpmath' 2>/dev/null; then
    echo "corpus regeneration check: FAILED (mpmath missing for $PY; pip install -r requirements.txt)"
    exit 1
fi
out=$("$PY" tests/golden/generate.py --check 2>&1)
rc=$?
if [ $rc -eq 0 ]; then
    echo "corpus regeneration check: ok ($(echo "$out" | tail -n 1 | sed 's/^golden corpus: OK (//; s/)$//'))"
else
    echo "$out" | sed '$d'
    echo "corpus regeneration check: FAILED ($(echo "$out" | tail -n 1))"
fi
exit $rc
