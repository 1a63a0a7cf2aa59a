#!/usr/bin/env bash
# The sdist installed where no C compiler works (CC=false): the package installs without its
# compiled core, plays on the reference engine and says so in one line.
# Usage: .ci/fallback.sh PYTHON   (after `python -m build` filled $DIST, default dist/)
set -euo pipefail
py=$1
root=$(pwd)
sdist=$(ls "${DIST:-$root/dist}"/*.tar.gz)
work=$(mktemp -d /tmp/evapcool-fallback.XXXXXX)
trap 'rm -rf "$work"' EXIT
uv venv -q -p "$py" "$work/venv"
export VIRTUAL_ENV="$work/venv" PATH="$work/venv/bin:$PATH"
echo "== [fallback] $(python --version), the sdist installed with CC=false (no compiler)"
CC=false uv pip install -q --no-cache "$sdist"
python -c 'import importlib.util as u, sys; sys.exit(u.find_spec("evapcool.physics._core") is not None)'
export SDL_VIDEODRIVER=dummy SDL_AUDIODRIVER=dummy PYGAME_HIDE_SUPPORT_PROMPT=1
err=$(evapcool --frames 30 --screenshot "$work/shot.png" --data-dir "$work/d" --config-dir "$work/c" 2>&1 >/dev/null)
test -s "$work/shot.png"
echo "   stderr: $err"
[ "$(printf '%s\n' "$err" | wc -l)" = 1 ]
case "$err" in
  "evapcool: note: the compiled engine core is not installed"*) ;;
  *) echo "expected one note that the core is missing"; exit 1 ;;
esac
python -c 'from evapcool import Simulation as S; s = S.classic(seed=1); s.advance(30); assert s.engine == "reference"' 2>/dev/null
echo "== [fallback] no core: the applet plays on the reference engine and says so once"
