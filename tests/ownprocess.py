"""Tests marked `own_process(timeout=s)` run each in a fresh pytest child with a time limit.

A real window under Xvfb + openbox can block SDL forever inside a C call (it waits for an
X event with the GIL held, so no Python timer can interrupt it) and with it the whole
suite. Such a test runs here in a child `python -m pytest <its node id>` of its own: a
fresh SDL and display connection, none of the earlier tests' state, and a time limit.
The child's result is the test's result (its failure text, skip reason or pass). At the
limit the child's process group (the child with the Xvfb and openbox it started) is
ended and the test fails with the stack faulthandler printed in the child shortly before.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from _pytest.reports import TestReport

#: Set in the child, so the test runs there in the usual way.
CHILD = "EVAPCOOL_TEST_CHILD"
#: The child prints every thread's stack this long before its time limit.
STACK_LEAD = 20.0


def configure(config: pytest.Config) -> None:
    config.addinivalue_line(
        "markers",
        "own_process(timeout): run the test alone in a child pytest, failing after timeout s",
    )


def wanted(item: pytest.Item) -> pytest.Mark | None:
    if os.environ.get(CHILD):
        return None
    return item.get_closest_marker("own_process")


def run(item: pytest.Item, mark: pytest.Mark) -> None:
    """Run item in a child and log its setup, call and teardown reports here."""
    timeout = float(mark.kwargs.get("timeout", 120.0))
    item.ihook.pytest_runtest_logstart(nodeid=item.nodeid, location=item.location)
    outcome, longrepr, output, seconds = _child(item, timeout)
    for when in ("setup", "call", "teardown"):
        mine = when == "call" or (outcome == "skipped" and when == "setup")
        report = TestReport(
            item.nodeid,
            item.location,
            {k: 1 for k in item.keywords},
            outcome if mine else "passed",
            longrepr if mine else None,
            when,
            sections=[("Captured output of the child pytest", output)] if mine and output else [],
            duration=seconds if mine else 0.0,
        )
        item.ihook.pytest_runtest_logreport(report=report)
        if mine and outcome == "skipped":
            break
    item.ihook.pytest_runtest_logfinish(nodeid=item.nodeid, location=item.location)


def _child(item: pytest.Item, timeout: float):
    root = item.config.rootpath
    with tempfile.TemporaryDirectory(prefix="evapcool-child-") as tmp:
        xml = Path(tmp) / "result.xml"
        log = Path(tmp) / "output.txt"
        command = [sys.executable, "-m", "pytest", item.nodeid, "-q", "-p", "no:cacheprovider"]
        command += ["-o", f"faulthandler_timeout={max(1.0, timeout - STACK_LEAD)}"]
        command += [f"--junitxml={xml}", "-m", "", f"--rootdir={root}"]
        started = time.monotonic()
        with open(log, "w+b") as out:
            child = subprocess.Popen(
                command,
                cwd=root,
                env={**os.environ, CHILD: "1"},
                stdout=out,
                stderr=subprocess.STDOUT,
                start_new_session=True,  # its own process group: it and its X servers
            )
            try:
                child.wait(timeout)
                timed_out = False
            except subprocess.TimeoutExpired:
                timed_out = True
                _end_group(child)
            out.seek(0)
            output = out.read().decode(errors="replace")
        if timed_out:
            message = (
                f"timed out: no result in {timeout:g} s from the child pytest running this "
                f"test ({item.nodeid}), which was ended; its threads {STACK_LEAD:g} s before "
                "(faulthandler):"
            )
            return "failed", f"{message}\n{output}", "", timeout
        seconds = time.monotonic() - started
        return (*_result(xml, child.returncode, output, item.location), seconds)


def _end_group(child: subprocess.Popen) -> None:
    """SIGTERM the child's group (so Xvfb removes its lock file); SIGKILL what outlives 5 s."""
    try:
        os.killpg(child.pid, signal.SIGTERM)
    except ProcessLookupError:
        return
    end = time.monotonic() + 5.0
    while time.monotonic() < end:
        child.poll()  # reaps the child, which would otherwise stay in the group
        try:
            os.killpg(child.pid, 0)
        except ProcessLookupError:
            break
        time.sleep(0.1)
    else:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(child.pid, signal.SIGKILL)
    child.wait()


def _result(xml: Path, returncode: int, output: str, location: tuple):
    """(outcome, longrepr, output) from the child's JUnit XML."""
    cases = ET.parse(xml).getroot().iter("testcase") if xml.exists() else iter(())
    case = next(cases, None)
    if case is None:
        return "failed", f"the child pytest ran no test (exit {returncode}):\n{output}", output
    skipped = case.find("skipped")
    if skipped is not None:
        reason = skipped.get("message", "skipped").removeprefix("Skipped: ")
        return "skipped", (location[0], location[1] or 0, reason), output
    for tag in ("failure", "error"):
        found = case.find(tag)
        if found is not None:
            return "failed", found.text or found.get("message", tag), output
    if returncode != 0:
        return "failed", f"the child pytest exited with {returncode}:\n{output}", output
    return "passed", None, output
