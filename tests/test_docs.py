"""Every code block of README.md and docs/*.md runs, as written, in a scratch folder.

Fenced blocks are tagged: ```python and ```sh blocks run (Python as a script, each shell
command on its own, headless: SDL's dummy driver, scores and settings in the scratch
folder; a command that would open the applet's window gets `--frames 5` so it plays five
frames and exits). Blocks that must not run here say so in their tag: ```text for output
and listings, and `not-run` after the language (```sh not-run) for commands that install
the package, run this very suite or build the executable (CI runs packaging/check_exe.sh
for that one). An untagged block fails this test: nothing is skipped silently.

A ```text output block right after a block that runs is what that block's last command
prints: its lines must come, in a row, in what the command wrote (stdout or stderr), so a
worked example's numbers that drift fail here. Commands run in the scratch folder, so an
example writes nothing over the repository's files.
"""

from __future__ import annotations

import itertools
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
RUN = {"python", "sh"}
FENCE = re.compile(r"^```(.*)$")
#: Frames a window-opening command plays in this test.
FRAMES = "5"


def blocks(path: Path) -> list[tuple[int, str, str]]:
    """(line number, info string, code) of every fenced block in a Markdown file."""
    out, info, start, lines = [], None, 0, []
    for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        m = FENCE.match(line.strip())
        if m and info is None:
            info, start, lines = m.group(1).strip(), n, []
        elif m and info is not None:
            out.append((start, info, "\n".join(lines)))
            info = None
        elif info is not None:
            lines.append(line)
    assert info is None, f"{path.name}: a block opened at line {start} is never closed"
    return out


ALL = [(p, n, info, code) for p in DOCS for n, info, code in blocks(p)]
#: The printed output a block's last command must give: (file, line) -> the text block after.
OUTPUT = {
    (a[0], a[1]): b[3]
    for a, b in itertools.pairwise(ALL)
    if a[0] == b[0] and b[2].split() == ["text", "output"]
}


def _id(block) -> str:
    path, n, info, _ = block
    return f"{path.relative_to(ROOT)}:{n}:{info.split()[0] if info else 'untagged'}"


def _runs(info: str) -> bool:
    words = info.split()
    return bool(words) and words[0] in RUN and "not-run" not in words[1:]


def test_every_block_is_tagged():
    for block in ALL:
        info = block[2]
        words = info.split()
        assert words, f"{_id(block)}: tag it (python, sh, text, or sh not-run)"
        assert words[0] in (*RUN, "text"), f"{_id(block)}: unknown language {words[0]!r}"
        if "not-run" in words:
            assert words[0] in RUN, f"{_id(block)}: only code is marked not-run"
    for before, block in itertools.pairwise(ALL):
        if block[2].split() == ["text", "output"]:
            assert before[0] == block[0] and _runs(before[2]), (
                f"{_id(block)}: an output block follows a block that runs"
            )


def commands(code: str) -> list[list[str]]:
    """The shell block's commands (continuation lines joined), as argument lists."""
    out = []
    for line in code.replace("\\\n", " ").splitlines():
        argv = shlex.split(line, comments=True)
        if argv:
            out.append(argv)
    return out


def headless(argv: list[str]) -> list[str]:
    """The command, with `--frames 5` if it would open the applet's window."""
    if argv[:3] == ["python", "-m", "evapcool"]:
        rest = argv[3:]
    elif argv[0] == "evapcool":
        rest = argv[1:]
    else:
        return argv
    opens = rest[:1] == ["open"]  # `evapcool open LINK` plays the link in the window
    if (
        (rest and not rest[0].startswith("-") and not opens)
        or "--frames" in rest
        or "--help" in rest
    ):
        return argv  # a subcommand (lab, bench, web...), or a run that ends by itself
    return [*argv, "--frames", FRAMES]


