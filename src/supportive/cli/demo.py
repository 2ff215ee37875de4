"""``supportive demo``: the guided tour of the IKEA chair and the rest of the toolkit."""

from __future__ import annotations

from supportive.cli.output import out

__all__ = ["demo"]


def demo() -> None:
    """Learn the bundled IKEA chair task and show what the demonstrations did and did not pin down."""
    from supportive.cli.demo_tour import run_demo

    run_demo(out)
