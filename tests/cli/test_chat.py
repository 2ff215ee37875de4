"""``supportive chat`` driven through stdin, and the console driven by a script."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from supportive import examples
from supportive.cli.chat_console import ChatConsole
from supportive.io import parse_task_file


def _console(path: Path, lines: list[str], shown: list[str]) -> ChatConsole:
    feed = iter(lines)

    def read() -> str:
        try:
            return next(feed)
        except StopIteration:
            raise EOFError from None

    return ChatConsole(path, read, shown.append)


def test_a_confirmed_preference_is_saved_and_explained_back(tmp_path: Path) -> None:
    path = tmp_path / "chair.yaml"
    shutil.copy(examples.path("ikea-chair"), path)
    shown: list[str] = []
    _console(path, [
        "When I am tightening the bolts, I want you to shine a light on the bolt until the rear left bolt is tight",
        "yes",
    ], shown).run()
    saved = parse_task_file(path)
    light = next(b for b in saved.behaviors if b.text == "shine a light on the bolt")
    assert light.subtasks == ("Fasten nuts and bolts",) and light.termination == "bolted(rear_left)"
    assert any(line.startswith("By 'tightening the bolts', do you mean Fasten nuts and bolts?") for line in shown)
    assert any("OK. I will now shine a light on the bolt. While you are fastening nuts and bolts" in line for line in shown)


def test_declining_or_picking_another_candidate(tmp_path: Path) -> None:
    path = tmp_path / "chair.yaml"
    shutil.copy(examples.path("ikea-chair"), path)
    before = parse_task_file(path)
    shown: list[str] = []
    _console(path, ["While I attach the front rail, please hold the side frames steady", "no"], shown).run()
    assert parse_task_file(path) == before and "All right, I changed nothing." in shown
    _console(path, ["While I attach the front rail, please hold the side frames steady", "2"], shown).run()
    frames = next(b for b in parse_task_file(path).behaviors if b.name == "hold-frames")
    assert "Mount supports" in frames.subtasks


def test_chat_command_reads_stdin(tmp_path: Path) -> None:
    path = tmp_path / "chair.yaml"
    shutil.copy(examples.path("ikea-chair"), path)
    script = shutil.which("supportive", path=str(Path(sys.executable).parent))
    assert script is not None
    result = subprocess.run(
        [script, "chat", str(path)],
        input="How will you help me screw the seat?\nWhen will you hold the seat?\nfoo bar\n\nbehaviors\n"
        "When will you juggle?\nquit\n",
        capture_output=True, text=True, check=False,
    )
    assert result.returncode == 0, result.stderr
    out = result.stdout
    assert "When you are screwing seat, I can give you screws" in out
    assert "While you are attaching seat, I will hold the seat in place" in out
    assert "I did not understand 'foo bar'" in out and "Say something, or 'quit'." in out
    assert "- give-screws: give you screws (materials retrieval; during Screw seat)" in out
    assert "I have no behavior like 'juggle'" in out
    missing = subprocess.run([script, "chat", str(tmp_path / "none.yaml")], capture_output=True, text=True, check=False)
    assert missing.returncode == 2 and "no such file" in missing.stderr and "Traceback" not in missing.stderr


def _chair(tmp_path: Path) -> Path:
    path = tmp_path / "chair.yaml"
    shutil.copy(examples.path("ikea-chair"), path)
    return path


def test_the_headline_request_is_carried_out_and_said_truthfully(tmp_path: Path) -> None:
    path = _chair(tmp_path)
    shown: list[str] = []
    _console(path, ["When I am attaching the front frame, I want you to give me screws", "yes"], shown).run()
    screws = next(b for b in parse_task_file(path).behaviors if b.name == "give-screws")
    assert screws.subtasks == ("Screw seat", "Build frame")
    answer = shown[-1]
    assert answer.startswith("OK. I will now also give you screws while you are building frame. ")
    assert "While you are building frame, I will give you screws at any point" in answer
    assert "While you are screwing seat, I will give you screws" in answer


def test_a_negative_preference_removes_the_subtask(tmp_path: Path) -> None:
    path = _chair(tmp_path)
    shown: list[str] = []
    _console(path, ["Don't hold the side frames steady when I'm mounting the front support"], shown).run()
    frames = next(b for b in parse_task_file(path).behaviors if b.name == "hold-frames")
    assert frames.subtasks == ("Mount back support",)
    assert shown[-1].startswith("OK. I will no longer hold the side frames steady while you are mounting front support.")
    assert not [line for line in shown if "do not hold" in line]


def test_each_subtask_phrase_is_confirmed_once_whatever_the_behaviors(tmp_path: Path) -> None:
    path = _chair(tmp_path)
    shown: list[str] = []
    _console(path, [
        "When I am tightening the bolts or fitting the rails, I want you to shine a light and hold the frames",
        "yes", "yes",
    ], shown).run()
    questions = [line for line in shown if line.startswith("By '")]
    assert len(questions) == 2, questions
    saved = {b.name: b for b in parse_task_file(path).behaviors}
    assert saved["shine-light"].subtasks == ("Fasten nuts and bolts", "Mount supports")
    assert saved["hold-frames"].subtasks == ("Mount front support", "Mount back support", "Fasten nuts and bolts", "Mount supports")


def test_a_new_sentence_at_a_question_is_answered_as_itself(tmp_path: Path) -> None:
    path = _chair(tmp_path)
    before = parse_task_file(path)
    shown: list[str] = []
    _console(path, [
        "When I am tightening the bolts, I want you to shine a light on the bolt",
        "How will you help me screw the seat?",
    ], shown).run()
    assert parse_task_file(path) == before
    assert "I take that as something new, so I changed nothing for the question I asked." in shown
    assert shown[-1].startswith("When you are screwing seat, I can give you screws")
    _console(path, ["When I am tightening the bolts, I want you to shine a light on the bolt", "Yes, please."], shown).run()
    assert any(b.text == "shine a light on the bolt" for b in parse_task_file(path).behaviors)


def test_a_subtask_the_robot_does_not_know_is_not_proposed(tmp_path: Path) -> None:
    shown: list[str] = []
    _console(_chair(tmp_path), ["How will you help me fly?", "When I am juggling, hold the seat"], shown).run()
    unknown = [line for line in shown if line.startswith("I don't know a part of the task like")]
    assert unknown == [
        "I don't know a part of the task like 'fly'. I know, for example: Assemble chair, Build frame, Fasten nuts "
        "and bolts, Attach seat, Prepare side frames.",
        "I don't know a part of the task like 'juggling'. I know, for example: Assemble chair, Build frame, Fasten "
        "nuts and bolts, Attach seat, Prepare side frames.",
    ]
    assert not [line for line in shown if "do you mean" in line]


WITHOUT_SCIKIT_LEARN = "import sys; sys.modules['sklearn'] = None; from supportive.cli import main; sys.argv = {}; main()"


def test_without_the_language_extra_chat_and_demo_say_so_in_one_line(tmp_path: Path) -> None:
    path = _chair(tmp_path)
    for argv in (["supportive", "chat", str(path)], ["supportive", "demo"]):
        result = subprocess.run(
            [sys.executable, "-c", WITHOUT_SCIKIT_LEARN.format(argv)],
            input="How will you help me screw the seat?\n", capture_output=True, text=True, check=False,
        )
        assert result.returncode == 2, (argv, result.stderr[-500:])
        assert result.stderr.splitlines() == [
            "supportive: error: understanding what people say needs scikit-learn, which is not installed: "
            "pip install 'supportive[language]'"
        ]


def test_chat_claims_no_understanding_it_does_not_have_and_help_helps(tmp_path: Path) -> None:
    """Issue 16.7: "stop" and "help" were answered "I understood 'stop' …", and help gave no help."""
    path = tmp_path / "chair.yaml"
    shutil.copy(examples.path("ikea-chair"), path)
    shown: list[str] = []
    _console(path, ["stop", "help", "I want you to juggle", "thanks"], shown).run()
    assert not any(line.startswith("I understood") for line in shown)
    assert any(line.startswith("Stop what?") for line in shown)
    helped = shown[shown.index("You can tell me how to help, or ask what I will do:") :]
    assert any('"When I am screwing seat, I want you to give me screws"' in line for line in helped)
    assert any(line.startswith("Parts of the task I know: Assemble chair, Build frame") for line in helped)
    assert shown[-1].startswith("I did not understand 'thanks'")


def test_a_request_with_no_verb_of_help_is_not_made_up_as_a_behavior(tmp_path: Path) -> None:
    """Issue 16.7: "I want you to juggle" used to become a new behavior: "OK. I will now juggle."."""
    path = tmp_path / "chair.yaml"
    shutil.copy(examples.path("ikea-chair"), path)
    before = path.read_text()
    shown: list[str] = []
    _console(path, ["When I am screwing the seat, I want you to juggle"], shown).run()
    assert path.read_text() == before
    assert not any("I will now juggle" in line for line in shown)
    assert any(line.startswith("I don't know how to juggle. I can help by doing what I already do (give you screws") for line in shown)
    _console(path, ["When I am screwing the seat, I want you to fetch the glue"], shown).run()  # a verb of help
    assert any(b.text == "fetch the glue" for b in parse_task_file(path).behaviors)


def test_chat_on_a_bundled_example_saves_into_a_copy_not_the_package(tmp_path: Path) -> None:
    """Issue 16.2: the README's chat line used to rewrite the package's own chair (comments gone)."""
    bundled = examples.path("ikea-chair")
    before = bundled.read_bytes()
    script = Path(sys.executable).parent / "supportive"
    result = subprocess.run(
        [str(script), "chat", "ikea-chair"],
        cwd=tmp_path,
        input="When I am tightening the bolts, I want you to shine a light on the bolt\nyes\nquit\n",
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("Saving to ikea-chair.edited.yaml, a new copy of ")
    assert bundled.read_bytes() == before
    copy = tmp_path / "ikea-chair.edited.yaml"
    assert any(b.text == "shine a light on the bolt" for b in parse_task_file(copy).behaviors)


def test_a_sentence_over_the_limit_is_answered_in_one_line_at_once(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A 4.8 KB sentence used to take 97 s and 3.2 GB; now it is refused before parsing, and the next one is
    answered as usual."""
    import shutil

    from supportive import examples
    from supportive.cli.chat_console import ChatConsole
    from supportive.io.limits import MAX_SENTENCE_CHARS
    from supportive.language import grammar

    path = tmp_path / "chair.yaml"
    shutil.copy(examples.path("ikea-chair"), path)
    long = "When I am attaching the seat, I want you to " + "hold the frames steady and " * 200
    assert len(long) > 4800
    typed = iter([long, "How will you help me attach the seat?", "quit"])
    said: list[str] = []
    parsed: list[int] = []
    parser = grammar._parser()

    class Watched:
        def parse(self, text: str, start: str) -> object:
            parsed.append(len(text))
            return parser.parse(text, start=start)

    monkeypatch.setattr(grammar, "_parser", Watched)
    ChatConsole(path, lambda: next(typed), said.append).run()
    assert parsed and max(parsed) <= MAX_SENTENCE_CHARS  # the long one never reached the parser (it took 97 s)
    assert said[1] == f"That is {len(long.strip()):,} characters; I read sentences of at most {MAX_SENTENCE_CHARS}: say it in shorter sentences, one at a time."
    assert len(said) > 2 and "seat" in said[2].lower()


def test_a_stop_condition_in_the_past_tense_is_the_subtask_finished(tmp_path: Path) -> None:
    """Issue 26: "… until the seat is screwed" was read as "you are screwing seat", and the robot answered
    "While you are screwing seat, I will hold the seat … until you are screwing seat"."""
    path = _chair(tmp_path)
    shown: list[str] = []
    _console(
        path, ["When I am screwing the seat, I want you to hold the seat until the seat is screwed"], shown
    ).run()
    answer = next(line for line in shown if line.startswith("OK."))
    assert "until you have finished screwing seat" in answer and "until you are screwing seat" not in answer
    hold = next(b for b in parse_task_file(path).behaviors if b.name == "hold-seat")
    assert "active(Screw seat)" not in hold.termination  # it no longer stops as soon as screwing begins
