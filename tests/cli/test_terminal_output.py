"""The one escaping rule: whatever a user wrote reaches the terminal as written and only as text — rich markup
is not read, emoji codes are not replaced, control characters and lone surrogates are shown as escapes."""

from __future__ import annotations

import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.render.terminal import printable

CliRunner = Callable[[list[str]], tuple[int, str, str]]

MARKUP_TASK = """name: "x[/]y"
actions:
  - {id: "close[/]", text: "a [bold]bold[/bold] claim :poop:"}
  - {id: ":poop:"}
  - "[red]"
demonstrations:
  - steps: ["close[/]", ":poop:", "[red]"]
  - steps: [":poop:", "close[/]", "[red]"]
"""


def test_markup_and_emoji_codes_in_ids_are_printed_as_written(tmp_path: Path, cli: CliRunner) -> None:
    path = tmp_path / "markup.yaml"
    path.write_text(MARKUP_TASK)
    code, out, err = cli(["learn", str(path)])
    assert code == 0, err
    assert "x[/]y" in out and "close[/] — a [bold]bold[/bold] claim :poop:" in out
    assert "├── :poop:" in out or "└── :poop:" in out or ":poop:" in out.split("close[/]")[0]
    assert "💩" not in out and "[red]" in out


def test_error_lines_show_control_characters_markup_and_emoji_codes_as_text(tmp_path: Path, cli: CliRunner) -> None:
    path = tmp_path / "bad\x1b[2J[bold]:poop:.yaml"
    path.write_text("name: t\ncolour: red\n")
    code, out, err = cli(["learn", str(path)])
    assert code == 2 and out == ""
    assert "\x1b" not in err and "\\x1b[2J[bold]:poop:.yaml:2: unknown key 'colour'" in err
    assert "💩" not in err and len(err.strip().splitlines()) == 1


def test_a_lone_surrogate_in_a_file_name_is_printed_under_a_strict_utf8_locale(tmp_path: Path) -> None:
    """A file name of bytes that are not UTF-8 (Python holds them as lone surrogates) is shown as \\xff."""
    name = tmp_path.as_posix().encode() + b"/caf\xff.yaml"
    result = subprocess.run(
        [sys.executable, "-m", "supportive.cli", "learn", name],
        capture_output=True,
        env={"PYTHONIOENCODING": "utf-8:strict", "LC_ALL": "C.UTF-8", "PATH": "/usr/bin:/bin"},
        check=False,
    )
    assert result.returncode == 2, result.stderr
    assert result.stderr.decode("utf-8") == f"supportive: error: {tmp_path}/caf\\xff.yaml: no such file\n"


def test_teach_and_chat_echo_what_was_typed_as_text(
    tmp_path: Path, cli: CliRunner, monkeypatch: pytest.MonkeyPatch
) -> None:
    path = tmp_path / "t.yaml"
    path.write_text("name: t\nactions: [a, b]\n")
    typed = iter(["[/]\x1b[2J:poop:", "quit"])
    monkeypatch.setattr("builtins.input", lambda prompt="": next(typed))
    code, out, err = cli(["teach", str(path)])
    assert code == 0, err
    assert "unknown action '[/]\\x1b[2J:poop:'" in out and "\x1b" not in out and "💩" not in out


@given(st.text(max_size=40))
def test_printable_leaves_no_character_that_acts_on_a_terminal(text: str) -> None:
    shown = printable(text)
    assert not any((ord(c) < 32 and c not in "\n\t") or 0x7F <= ord(c) <= 0x9F for c in shown)
    assert not any(0xD800 <= ord(c) <= 0xDFFF or 0x202A <= ord(c) <= 0x202E for c in shown)
    shown.encode("utf-8")  # a strict UTF-8 terminal can take it
    if all(c.isprintable() or c in "\n\t" for c in text):
        assert shown == text  # ordinary text is left as it is
