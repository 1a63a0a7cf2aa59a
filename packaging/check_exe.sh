#!/usr/bin/env bash
# Build the stand-alone applet with PyInstaller, exactly as the README says (one file,
# dist/evapcool, dist\evapcool.exe on Windows; PyInstaller's work files in build/), and
# prove it starts and draws: run it headless for 60 frames, save a screenshot, check it.
#
#     bash packaging/check_exe.sh            # PYTHON=... to pick the interpreter
#
# Exits non-zero if the build fails, the executable fails, or the PNG is wrong.
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/.." && pwd)"
PY="${PYTHON:-python3}"
DIST="$ROOT/dist"
WORK="$ROOT/build/pyinstaller"
cd "$ROOT"

start=$(date +%s)
"$PY" -m PyInstaller --noconfirm --log-level WARN \
    --distpath "$DIST" --workpath "$WORK" packaging/evapcool.spec
build_s=$(( $(date +%s) - start ))

exe="$DIST/evapcool"
[ -x "$exe" ] || exe="$DIST/evapcool.exe"
[ -x "$exe" ] || { echo "check_exe: no executable dist/evapcool (the README's path)" >&2; exit 1; }
size_mb=$(du -m "$exe" | cut -f1)

shot="$WORK/screenshot.png"
rm -f "$shot"
start=$(date +%s)
SDL_VIDEODRIVER=dummy SDL_AUDIODRIVER=dummy timeout 180 \
    "$exe" --frames 60 --seed 1 --screenshot "$shot" 2> "$WORK/stderr.txt"
run_s=$(( $(date +%s) - start ))
# The executable carries the compiled core: no note that it plays on the reference engine.
if grep -q "compiled engine core is not installed" "$WORK/stderr.txt"; then
    echo "check_exe: the executable has no compiled core:" >&2
    cat "$WORK/stderr.txt" >&2
    exit 1
fi

# A real picture: a PNG of the window's size with the scene's many colours.
"$PY" - "$shot" <<'PYEOF'
import struct
import sys

path = sys.argv[1]
data = open(path, "rb").read()
if data[:8] != b"\x89PNG\r\n\x1a\n":
    sys.exit(f"check_exe: {path} is not a PNG")
width, height = struct.unpack(">II", data[16:24])
if (width, height) != (640, 672):
    sys.exit(f"check_exe: screenshot is {width}x{height}, expected 640x672")
if len(data) < 10_000:
    sys.exit(f"check_exe: screenshot is only {len(data)} bytes")
print(f"check_exe: screenshot {width}x{height}, {len(data)} bytes")
PYEOF

echo "check_exe: OK  dist/$(basename "$exe"): build ${build_s} s, ${size_mb} MB, 60-frame run ${run_s} s"
