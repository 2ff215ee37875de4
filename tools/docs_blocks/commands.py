"""Blocks made by running a quick command: ``supportive support``, ``supportive chat``."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

from .common import ROOT, Block, command


def support_two_cells_led() -> str:
    """docs/support.md: `supportive support two-cells-led --simulate`, its first lines (a few favoured plans)."""
    lines = command("support", "two-cells-led", "--simulate").splitlines()
    favoured = [i for i, line in enumerate(lines) if line.startswith("  favours")]
    kept = [*lines[: favoured[0] + 1], "  ...", *lines[favoured[-1] + 1 :]] if len(favoured) > 1 else lines
    return "```console\n$ supportive support two-cells-led --simulate\n" + "\n".join(kept) + "\n```\n"


CHAT = (
    "How will you help me screw the seat?",
    "When I am attaching the front frame, I want you to give me screws",
    "yes",
    "Don't hold the side frames steady when I'm mounting the front support",
    "How will you help me fly?",
)
"""What docs/language.md's conversation says to the robot, a line at a time."""


def chat_transcript() -> str:
    """docs/language.md: ``supportive chat examples/ikea-chair.yaml`` fed :data:`CHAT`, each line shown after its
    prompt as a terminal shows it; run in a temporary folder holding a copy of the example, so the copy the chat
    saves to is made there, never in the repository."""
    with tempfile.TemporaryDirectory() as folder:
        (Path(folder) / "examples").mkdir()
        (Path(folder) / "examples" / "ikea-chair.yaml").write_bytes(
            (ROOT / "examples" / "ikea-chair.yaml").read_bytes()
        )
        env = {**os.environ, "COLUMNS": "110", "NO_COLOR": "1", "TERM": "dumb"}
        done = subprocess.run(
            [sys.executable, "-m", "supportive.cli", "chat", "examples/ikea-chair.yaml"],
            cwd=folder,
            env=env,
            input="".join(line + "\n" for line in CHAT),
            capture_output=True,
            text=True,
            check=False,
        )
    if done.returncode:
        raise RuntimeError(f"supportive chat failed ({done.returncode}): {done.stderr.strip()}")
    header, *answers = re.split(r"(?m)^> ", done.stdout)
    if len(answers) != len(CHAT) + 1 or answers[-1].strip():
        raise RuntimeError(
            f"supportive chat answered {len(answers) - 1} of {len(CHAT)} lines: {done.stdout!r}"
        )
    turns = "".join(f"> {said}\n{answer}" for said, answer in zip(CHAT, answers, strict=False))
    text = "\n".join(line.rstrip() for line in (header + turns).splitlines())
    return f"```console\n$ supportive chat examples/ikea-chair.yaml\n{text}\n```\n"


BLOCKS: dict[str, Block] = {
    "support-two-cells-led": Block(
        "supportive support two-cells-led --simulate", support_two_cells_led, True
    ),
    "chat-transcript": Block(
        "supportive chat examples/ikea-chair.yaml, fed docs_blocks.commands.CHAT (in a temporary folder)",
        chat_transcript,
        True,
    ),
}
