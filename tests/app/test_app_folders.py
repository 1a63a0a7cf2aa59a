"""A folder the Python caller gives the applet is checked like the command line's (issue 25.5)."""

from __future__ import annotations

import pytest

from evapcool.app import applet
from evapcool.game.rules import GameConfig


@pytest.mark.parametrize("name", ["data_dir", "config_dir"])
@pytest.mark.parametrize("value", ["\0", "", "scores\0x", b"a\0b", 3])
def test_a_folder_that_names_no_folder_is_refused_by_name(name: str, value: object) -> None:
    with pytest.raises(ValueError, match=rf"^{name} must name a folder \(got "):
        applet.App(GameConfig(), **{name: value})


def test_a_good_folder_is_taken(make_app, tmp_path) -> None:
    app = make_app(data_dir=tmp_path / "scores here")
    assert app.scores.table.path.parent == tmp_path / "scores here"