def test_window_commands_get_a_short_headless_run():
    assert headless(["evapcool"]) == ["evapcool", "--frames", "5"]
    assert headless(["python", "-m", "evapcool", "--speed", "2"])[-2:] == ["--frames", "5"]
    assert headless(["evapcool", "--frames", "300", "--screenshot", "a.png"])[-1] == "a.png"
    assert headless(["evapcool", "lab", "--frames", "10"]) == ["evapcool", "lab", "--frames", "10"]
    assert headless(["evapcool", "web", "--print-path"]) == ["evapcool", "web", "--print-path"]


@pytest.fixture
def scratch(tmp_path) -> tuple[Path, dict[str, str]]:
    """A scratch folder with docs/ (where examples put figures), and the env."""
    (tmp_path / "docs").mkdir()
    env = dict(os.environ)
    env.update(
        SDL_VIDEODRIVER="dummy",
        SDL_AUDIODRIVER="dummy",
        PYGAME_HIDE_SUPPORT_PROMPT="1",
        EVAPCOOL_DATA_DIR=str(tmp_path / "data"),
        EVAPCOOL_CONFIG_DIR=str(tmp_path / "config"),
        MPLBACKEND="Agg",
        PATH=f"{Path(sys.executable).parent}{os.pathsep}{env.get('PATH', '')}",
    )
    return tmp_path, env


@pytest.mark.parametrize("block", [b for b in ALL if _runs(b[2])], ids=_id)
def test_block_runs(block, scratch):
    _, _, info, code = block
    folder, env = scratch
    if info.split()[0] == "python":
        script = folder / "block.py"
        script.write_text(code + "\n", encoding="utf-8")
        runs = [[sys.executable, str(script)]]
    else:
        runs = [headless(argv) for argv in commands(code)]
        assert runs, f"{_id(block)}: an empty block"
    for argv in runs:
        proc = subprocess.run(
            argv, cwd=folder, env=env, capture_output=True, text=True, timeout=600
        )
        assert proc.returncode == 0, f"{shlex.join(argv)}\n{proc.stdout}\n{proc.stderr}"
    expected = OUTPUT.get((block[0], block[1]))
    if expected is not None:
        said = printed(expected, proc.stdout, proc.stderr)
        assert said, (
            f"{_id(block)}: the docs say it prints\n{expected}\n"
            f"it printed\n{proc.stdout}{proc.stderr}"
        )


def printed(expected: str, *outputs: str) -> bool:
    """The expected lines come, in a row, in one of the outputs (trailing spaces aside)."""
    want = [line.rstrip() for line in expected.strip().splitlines()]
    for out in outputs:
        lines = [line.rstrip() for line in out.splitlines()]
        if any(lines[k : k + len(want)] == want for k in range(len(lines) - len(want) + 1)):
            return True
    return False


