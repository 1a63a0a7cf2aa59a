"""TextInput: typing, editing, submit, cancel, limits and blink, driven by synthetic events."""

from __future__ import annotations

import pygame
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from evapcool.view.pen import Pen
from evapcool.view.text_input import CANCEL, CHANGE, SUBMIT, TextInput


@pytest.fixture(scope="module", autouse=True)
def _pygame() -> None:
    pygame.init()
    yield
    pygame.quit()


def _text(s: str) -> pygame.event.Event:
    return pygame.event.Event(pygame.TEXTINPUT, text=s)


def _key(key: int, mod: int = 0) -> pygame.event.Event:
    return pygame.event.Event(pygame.KEYDOWN, key=key, mod=mod, unicode="")


def test_typing_and_submitting_a_name() -> None:
    box = TextInput(max_length=12)
    for ch in "Ada L":
        assert box.handle_event(_text(ch)) == CHANGE
    assert box.text == "Ada L"
    assert box.handle_event(_key(pygame.K_BACKSPACE)) == CHANGE
    assert box.handle_event(_key(pygame.K_BACKSPACE)) == CHANGE
    assert box.text == "Ada"
    assert box.handle_event(_key(pygame.K_RETURN)) == SUBMIT
    assert box.value == "Ada" and not box.active
    # Finished: further events are not used.
    assert box.handle_event(_text("x")) is None
    assert box.text == "Ada"


def test_keypad_enter_submits_and_escape_cancels() -> None:
    box = TextInput(text="Bo")
    assert box.handle_event(_key(pygame.K_KP_ENTER)) == SUBMIT and box.value == "Bo"
    box.reset("Cy")
    assert box.active and box.value is None and box.text == "Cy"
    assert box.handle_event(_key(pygame.K_ESCAPE)) == CANCEL
    assert box.value is None and not box.active


def test_max_length_and_filtering() -> None:
    box = TextInput(max_length=5)
    assert box.handle_event(_text("Marie Curie")) == CHANGE  # a pasted chunk is cut
    assert box.text == "Marie"
    assert box.handle_event(_text("!")) is None
    box.reset()
    assert box.handle_event(_text("a\tb\x1bç")) == CHANGE
    assert box.text == "abç"
    assert box.handle_event(_text("\n")) is None


def test_backspace_on_empty_and_ctrl_backspace_clears() -> None:
    box = TextInput()
    assert box.handle_event(_key(pygame.K_BACKSPACE)) is None
    box.handle_event(_text("Noether"))
    assert box.handle_event(_key(pygame.K_BACKSPACE, pygame.KMOD_LCTRL)) == CHANGE
    assert box.text == ""


def test_unrelated_events_are_ignored() -> None:
    box = TextInput()
    assert (
        box.handle_event(pygame.event.Event(pygame.MOUSEBUTTONDOWN, button=1, pos=(0, 0))) is None
    )
    assert box.handle_event(_key(pygame.K_LEFT)) is None
    assert box.text == "" and box.active


def test_cursor_blinks_with_the_time_given() -> None:
    box = TextInput(blink_period=1.0)
    assert box.cursor_visible
    box.update(0.6)
    assert not box.cursor_visible
    box.update(0.5)
    assert box.cursor_visible
    box.update(0.6)
    assert not box.cursor_visible
    box.handle_event(_text("a"))  # typing shows the cursor at once
    assert box.cursor_visible
    box.handle_event(_key(pygame.K_RETURN))
    assert not box.cursor_visible


def test_draw_shows_text_and_cursor_inside_the_box() -> None:
    surf = pygame.Surface((400, 100))
    surf.fill((0, 0, 0))
    box = TextInput(prompt="Name: ", text="Lise")
    rect = pygame.Rect(20, 20, 300, 50)
    pen = Pen(surf)
    cursor = box.draw(pen, rect)
    assert rect.contains(cursor)
    assert tuple(surf.get_at(cursor.center))[:3] == (20, 20, 20)  # the cursor is drawn
    assert tuple(surf.get_at((5, 5)))[:3] == (0, 0, 0)  # nothing outside the box
    box.update(0.6)
    surf.fill((0, 0, 0))
    cursor = box.draw(pen, rect)
    assert tuple(surf.get_at(cursor.center))[:3] == (255, 255, 255)  # blinked off
    long_box = TextInput(max_length=200, text="W" * 200)
    cur = long_box.draw(pen, rect)  # text wider than the box keeps its end in view
    assert rect.left < cur.x < rect.right


def test_draw_at_twice_the_size_doubles_the_box() -> None:
    surf = pygame.Surface((800, 200))
    box = TextInput(text="Lise")
    rect = pygame.Rect(20, 20, 300, 50)
    cursor = box.draw(Pen(surf, 2.0), rect)
    assert pygame.Rect(40, 40, 600, 100).contains(cursor) and cursor.h > 50
    assert tuple(surf.get_at((41, 41)))[:3] == (20, 20, 20)  # the frame, 2 px wide
    assert tuple(surf.get_at((42, 42)))[:3] == (20, 20, 20)
    assert tuple(surf.get_at((45, 45)))[:3] == (255, 255, 255)


def test_bad_max_length() -> None:
    with pytest.raises(ValueError):
        TextInput(max_length=0)


_events = st.lists(
    st.one_of(
        st.text(max_size=8).map(_text),
        st.sampled_from([pygame.K_BACKSPACE, pygame.K_LEFT, pygame.K_a]).map(_key),
    ),
    max_size=40,
)


@settings(max_examples=100, deadline=None)
@given(_events, st.integers(min_value=1, max_value=20))
def test_text_stays_printable_and_within_the_limit(events: list, limit: int) -> None:
    box = TextInput(max_length=limit)
    for ev in events:
        box.handle_event(ev)
        assert len(box.text) <= limit
        assert box.text.isprintable()
    assert box.active
    assert box.handle_event(_key(pygame.K_RETURN)) == SUBMIT
    assert box.value == box.text
