"""Names in any script render as typed: per-character fallback over the system's fonts."""

from __future__ import annotations

import numpy as np
import pygame
import pytest
from apphelp import frames, pixels

from evapcool.app.input import Mode
from evapcool.view import fonts
from evapcool.view.fonts import text_image
from evapcool.view.scene import PLAY_RECT, UNDER_MESSAGE

pytestmark = pytest.mark.usefixtures("own_folders")

#: A class list: Chinese, Japanese, Korean, Arabic, Greek, Cyrillic, accents, emoji.
NAMES = ["王小明", "さくら", "김민준", "علي", "Ελένη", "Иван", "Zoë", "😀 Ana"]
#: Unassigned in Unicode: every font draws its empty box (.notdef) for it.
NO_GLYPH = "\u0378"


@pytest.fixture(autouse=True)
def _fonts():
    pygame.font.init()
    if fonts.missing("".join(NAMES)):
        pytest.skip(
            "this system lacks fonts for "
            + " ".join(fonts.missing("".join(NAMES)))
            + " (install fonts-noto-cjk and fonts-dejavu-core)"
        )


def _array(surface: pygame.Surface) -> np.ndarray:
    flat = pygame.Surface(surface.get_size())
    flat.fill((255, 255, 255))
    flat.blit(surface, (0, 0))
    return pygame.surfarray.array3d(flat)


def _box(face_index: int, size: int) -> np.ndarray:
    """The empty box this font draws for a character it does not have."""
    face = fonts.faces()[face_index]
    f = fonts._sdl_font(face.path, size, False, None)
    return _array(f.render(NO_GLYPH, True, (0, 0, 0)))


@pytest.mark.parametrize("name", NAMES)
def test_every_character_comes_from_a_font_that_has_it(name):
    for face_index, _, run in fonts.runs(name):
        face = fonts.faces()[face_index]
        for ch in run:
            if not ch.isspace():
                assert face.has(ch), (name, ch, face.path)


@pytest.mark.parametrize("name", NAMES)
def test_no_character_renders_as_the_empty_box(name):
    chain = fonts.faces()
    for ch in name:
        if ch.isspace():
            continue
        (k, _, _), *_ = fonts.runs(ch)
        glyph = _array(text_image(ch, 32, (0, 0, 0)))
        box = _box(k, 32)
        assert glyph.shape != box.shape or (glyph != box).any(), (ch, chain[k].path)
        assert (glyph < 128).any(), ch  # and it is not blank either


def test_the_bundled_font_alone_would_draw_boxes():
    """The check above can fail: without the fallback these names are boxes."""
    primary = fonts.faces()[0]
    assert not primary.has("明") and not primary.has("ع")
    box = _box(0, 32)
    plain = _array(fonts.font(32).render("明", True, (0, 0, 0)))
    assert plain.shape == box.shape and (plain == box).all()


def test_arabic_is_shaped_right_to_left():
    [(k, script, run)] = fonts.runs("علي")
    assert script == "Arab" and run == "علي"
    face = fonts.faces()[k]
    unshaped = pygame.font.Font(face.path, 40).render("علي", True, (0, 0, 0))
    shaped = text_image("علي", 40, (0, 0, 0))
    assert (
        _array(shaped).shape != _array(unshaped).shape or (_array(shaped) != _array(unshaped)).any()
    )
    # A right-to-left paragraph puts a following number on the left of the word.
    assert [r[2] for r in fonts.runs("علي 12")] == ["علي", " ", "12"]
    assert fonts._rtl_paragraph("علي 12") and not fonts._rtl_paragraph("Ali علي")


def test_a_name_in_several_scripts_shows_as_typed_in_the_name_box(app):
    app.game.paused = False
    frames(app, 2)
    app.game.sim.force_win()
    frames(app)
    assert app.input.mode is Mode.NAME
    name = "明 さ 민 ع Ж😀"
    for ch in name:
        pygame.event.post(pygame.event.Event(pygame.TEXTINPUT, text=ch))
    app.scores.name_box.update(0.6)  # cursor blinked off, so the field shows only the name
    frames(app)
    assert app.scores.name_box.text == name
    # The field shows exactly the name as the fallback renders it, on white.
    field = pygame.Rect(PLAY_RECT.left + 50, UNDER_MESSAGE + 40, PLAY_RECT.width - 100, 44)
    image = text_image(name, 32, (20, 20, 20))
    where = image.get_rect(midleft=(field.x + 7, field.centery))
    shown = pixels(app)[where.left : where.right, where.top : where.bottom]
    np.testing.assert_array_equal(shown, _array_on(image, (255, 255, 255)))


def _array_on(image: pygame.Surface, background) -> np.ndarray:
    flat = pygame.Surface(image.get_size())
    flat.fill(background)
    flat.blit(image, (0, 0))
    return pygame.surfarray.array3d(flat).astype(int)


@pytest.mark.parametrize(
    ("text", "rtl", "expected"),
    [
        # Arabic with a bracket and Latin inside, right to left: the closing bracket at the
        # left end, then the Latin run, then the Arabic run holding the opening bracket.
        ("أسرع (حتى 4x)", True, [(True, ")"), (False, "4x"), (True, "أسرع (حتى ")]),
        # A key cap first in an Arabic line: the colon and space join the Arabic run (they
        # stand between two directions), so the line reads "مساعدة :H" as a browser shows it.
        ("H: مساعدة", True, [(True, ": مساعدة"), (False, "H")]),
        # An Arabic name in an English line: one run, its words in their order.
        ("Winner: علي حسن!", False, [(False, "Winner: "), (True, "علي حسن"), (False, "!")]),
        ("Score 12", False, [(False, "Score 12")]),
    ],
)
def test_bidi_runs_in_visual_order(text, rtl, expected):
    assert fonts.bidi_runs(text, rtl) == expected


def _middle_leans_right(ink: np.ndarray) -> bool:
    """A ")" bulges right at mid-height of its ends; a "(" left. ink[x, y] booleans."""
    xs, ys = np.nonzero(ink)
    top, bottom = ys.min(), ys.max()
    third = (bottom - top) / 3
    middle = xs[(ys > top + third) & (ys < bottom - third)].mean()
    ends = xs[(ys <= top + third / 2) | (ys >= bottom - third / 2)].mean()
    return bool(middle > ends)


def test_a_bracket_in_a_right_to_left_run_is_mirrored():
    # "(" then an Arabic letter, right to left: the bracket stands at the right end, drawn
    # as ")" (HarfBuzz mirrors it), as a browser draws it.
    assert _middle_leans_right((_array(text_image(")", 32, (0, 0, 0))) < 128).any(axis=2))
    assert not _middle_leans_right((_array(text_image("(", 32, (0, 0, 0))) < 128).any(axis=2))
    image = _array(fonts._shaped("(ب", 32, (0, 0, 0), False, True)[0]) < 128
    bracket = image[-text_image(")", 32, (0, 0, 0)).get_width() :]
    assert _middle_leans_right(bracket.any(axis=2))
