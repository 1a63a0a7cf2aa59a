#!/usr/bin/env bash
# The wheel built from the sdist by another Python (the compiled core is built for it),
# on that Python: installed lean and checked
# (.ci/check_lean.py), then with the test extras, the quick suite run from the unpacked
# sdist (its own tests, conftest and helpers). `floors` pins every requirement to the
# lowest version pyproject.toml allows (.ci/floors.py): CI proves the declared floors.
# Usage: .ci/wheel_suite.sh PYTHON NAME [floors]   (after `python -m build` filled $DIST, default dist/)
set -euo pipefail
py=$1 name=$2 mode=${3:-latest}
root=$(pwd)
dist=${DIST:-$root/dist}
sdist=$(ls "$dist"/*.tar.gz)
work=$(mktemp -d "/tmp/evapcool-$name.XXXXXX")
trap 'rm -rf "$work"' EXIT
echo "== [$name] the wheel built from the sdist with $("$py" --version)"
uv build -q --wheel -p "$py" -o "$work/wheel" "$sdist"
wheel=$(ls "$work"/wheel/*.whl)
echo "   $(basename "$wheel")"
constraints=() app_constraints=()
if [ "$mode" = floors ]; then  # the caller's Python (3.11+) reads pyproject.toml
  python3 "$root/.ci/floors.py" --dependencies "$root" > "$work/floors-applet.txt"
  python3 "$root/.ci/floors.py" "$root" > "$work/floors.txt"
  app_constraints=(-c "$work/floors-applet.txt")
  constraints=(-c "$work/floors.txt")
fi
uv venv -q -p "$py" "$work/venv"
export VIRTUAL_ENV="$work/venv" PATH="$work/venv/bin:$PATH"
echo "== [$name] $(python --version), lean install of the wheel built from the sdist"
uv pip install -q "${app_constraints[@]}" "$wheel"
uv pip list 2>/dev/null | grep -iE '^(numpy|pygame-ce|platformdirs) ' | tr -s ' ' | paste -sd, -
python "$root/.ci/check_lean.py"
echo "== [$name] with the test extras ($mode versions)"
uv pip install -q "${constraints[@]}" "evapcool[test] @ file://$wheel"
uv pip list 2>/dev/null | grep -iE '^(numpy|pygame-ce|matplotlib|platformdirs|pandas|pyarrow|dask|optuna|pytest|hypothesis) ' | tr -s ' ' | paste -sd, -
tar -xzf "$sdist" -C "$work"
cd "$work"/evapcool-*/
# The tests import the installed wheel (src/ is there only for the tests that read it).
python -c 'import evapcool, sys; sys.exit("evapcool" not in evapcool.__file__ or "site-packages" not in evapcool.__file__)'
export SDL_VIDEODRIVER=dummy SDL_AUDIODRIVER=dummy PYGAME_HIDE_SUPPORT_PROMPT=1
python -m pytest -m "not slow" -p no:cacheprovider -o faulthandler_timeout=600
