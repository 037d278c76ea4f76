"""The README is a test: every ``robodesc ...`` command in its shell blocks runs, as written, from a
folder that holds the bundled examples, and exits 0."""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest

from robodesc.cli import main
from tests.conftest import ROOT

README = ROOT / "README.md"


def readme_commands() -> list[str]:
    """Every ``robodesc`` command in the README's ```bash blocks (continuation lines joined,
    comments dropped, the ``robodesc`` part of ``a && robodesc ...``)."""
    commands = []
    for block in re.findall(r"```bash\n(.*?)```", README.read_text(encoding="utf-8"), re.DOTALL):
        for line in block.replace("\\\n", " ").splitlines():
            for part in line.split("&&"):
                words = shlex.split(part, comments=True)
                if words and words[0] == "robodesc":
                    commands.append(shlex.join(words))
    return commands


COMMANDS = readme_commands()


def test_the_readme_has_the_commands_it_promises() -> None:
    text = " ".join(COMMANDS)
    for needle in (
        "--isaac-sim",
        "-t sdf",
        "--world",
        "-t usd",
        "--ros2",
        "four_bar.py",
        "validate",
        "inspect",
        "expand",
    ):
        assert needle in text, needle


@pytest.mark.parametrize("command", COMMANDS)
def test_readme_command_runs(
    command: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "examples").symlink_to(ROOT / "examples", target_is_directory=True)
    monkeypatch.chdir(tmp_path)
    argv = shlex.split(command)[1:]
    if argv[0] == "render":
        from robodesc.view.render import backend_candidates

        if not backend_candidates():
            pytest.skip("no offscreen OpenGL (EGL or OSMesa) on this machine: render says so and exits 2")
    try:
        code = main(argv)
    except SystemExit as exc:  # --help
        code = int(exc.code or 0)
    captured = capsys.readouterr()
    assert code == 0, captured.err
    assert "Traceback" not in captured.err
    out = [a for i, a in enumerate(argv) if i > 0 and argv[i - 1] == "-o"]
    for path in out:
        assert (tmp_path / path).exists(), path