def test_the_executable_is_where_the_readme_says():
    """packaging/check_exe.sh (CI) builds the README's dist/evapcool and checks it there."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    script = (ROOT / "packaging" / "check_exe.sh").read_text(encoding="utf-8")
    assert "`dist/evapcool`" in readme and "`dist\\evapcool.exe`" in readme
    assert 'DIST="$ROOT/dist"' in script and 'exe="$DIST/evapcool"' in script
    spec = (ROOT / "packaging" / "evapcool.spec").read_text(encoding="utf-8")
    assert 'name="evapcool"' in spec
    build = next(c for p, _, i, c in ALL if p.name == "README.md" and "PyInstaller" in c)
    assert "packaging/evapcool.spec" in build and "--distpath" not in build  # the default: dist/


def test_the_screenshot_script_makes_the_readmes_pictures(tmp_path):
    """docs/make_screenshots.py regenerates every picture the README shows."""
    env = dict(os.environ, SDL_VIDEODRIVER="dummy", PYGAME_HIDE_SUPPORT_PROMPT="1")
    proc = subprocess.run(
        [sys.executable, str(ROOT / "docs" / "make_screenshots.py"), str(tmp_path)],
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert proc.returncode == 0, proc.stderr
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    # Absolute addresses, so that the pictures show on PyPI too.
    raw = "https://raw.githubusercontent.com/evapcool/evapcool/main/docs/"
    shown = re.findall(r"!\[[^\]]*\]\(" + re.escape(raw) + r"([^)]+\.png)\)", readme)
    made = {p.name for p in tmp_path.glob("*.png")}
    assert made == {"classic-start.png", "win.png", "small-screen.png"}
    assert made <= set(shown)  # (the browser edition's picture comes from web/)
    for name in shown:
        assert (ROOT / "docs" / name).exists()


# -- docs/teach.md (issue 48) ---------------------------------------------------------------------
TEACH = ROOT / "docs" / "teach.md"


def _teach_table():
    import importlib.util

    spec = importlib.util.spec_from_file_location(
        "teach_table", ROOT / "scripts" / "teach_table.py"
    )
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_teach_table_is_the_option_lists():
    """The link options' table is made from web/src/link-options.json: a new option, value or
    word there fails here until `python scripts/teach_table.py --write` is run."""
    tt = _teach_table()
    made = tt.table()
    assert tt.page_table(TEACH.read_text(encoding="utf-8")) == made
    options = __import__("json").loads(tt.OPTIONS.read_text("utf-8"))["options"]
    for option in options:  # every option and every value it allows is in the table
        row = next(r for r in made.splitlines() if r.startswith(f"| `{option['name']}` |"))
        assert all(f"`{v}`" in row for v in option.get("values", []))


def test_teach_table_notices_a_changed_option(tmp_path, monkeypatch):
    tt = _teach_table()
    changed = __import__("json").loads(tt.OPTIONS.read_text("utf-8"))
    changed["options"][0]["high"] = 12
    fake = tmp_path / "link-options.json"
    fake.write_text(__import__("json").dumps(changed), "utf-8")
    monkeypatch.setattr(tt, "OPTIONS", fake)
    assert tt.table() != tt.page_table(TEACH.read_text(encoding="utf-8"))


def test_teach_is_in_the_sites_menu():
    assert "teach.md" in (ROOT / "mkdocs.yml").read_text(encoding="utf-8")


def _lab(**params):
    from evapcool.lab import run_experiment

    return run_experiment(n_atoms=49, seed=3, **params)


def test_teach_answer_key_numbers_are_the_labs():
    """Every number of the three answer keys, from the lab commands the page gives."""
    text = " ".join(TEACH.read_text(encoding="utf-8").split())
    cool = _lab(escape="knife", schedule="300@0", win=False, frames=900, every=300)
    n = [int(v) for v in cool.n_trapped]
    t = [f"{v:.1f}" for v in cool.temperature]
    tc = [f"{v:.1f}" for v in cool.critical_temperature]
    per_atom = cool.evaporated_energy[-1] / cool.evaporated[-1]
    expected = [
        f"{int(cool.spilled[-1])} of the 49 leave at the first frame, {n[0]} stay",
        f"{n[0]} at the start, {n[1]} after 10 s, {n[2]} after 20 s, {n[3]} after 30 s",
        f"T falls from {t[0]} to {t[1]} after 10 s and {t[2]} after 20 s",
        f"took {per_atom:.1f} each on average",
        f"from {tc[0]} to {tc[3]}",
        f"({t[2]} against {tc[2]})",
    ]
    for name, schedule in (("fast", "400@0,60@150"), ("slow", "400@0,60@1500")):
        r = _lab(schedule=schedule, frames=1800, every=30)
        won = r.metadata["won_frame"]
        expected.append(
            f"condenses at frame {won} ({won / 30:.1f} s) with {int(r.n_trapped[-1])} atoms"
            if name == "fast"
            else f"at frame {won} ({won / 30:.1f} s) with {int(r.n_trapped[-1])} atoms"
        )
    for escape in ("knife", "rim"):
        r = _lab(escape=escape, schedule="400@0,60@900", frames=1800, every=30)
        won = r.metadata["won_frame"]
        expected.append(f"at frame {won} ({won / 30:.1f} s) with {int(r.n_trapped[-1])} atoms")
    missing = [phrase for phrase in expected if phrase not in text]
    assert missing == []


def test_teach_commands_are_the_answer_keys_runs():
    """The page's lab commands are the runs the answer keys were computed from."""
    text = TEACH.read_text(encoding="utf-8")
    for command in (
        "--escape knife --schedule 300@0 --no-win --frames 900 --every 300",
        "--schedule 400@0,60@150 --frames 1800",
        "--schedule 400@0,60@1500 --frames 1800",
        "--escape rim --schedule 400@0,60@900 --frames 1800",
        "--escape knife --schedule 400@0,60@900 --frames 1800",
    ):
        assert f"evapcool lab --atoms 49 --seed 3 {command}" in text


