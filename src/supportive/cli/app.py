"""The ``supportive`` command: a typer app whose commands live one family per module of this package
(:mod:`~supportive.cli.learn`, :mod:`~supportive.cli.infer`, :mod:`~supportive.cli.bag`, …). Commands parse
arguments, call the library and print what it returns; they compute nothing the library should own.

Bad input never shows a traceback: :func:`main` is the one handler, turning any
:class:`~supportive.errors.SupportiveError` into one line on stderr and exit status 2.
"""

from __future__ import annotations

import io
import sys
from typing import Annotated, Any

import typer
from typer.exceptions import TyperException

from supportive.cli import caregiver, chat, demo, infer, learn, reproduce, serve, support, teach, workbench
from supportive.cli.bag import bag_app
from supportive.cli.interrupt import causes, handling, interruption
from supportive.cli.output import out, say
from supportive.cli.tokens import tokens_app
from supportive.errors import SupportiveError
from supportive.render.terminal import printable

__all__ = ["INTERRUPTED", "app", "main", "tolerant_streams"]

INTERRUPTED = 130
"""The status typer gives a command that a KeyboardInterrupt (Ctrl-C, or SIGTERM here) stopped."""

HELP = {"help_option_names": ["-h", "--help"]}
"""Every command's help is ``-h`` or ``--help`` (subcommands inherit the group's context settings)."""

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    context_settings=HELP,
    help="Supportive behaviors for human-robot teaming: learn CC-HTNs from demonstrations, and more.",
)
app.add_typer(bag_app, name="bag")
app.add_typer(tokens_app, name="tokens")
for command in (
    learn.learn,
    infer.infer,
    learn.generate,
    learn.evaluate,
    learn.captaincook,
    teach.teach,
    chat.chat,
    demo.demo,
    caregiver.caregiver,
    support.support,
    serve.serve,
):
    app.command()(command)
app.command("workbench-sim")(workbench.workbench_sim)
app.command()(reproduce.reproduce)


def _print_version(wanted: bool) -> None:
    if wanted:
        from importlib.metadata import version

        out.print(f"supportive {version('supportive')}", markup=False)
        raise typer.Exit


@app.callback(context_settings=HELP)
def _options(
    version: Annotated[
        bool,
        typer.Option("--version", is_eager=True, callback=_print_version, help="Print the version and exit."),
    ] = False,
) -> None:
    """Supportive behaviors for human-robot teaming: learn CC-HTNs from demonstrations, and more."""


def _plain_placeholders(command: Any) -> None:
    """Help as people read it, not as typer shows Python (typer ≥ 0.2x): no ``<bool>``/``<str>``/``<path>``
    or ``list[str]`` placeholders — a flag shows none, a value its kind in capitals (``TEXT``, ``INTEGER``,
    ``NUMBER``, ``PATH``; a repeatable one the kind of one value), a choice its choices, an argument its name
    (``FILE``, not ``{FILE}``) and no type — and a command's description as flowing text (a docstring's line
    breaks are where its source wrapped, not where a sentence ends; a blank line still starts a paragraph).
    A typer without these is left alone."""
    kinds = {"str": "TEXT", "int": "INTEGER", "float": "NUMBER", "path": "PATH", "file": "PATH", "Path": "PATH"}
    if getattr(command, "help", None):
        command.help = _flowing(command.help)
    helper = command.get_help_option(command.context_class(command, **HELP))  # click keeps the first one made
    for param in [*command.params, *([helper] if helper is not None else [])]:
        if param.metavar is not None or not hasattr(param, "display_type"):
            continue
        if param.param_type_name == "argument":
            param.metavar = str(param.name).upper()
            param.display_type_rich = lambda ctx: None  # the name says it; no type column
            usage = param.metavar if param.required else f"[{param.metavar}]"
            param._usage_display_name = lambda usage=usage, many=param.nargs != 1: usage + ("..." if many else "")
        elif getattr(param, "is_flag", False):
            param.metavar = ""
        else:
            label = str(param.display_type(None)).strip("<>").removesuffix(" range")
            if label.startswith("list[") and label.endswith("]"):  # a repeatable option: one value's kind
                label = label[len("list[") : -1]
            param.metavar = kinds.get(label, label)
    for sub in getattr(command, "commands", {}).values():
        _plain_placeholders(sub)


