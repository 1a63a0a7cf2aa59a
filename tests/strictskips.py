"""Under scripts/test-all.sh (EVAPCOOL_STRICT_SKIPS=1) a skipped test fails, unless what it
lacks is an optional part the README names (its Tests section): the proxies nginx and
caddy, or a machine of another kind (another user, CPU, platform or Python). Those are
written to EVAPCOOL_SKIP_LOG, one reason a line, for the script's last line.

Outside that script a skip stays a skip, said in pytest's summary as ever.
"""

from __future__ import annotations

import os
import re

import pytest

STRICT_ENV = "EVAPCOOL_STRICT_SKIPS"
LOG_ENV = "EVAPCOOL_SKIP_LOG"

#: What may be missing, by the words of its skip reason (the README names each kind).
OPTIONAL_SKIPS = re.compile(
    "|".join(
        [
            r"\b(nginx|caddy) is not installed",  # the proxies
            r"chmod does not stop this user writing",  # root writes anywhere
            r"permissions that ignore directory modes",
            r"needs root, unshare and setpriv",  # a sandbox only root can make
            r"no fused multiply-add",  # this CPU
            r"has no -march=native",
            r"POSIX|Linux paths|on Linux",  # another platform
            r"could not import 'tomllib'",  # Python 3.10
        ]
    ),
    re.IGNORECASE,
)


def skip_reason(report: pytest.TestReport) -> str:
    """The reason a skipped report gives."""
    longrepr = report.longrepr
    if isinstance(longrepr, tuple) and len(longrepr) == 3:
        reason = str(longrepr[2])
    else:
        reason = str(longrepr)
    return reason.removeprefix("Skipped: ")


def _judge(report: pytest.TestReport | pytest.CollectReport, nodeid: str) -> None:
    """A skip under test-all: noted if optional, else turned into a failure saying why."""
    if not os.environ.get(STRICT_ENV) or not report.skipped or hasattr(report, "wasxfail"):
        return
    reason = skip_reason(report)
    if OPTIONAL_SKIPS.search(reason):
        log = os.environ.get(LOG_ENV)
        if log:
            with open(log, "a", encoding="utf-8") as f:
                f.write(f"{reason}\n")
        return
    report.outcome = "failed"
    report.longrepr = (
        f"{nodeid} cannot run here: {reason}\n"
        "scripts/test-all.sh skips only the optional parts the README names "
        "(the proxies nginx and caddy; another kind of machine): install what is missing"
    )


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo[None]) -> object:
    """A test's skip (in its setup or its call)."""
    outcome = yield
    _judge(outcome.get_result(), item.nodeid)


@pytest.hookimpl(hookwrapper=True)
def pytest_make_collect_report(collector: pytest.Collector) -> object:
    """A whole module's skip (pytest.importorskip at its top, pytestmark's skip)."""
    outcome = yield
    _judge(outcome.get_result(), collector.nodeid)
