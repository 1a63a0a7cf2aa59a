"""The package as a release (issue 16): one version, the metadata, the licence and citation,
the changelog, every command in the help, and type information shipped."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from importlib import metadata
from pathlib import Path

import pytest

import evapcool
from evapcool import about
from evapcool.cli import SUBCOMMANDS, main

ROOT = Path(__file__).resolve().parents[1]


def test_one_version_everywhere(capsys):
    assert evapcool.__version__ == about.__version__
    assert metadata.version("evapcool") == about.__version__
    assert main(["--version"]) == 0
    assert capsys.readouterr().out == f"evapcool {about.__version__}\n"
    pyproject = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    assert 'dynamic = ["version"]' in pyproject
    assert 'version = { attr = "evapcool.about.__version__" }' in pyproject


def test_help_lists_every_command_and_each_has_help(capsys):
    assert main(["--help"]) == 0
    text = capsys.readouterr().out
    listed = re.findall(r"^  (\w+)  ", text.split("commands (")[1], flags=re.M)
    assert listed == list(SUBCOMMANDS)
    assert "--version" in text
    for command in SUBCOMMANDS:
        with pytest.raises(SystemExit) as stop:
            main([command, "--help"])
        assert stop.value.code == 0
        assert f"usage: evapcool {command}" in capsys.readouterr().out


def test_python_m_evapcool_is_the_same_command():
    done = subprocess.run(
        [sys.executable, "-m", "evapcool", "--version"], capture_output=True, text=True
    )
    assert done.returncode == 0 and done.stdout == f"evapcool {about.__version__}\n"


def test_metadata_licence_urls_and_extras():
    meta = metadata.metadata("evapcool")
    assert meta["License-Expression"] == "MIT"
    urls = dict(u.split(", ", 1) for u in meta.get_all("Project-URL"))
    assert urls["Homepage"] == about.HOMEPAGE
    assert urls["Source"] == about.REPOSITORY
    assert all(
        u.startswith(("https://evapcool.github.io/evapcool/", about.REPOSITORY))
        for u in urls.values()
    )
    extras = {"fast", "lab", "cluster", "all", "test", "docs", "dev"}
    assert set(meta.get_all("Provides-Extra")) >= extras
    base = [r for r in meta.get_all("Requires-Dist") if "extra ==" not in r]
    assert sorted(re.split(r"[<>=;\[ ]", r)[0] for r in base) == [
        "babel",
        "numpy",
        "platformdirs",
        "pygame-ce",
    ]
    assert "Programming Language :: Python :: 3.13" in meta.get_all("Classifier")
    assert not [c for c in meta.get_all("Classifier") if c.startswith("License ::")]


def test_type_information_is_shipped():
    assert (Path(evapcool.__file__).parent / "py.typed").is_file()


def test_citation_matches_the_package():
    text = (ROOT / "CITATION.cff").read_text(encoding="utf-8")
    assert f'repository-code: "{about.REPOSITORY}"' in text
    assert f'url: "{about.HOMEPAGE}"' in text
    assert "license: MIT" in text
    assert f'version: "{about.__version__}"' in text
    assert "MIT License" in (ROOT / "LICENSE").read_text(encoding="utf-8")


@pytest.mark.skipif(shutil.which("cffconvert") is None, reason="cffconvert is in [dev]")
def test_citation_is_valid_cff():
    done = subprocess.run(
        ["cffconvert", "--validate", "-i", str(ROOT / "CITATION.cff")],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stdout + done.stderr


def test_changelog_keeps_a_changelog():
    text = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    assert "https://keepachangelog.com/" in text
    sections = re.findall(r"^## \[([^\]]+)\]", text, flags=re.M)
    assert sections and sections[0] == "Unreleased"
    for name in sections:  # every section heading has its link
        assert re.search(rf"^\[{re.escape(name)}\]: https://", text, flags=re.M), name


def test_readme_links_work_on_pypi():
    """PyPI shows the README without the repository around it: every link is absolute."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    targets = re.findall(r"\]\(([^)\s]+)\)", readme)
    assert targets
    relative = [t for t in targets if not t.startswith("https://")]
    assert relative == []
    for t in targets:
        assert t.startswith((about.HOMEPAGE, about.REPOSITORY, _RAW)), t


_RAW = "https://raw.githubusercontent.com/evapcool/evapcool/main/"


def test_web_package_version_is_the_packages():
    package = ROOT / "web" / "package.json"
    if not package.exists():
        pytest.skip("web/ is not in the sdist")
    assert json.loads(package.read_text(encoding="utf-8"))["version"] == about.__version__