def _flowing(text: str) -> str:
    """A docstring's text with its source line breaks joined (paragraphs, blank-line separated, kept).

    >>> _flowing("One sentence" + chr(10) + "wrapped." + chr(10) * 2 + "A paragraph.").split(chr(10))
    ['One sentence wrapped.', '', 'A paragraph.']
    """
    paragraphs = [" ".join(line.strip() for line in block.splitlines()) for block in text.strip().split("\n\n")]
    return "\n\n".join(paragraphs)


def main() -> None:
    """Entry point: run the app, turning library errors into one line and exit status 2 (a missing optional
    dependency too: the line names the extra that installs it), and Ctrl-C or SIGTERM into one line saying
    what was kept and what was not, with exit status 130 or 143 (:mod:`supportive.cli.interrupt`)."""
    tolerant_streams()
    with handling() as stopped:
        code = _run()
        if code == INTERRUPTED:
            stopped.arrived = True
            say(stopped.line(), to_stderr=True, whole=True)
            sys.exit(stopped.status)
    if code:
        sys.exit(code)


def tolerant_streams() -> None:
    """Let stdin, stdout and stderr whose encoding is not UTF-8 (``PYTHONIOENCODING=ascii``, a Latin-1 locale)
    replace what they cannot encode (``?``) instead of raising in the middle of the output: the text is the
    same but for those characters (JSON is ASCII already)."""
    for stream in (sys.stdin, sys.stdout, sys.stderr):
        encoding = (getattr(stream, "encoding", None) or "utf-8").lower().replace("_", "-")
        if not encoding.startswith("utf") and isinstance(stream, io.TextIOWrapper):
            stream.reconfigure(errors="replace")


def _run() -> int:
    """Run the command line; its exit status (typer's 130 for a KeyboardInterrupt)."""
    from supportive.extras import missing_extra

    try:
        command = typer.main.get_command(app)  # building the command line takes some tenths of a second
        _plain_placeholders(command)
        try:
            code = command.main(standalone_mode=False)
        except Exception as exc:  # a library turned the interruption into an error of its own ("from" it), or
            if _interrupted(exc) or interruption().raised:  # caught it and went on in a wrong state (lark once)
                return INTERRUPTED
            raise
    except KeyboardInterrupt:  # before the command started (typer turns one inside it into 130)
        return INTERRUPTED
    except typer.Abort:
        say("supportive: aborted", to_stderr=True)
        sys.exit(1)
    except TyperException as exc:  # a bad option or argument: one line too, with click's status (2)
        message = getattr(exc, "format_message", None)
        if message is None:
            raise
        context = getattr(exc, "ctx", None)
        where = context.command_path if context is not None else "supportive"
        said = _plain_value_error(message())
        say(f"{where}: error: {printable(said, newlines=False)}", to_stderr=True)
        sys.exit(int(getattr(exc, "exit_code", 2)))
    except SupportiveError as exc:
        say(f"supportive: error: {printable(str(exc), newlines=False)}", to_stderr=True)
        sys.exit(2)
    except ModuleNotFoundError as exc:
        problem = missing_extra(exc, " ".join(sys.argv[1:2]) or "this command")
        if problem is None:
            raise
        say(f"supportive: error: {problem}", to_stderr=True)
        sys.exit(2)
    return code if isinstance(code, int) else 0


def _plain_value_error(message: str) -> str:
    """A usage error in plain words: typer passes pydantic's on ("Invalid value for '--seed': Input should be
    greater than or equal to 0" becomes "… : expected at least 0").

    >>> _plain_value_error("Invalid value for '--top': Input should be greater than or equal to 1")
    "Invalid value for '--top': expected at least 1"
    """
    from supportive.io.structured import plain_words

    head, colon, problem = message.partition(": ")
    if not colon:
        return plain_words(message.removeprefix("Value error, "))
    return f"{head}: {plain_words(problem.removeprefix('Value error, '))}"


def _interrupted(exc: BaseException) -> bool:
    """Whether ``exc`` was raised because of a Ctrl-C or SIGTERM: a ``KeyboardInterrupt`` among its causes
    and contexts."""
    return any(isinstance(cause, KeyboardInterrupt) for cause in causes(exc))
