#!/usr/bin/env bash
# Every test, Python and web, with the Python that runs this script (the active virtual
# environment's `python`, else `python3`): the whole Python suite (slow tests too), then the
# browser edition's unit tests and its tests in headless Chromium, which drive that same
# Python (EVAPCOOL_PYTHON). Run from a clone with the dev extra installed
# (python -m pip install -e '.[dev]'); extra arguments go to pytest.
#
# A test that cannot find what it needs fails the run. Only the optional parts the README
# names may skip (the proxies nginx and caddy, and tests meant for another kind of machine:
# see tests/conftest.py, OPTIONAL_SKIPS); the last line says what was skipped, or that
# nothing was.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=$(command -v python || command -v python3 || true)
if [ -z "$PY" ] || ! "$PY" -c "import evapcool" 2>/dev/null; then
  echo "test-all: no Python with evapcool (${PY:-no python on the PATH}): activate the" \
    "environment where it is installed, or python -m pip install -e '.[dev]'" >&2
  exit 1
fi
EVAPCOOL_PYTHON=$("$PY" -c "import sys; print(sys.executable)")
SKIPPED=$(mktemp)
trap 'rm -f "$SKIPPED"' EXIT
export EVAPCOOL_PYTHON EVAPCOOL_STRICT_SKIPS=1 EVAPCOOL_SKIP_LOG="$SKIPPED"
echo "test-all: Python $EVAPCOOL_PYTHON"
# The browser edition's packages first: some Python tests drive Chromium through them
# (the teaching activities printed as PDFs by web/scripts/teach-pdf.mjs).
(cd web && npm ci --no-audit --no-fund)
"$EVAPCOOL_PYTHON" -m pytest -m "slow or not slow" "$@"
cd web
npm run build
npm test
npm run test:e2e
if [ -s "$SKIPPED" ]; then
  echo "test-all: passed; skipped, optional (README, Tests): $(sort -u "$SKIPPED" | paste -sd ';' - | sed 's/;/; /g')"
else
  echo "test-all: passed; every test ran, none skipped"
fi
