"""scripts/test-all.sh, the README's one test command (issue 49.1): it runs every test with
the Python that runs it and hands that Python to the browser tests; a test that cannot
find what it needs fails the run, and only the optional parts the README names skip, said
in the last line. Checked on the script itself with a stand-in `npm` and a small suite of
its own (never the whole suite here)."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = ROOT / "scripts" / "test-all.sh"
E2E = ROOT / "web" / "test" / "e2e"
HERE = Path(__file__).resolve().parent

#: This module checks the repository itself (web/ beside src/): not in the sdist.
pytestmark = pytest.mark.skipif(
    not (ROOT / "web" / "package.json").exists(), reason="web/ is not in the sdist"
)

SAMPLE = """
import sys
sys.path.insert(0, {tests!r})
from strictskips import pytest_make_collect_report, pytest_runtest_makereport  # noqa: F401
"""

TESTS = """
import pytest

def test_runs():
    pass

def test_a_proxy():
    pytest.skip("nginx is not installed (Debian: apt-get install nginx)")
"""

#: npm as test-all.sh calls it; `run test:e2e` says which Python it was given, and skips
#: Caddy as classroom-proxy.test.mjs does (python.mjs's optional()).
NPM = """#!/bin/sh
if [ "$1 $2" = "run test:e2e" ]; then
  echo "e2e with $EVAPCOOL_PYTHON"
  echo "Caddy is not installed (Debian: apt-get install caddy)" >> "$EVAPCOOL_SKIP_LOG"
fi
exit 0
"""


def _suite(tmp_path: Path, tests: str) -> Path:
    suite = tmp_path / "suite"
    suite.mkdir()
    (suite / "conftest.py").write_text(SAMPLE.format(tests=str(HERE)), encoding="utf-8")
    (suite / "test_sample.py").write_text(tests, encoding="utf-8")
    return suite


def _run_script(tmp_path: Path, suite: Path) -> subprocess.CompletedProcess[str]:
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    npm = bin_dir / "npm"
    npm.write_text(NPM, encoding="utf-8")
    npm.chmod(0o755)
    path = os.pathsep.join([str(bin_dir), str(Path(sys.executable).parent), os.environ["PATH"]])
    env = {k: v for k, v in os.environ.items() if not k.startswith("EVAPCOOL_")}
    env.update(PATH=path, PYTEST_ADDOPTS="-p no:cacheprovider")
    return subprocess.run(
        ["bash", str(SCRIPT), "-q", str(suite)],
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
    )


def test_the_python_that_runs_it_runs_every_test_and_the_skips_are_said_last(tmp_path):
    done = _run_script(tmp_path, _suite(tmp_path, TESTS))
    assert done.returncode == 0, done.stdout + done.stderr
    lines = done.stdout.strip().splitlines()
    python = subprocess.run(
        [sys.executable, "-c", "import sys; print(sys.executable)"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout.strip()
    assert lines[0] == f"test-all: Python {python}"
    assert f"e2e with {python}" in lines
    assert lines[-1] == (
        "test-all: passed; skipped, optional (README, Tests): "
        "Caddy is not installed (Debian: apt-get install caddy); "
        "nginx is not installed (Debian: apt-get install nginx)"
    )


def test_a_test_lacking_what_it_needs_fails_the_run(tmp_path):
    lacking = TESTS + (
        "\ndef test_a_database():\n"
        '    pytest.skip("PostgreSQL\'s initdb and pg_ctl are not installed")\n'
    )
    done = _run_script(tmp_path, _suite(tmp_path, lacking))
    assert done.returncode != 0
    assert "test_a_database cannot run here: PostgreSQL's initdb" in done.stdout
    assert "e2e with" not in done.stdout  # stopped at the first failing part
    assert "passed;" not in done.stdout.strip().splitlines()[-1]


def test_a_module_skipped_whole_fails_the_run(tmp_path):
    suite = _suite(tmp_path, TESTS)
    (suite / "test_lacking.py").write_text(
        "import pytest\nnumpy_twin = pytest.importorskip('evapcool_no_such_module')\n"
        "def test_never():\n    pass\n",
        encoding="utf-8",
    )
    done = _run_script(tmp_path, suite)
    assert done.returncode != 0
    assert "test_lacking.py cannot run here: could not import 'evapcool_no_such_module'" in (
        done.stdout
    )


def test_outside_test_all_a_skip_stays_a_skip(tmp_path):
    lacking = TESTS + "\ndef test_a_database():\n    pytest.skip('no PostgreSQL')\n"
    env = {k: v for k, v in os.environ.items() if not k.startswith("EVAPCOOL_")}
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "pytest",
            "-q",
            "-p",
            "no:cacheprovider",
            str(_suite(tmp_path, lacking)),
        ],
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stdout
    assert "1 passed, 2 skipped" in done.stdout


def test_no_browser_test_finds_python_or_skips_on_its_own():
    """The browser tests take their Python from python.mjs (EVAPCOOL_PYTHON first) and skip
    only through its optional(), which test-all.sh reports."""
    for path in sorted(E2E.glob("*.mjs")):
        if path.name == "python.mjs":
            continue
        text = path.read_text(encoding="utf-8")
        assert ".venv" not in text and "EVAPCOOL_PYTHON" not in text, path.name
        skips = re.findall(r"\bskip: |\.skip\(", text)
        if skips:
            assert "optional(" in text, f"{path.name} skips without python.mjs's optional()"


@pytest.mark.parametrize("given", ["sys", "missing"])
def test_the_browser_tests_python_is_the_one_given(given):
    node = shutil.which("node")
    assert node, "Node is needed for the browser tests (README, Tests)"
    python = sys.executable if given == "sys" else "/nonexistent/python"
    script = (
        f"import {{ pythonWithEvapcool }} from {str(E2E / 'python.mjs')!r};"
        "console.log(pythonWithEvapcool());"
    )
    env = dict(os.environ, EVAPCOOL_PYTHON=python)
    done = subprocess.run(
        [node, "--input-type=module", "-e", script],
        env=env,
        capture_output=True,
        text=True,
        timeout=60,
    )
    if given == "sys":
        assert done.returncode == 0 and done.stdout.strip() == python, done.stderr
    else:
        assert done.returncode != 0
        assert "no Python with evapcool: /nonexistent/python (from EVAPCOOL_PYTHON)" in done.stderr