def test_teach_activities_print_as_pdfs_in_chromium(tmp_path):
    """Each activity of docs/teach.md printed alone by headless Chromium (web/scripts/
    teach-pdf.mjs, as CI does on the built site), with the docs' print style."""
    import json
    import shutil

    import markdown

    node, chromium = shutil.which("node"), Path("/usr/bin/chromium")
    assert node and chromium.exists(), "node and Debian's chromium are needed (web/README)"
    body = markdown.markdown(TEACH.read_text(encoding="utf-8"), extensions=["tables"])
    css = (ROOT / "docs" / "stylesheets" / "print.css").read_text(encoding="utf-8")
    page = tmp_path / "teach.html"
    page.write_text(
        f'<!doctype html><meta charset="utf-8"><style>{css}</style>'
        f'<article class="md-content__inner md-typeset">{body}</article>',
        encoding="utf-8",
    )
    proc = subprocess.run(
        [node, str(ROOT / "web" / "scripts" / "teach-pdf.mjs"), str(page), str(tmp_path)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert proc.returncode == 0, proc.stderr
    made = json.loads((tmp_path / "activities.json").read_text(encoding="utf-8"))
    titles = [m["title"] for m in made]
    assert titles == [
        "1. Why evaporation cools",
        "2. Fast or slow ramp",
        "3. The knife against the rim",
    ]
    for k, m in enumerate(made):
        pdf = (tmp_path / m["file"]).read_bytes()
        assert pdf.startswith(b"%PDF-") and b"/Type /Page" in pdf
        text = m["text"]  # what was on the page as it printed: this activity alone
        assert text.startswith(m["title"]) and "Answer key." in text and "Setup link." in text
        others = [t for j, t in enumerate(titles) if j != k]
        assert not any(t in text for t in others)
        assert "What the model is" not in text


def test_the_lab_worked_examples_words_are_its_run():
    """docs/lab.md's words on the worked example (the printed line is compared above): the
    knife's span, the slope of the path, the atoms lost, the frame and m g H at the win."""
    from evapcool.lab import run_experiment

    text = " ".join((ROOT / "docs" / "lab.md").read_text(encoding="utf-8").split())
    r = run_experiment(
        n_atoms=120, radius=6.0, escape="knife", schedule="450@0,100@2400", frames=2400,
        every=30, seed=1,
    )  # fmt: skip
    mg = float(r.parameters["gravity"])  # m = 1
    slope = np.polyfit(np.log(r.n_trapped.astype(float)), np.log(r.temperature), 1)[0]
    won = r.metadata["won_frame"]
    said = (
        f"from m g H = {450 * mg:.0f} to {100 * mg:.0f} over {2400 / 30:.0f} s",
        f"T ~ N^{slope:.1f} here",
        f"the two meet after {120 - r.n_trapped[-1]} atoms are lost, at frame {won} "
        f"(m g H = {mg * r.trap_height[-1]:.0f} by then)",
    )
    assert r.frame[-1] == won  # the run stops at the win: its last record
    for words in said:
        assert words in text, words
