"""Shared fixtures: headless SDL for every pygame test, both physics engines, and the applet.

The applet fixtures (`make_app`, `app`, `own_folders`) are never autouse: app test modules ask
for them by name or with `pytestmark = pytest.mark.usefixtures("own_folders")`. The event
helpers that go with them are in apphelp.py.
"""

from __future__ import annotations

import importlib.util
import os

import ownprocess
import pytest
from hypothesis import settings
from strictskips import (  # noqa: F401 (scripts/test-all.sh: no skip in silence)
    pytest_make_collect_report,
    pytest_runtest_makereport,
)

# A long local fuzz run (tests/test_fuzz.py): --hypothesis-profile=fuzz, cases per test
# from $EVAPCOOL_FUZZ_EXAMPLES (default 5000). CI loads Hypothesis's own 'ci' profile
# (CI=true: derandomized), under which the fuzz runs a few cases per test.
settings.register_profile(
    "fuzz", max_examples=int(os.environ.get("EVAPCOOL_FUZZ_EXAMPLES", "5000")), deadline=None
)

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")


def _fast_engine_present() -> bool:
    """The compiled core (engine 'fast') is built; CI requires it (EVAPCOOL_REQUIRE_CORE=1)."""
    if importlib.util.find_spec("evapcool.physics._core") is not None:
        return True
    assert os.environ.get("EVAPCOOL_REQUIRE_CORE") != "1", "the compiled core was not built"
    return False


ENGINES = ["reference", "fast"]


@pytest.fixture(params=ENGINES)
def engine(request: pytest.FixtureRequest) -> str:
    """Every physics test runs against both engines."""
    if request.param == "fast" and not _fast_engine_present():
        pytest.skip("the compiled core is not built in this install")
    return request.param


def _no_user_folders():
    raise AssertionError("a test reached for the real user folders")


@pytest.fixture
def own_folders(tmp_path, monkeypatch):
    """Scores and settings live in this test's folder, never in the user's."""
    from evapcool.game import highscores, settings

    monkeypatch.setenv("EVAPCOOL_DATA_DIR", str(tmp_path / "data"))
    monkeypatch.setenv("EVAPCOOL_CONFIG_DIR", str(tmp_path / "config"))
    for module in (highscores, settings):
        monkeypatch.setattr(module, "default_path", _no_user_folders)


#: The desktop the applet lays itself out for in tests (the dummy driver reports 1024 x 768).
TEST_SCREEN = (1920, 1080)


@pytest.fixture
def make_app(tmp_path):
    """make(data_dir=None, screen=TEST_SCREEN, **config): an App on
    Game(GameConfig(seed=1, **config)) on a screen of that size, with its scores in
    data_dir (default tmp_path / "data") and settings in tmp_path / "config".
    Every App made is closed after the test."""
    from evapcool.app.applet import App
    from evapcool.game.rules import Game, GameConfig

    apps = []

    def make(data_dir=None, screen=TEST_SCREEN, **config) -> App:
        a = App(
            Game(GameConfig(seed=1, **config)),
            data_dir=tmp_path / "data" if data_dir is None else data_dir,
            config_dir=tmp_path / "config",
            screen=screen,
        )
        apps.append(a)
        return a

    yield make
    for a in apps:
        a.close()


@pytest.fixture
def app(make_app):
    return make_app()


def pytest_configure(config: pytest.Config) -> None:
    ownprocess.configure(config)


@pytest.hookimpl(tryfirst=True)
def pytest_runtest_protocol(item: pytest.Item, nextitem: pytest.Item | None) -> bool | None:
    """Tests marked own_process run in a child pytest with a time limit (ownprocess.py)."""
    mark = ownprocess.wanted(item)
    if mark is None:
        return None
    ownprocess.run(item, mark)
    # The child did the item's setup and teardown; here, tear down what the next item does
    # not share (a folder's collectors), as pytest's own protocol does after a teardown.
    item.session._setupstate.teardown_exact(nextitem)
    return True


#: Modules that start servers, clusters, windows or whole command runs: part of the whole suite
#: (`-m "slow or not slow"`, scripts/test-all.sh, CI's main run) but not of the quick part that
#: CI runs again on the other Pythons (issue 16: long runs marked slow).
SLOW_MODULES = {"test_cluster.py", "test_sweep.py", "test_app_wm.py", "test_docs.py"}


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    for item in items:
        if item.path.name in SLOW_MODULES:
            item.add_marker(pytest.mark.slow)


@pytest.fixture(autouse=True)
def _english_after_each_test() -> object:
    """A test that switches the language (--lang, the settings screen) leaves English behind."""
    yield None
    from evapcool import i18n

    if i18n.active().locale != i18n.FALLBACK:
        i18n.use(i18n.FALLBACK)
