"""Atomic writes: whole files, normal permissions, corrupt files set aside."""

from __future__ import annotations

import os
import stat

import pytest

from evapcool.fileio import atomic_write_bytes, atomic_write_text, set_aside


def test_atomic_write_replaces_whole_file_with_umask_mode(tmp_path) -> None:
    target = tmp_path / "out.csv"
    atomic_write_text(target, "a\n")
    atomic_write_text(target, "b\n")
    assert target.read_text() == "b\n"
    umask = os.umask(0)
    os.umask(umask)
    assert stat.S_IMODE(target.stat().st_mode) == 0o666 & ~umask
    assert [p.name for p in tmp_path.iterdir()] == ["out.csv"]  # no temporary left behind


def test_atomic_write_keeps_an_existing_files_mode(tmp_path) -> None:
    target = tmp_path / "scores.json"
    target.write_text("{}")
    target.chmod(0o640)
    atomic_write_bytes(target, b"[]")
    assert stat.S_IMODE(target.stat().st_mode) == 0o640


def test_failed_write_leaves_old_file_and_no_temporary(tmp_path) -> None:
    target = tmp_path / "keep.txt"
    target.write_text("old")
    with pytest.raises(TypeError):
        atomic_write_bytes(target, "not bytes")  # type: ignore[arg-type]
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["keep.txt"]


def test_set_aside_renames_beside_and_never_overwrites(tmp_path) -> None:
    a = tmp_path / "s.json"
    a.write_text("x")
    first = set_aside(a)
    a.write_text("y")
    second = set_aside(a)
    assert first != second and first.read_text() == "x" and second.read_text() == "y"
    assert not a.exists() and first.name.startswith("s.json.corrupt-")
