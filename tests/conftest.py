"""Shared fixtures: headless SDL for every pygame test, and both physics engines."""

from __future__ import annotations

import importlib.util
import os

import pytest

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")


def _fast_engine_present() -> bool:
    return importlib.util.find_spec("evapcool.physics.fast") is not None


ENGINES = ["reference", "fast"]


@pytest.fixture(params=ENGINES)
def engine(request: pytest.FixtureRequest) -> str:
    """Every physics test runs against both engines."""
    if request.param == "fast" and not _fast_engine_present():
        pytest.skip("fast engine not built yet")
    return request.param
