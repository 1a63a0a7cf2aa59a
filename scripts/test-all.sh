#!/usr/bin/env bash
# Every test, Python and web: the whole Python suite (slow tests too), then the browser
# edition's unit tests and its tests in headless Chromium. Run from a clone with the dev
# extra installed (python -m pip install -e '.[dev]'); extra arguments go to pytest.
set -euo pipefail
cd "$(dirname "$0")/.."
python -m pytest -m "slow or not slow" "$@"
cd web
npm ci --no-audit --no-fund
npm run build
npm test
npm run test:e2e
