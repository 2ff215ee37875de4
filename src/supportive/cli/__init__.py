"""The command layer: the ``supportive`` command (:data:`app`, entry point :func:`main`), one module per
command family, and the interactive front ends (the demo's tour, the teaching and chat consoles, the
workbench simulation). It sits above every library layer and draws what they return (with
:mod:`supportive.render`); nothing below imports it."""

from supportive.cli.app import app, main

__all__ = ["app", "main"]
