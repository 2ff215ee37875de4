"""The lab screen against the board's state: the page on the workcell's 1920 × 1080 monitor and on a 1280 × 800
laptop, in Debian's chromium. Each screenshot is written to test-artifacts/ and read back: what it shows (each
agent's "now", what is next and blocked, overall progress, the tree, goal inference, social force) is checked
against the board and insight the API gives, worked out here independently of the page, and the colours in the
picture against each agent's. Also: agents' colours apart under colour-vision deficiencies, "no hand data yet",
off-script steps flagged, a mistake shown as soon as the step that caused it is observed, an honest
connection state, confirmation before claiming the whole task or a
lead-only subtask, and the API docs offline."""

from __future__ import annotations

import itertools
import math
import re
from collections.abc import Callable
from typing import Any

import httpx
import numpy as np
import pytest
from colorspacious import cspace_convert, deltaE
from PIL import Image
from playwright.sync_api import Page, Route, expect

from supportive.examples import load
from supportive.social.board import BoardNode, TaskBoard

Headers = Callable[[str], dict[str, str]]
SIZES = {"1920x1080": {"width": 1920, "height": 1080}, "1280x800": {"width": 1280, "height": 800}}
DONE_GREY = "#98a2a8"
"""The left edge of a finished subtask (style.css)."""
CLAIMERS = ("alice", "bob", "robot")
"""The agents of the test board that claim (screen is an observer)."""


# -- the board's state, worked out here ----------------------------------------------------------------------


def board_of(url: str, headers: Headers) -> tuple[TaskBoard, int]:
    data = httpx.get(f"{url}/api/board", headers=headers("screen")).json()
    return TaskBoard.from_dict(data), int(data["version"])


def leaves(board: TaskBoard, ident: str) -> list[BoardNode]:
    return [n for n in board.subtree(ident) if n.kind == "action"]


def listed(names: list[str]) -> str:
    return " and ".join(names[:2]) + (f" (+{len(names) - 2})" if len(names) > 2 else "")


def expected_now(board: TaskBoard, agent: str) -> dict[str, str]:
    """What an agent's card must say: the action it is on (the one with progress, else the first it may
    start) or, when it may start nothing, its subtask and what it waits for."""
    byid = {n.id: n for n in board.nodes}
    claimed = [
        n
        for n in board.nodes
        if n.owner == agent and not n.done and (n.parent is None or byid[n.parent].owner != agent)
    ]
    if not claimed:
        return {"doing": "no subtask claimed"}
    root = claimed[0]
    steps = leaves(board, root.id)
    open_ = [s for s in steps if not s.done]
    ready = [s for s in open_ if board.ready(s.id)]
    current = next((s for s in ready if s.progress > 0), ready[0] if ready else None)
    count = f"{len(steps) - len(open_)}/{len(steps)} steps"
    if current is None:
        waits = [p.name for p in board.prerequisites(open_[0].id) if not p.done]
        return {"doing": root.name, "count": count, "next": f"waiting for {listed(waits)}"}
    after = [s for s in open_[open_.index(current) + 1 :]] or [s for s in open_ if s is not current]
    then = f"then: {after[0].name}" if after else "then: this subtask is finished"
    return {"doing": current.name, "count": count, "next": then}


def free_now(board: TaskBoard) -> list[str]:
    return [n.name for n in board.nodes if n.kind == "action" and not n.done and not n.owner and board.ready(n.id)]


def mid_task(url: str, headers: Headers) -> None:
    """alice has finished the left frame and claimed the front rail, which waits for the side frames; the
    robot has the right frame, one step done and 40 % into the next; both hands are moving; the robot has
    seen the right frame picked up and stood on the table."""
    board, _ = board_of(url, headers)
    ids = {n.name: n.id for n in board.nodes}

    def do(agent: str, name: str, op: str, **body: Any) -> None:
        response = httpx.post(f"{url}/api/nodes/{ids[name]}/{op}", headers=headers(agent), json=body or None)
        assert response.status_code == 200, response.text

    do("alice", "Prepare left frame", "claim")
    for step in leaves(board, ids["Prepare left frame"]):
        do("alice", step.name, "complete")
    do("alice", "Mount front support", "claim")
    do("robot", "Prepare right frame", "claim")
    do("robot", "pick up the right side frame", "complete")
    do("robot", "stand the right side frame on the table", "progress", progress=0.4)
    for i in range(12):
        for agent, x, y in (("alice", 0.3 + 0.03 * i, 0.2 + 0.01 * i), ("robot", 1.5 - 0.02 * i, 0.5)):
            hand = {"x": x, "y": y, "t": 0.1 * i}
            assert httpx.post(f"{url}/api/hands", headers=headers(agent), json=hand).status_code == 200
    for events in (["hand-right_frame"], ["hand-right_frame", "right_frame-table"]):
        seen = httpx.post(f"{url}/api/observations", headers=headers("robot"), json={"events": events})
        assert seen.status_code == 200


# -- reading the page and its picture ---------------------------------------------------------------------


def hex_of(css: str) -> str:
    """``rgb(0, 114, 178)`` as ``#0072b2``."""
    numbers = re.findall(r"[\d.]+", css)[:3]
    return "#" + "".join(f"{round(float(v)):02x}" for v in numbers)


def pixel(picture: Image.Image, x: float, y: float) -> str:
    r, g, b = picture.getpixel((math.floor(x), math.floor(y)))  # type: ignore[misc]
    return f"#{r:02x}{g:02x}{b:02x}"


def colours(page: Page) -> dict[str, str]:
    """Each agent's colour, from the legend."""
    found: dict[str, str] = page.evaluate(
        """() => Object.fromEntries([...document.querySelectorAll('.legend-item')].map((item) =>
            [item.querySelector('.who').textContent, getComputedStyle(item.querySelector('.swatch')).backgroundColor]))"""
    )
    return {agent: hex_of(css) for agent, css in found.items()}


def rendered(page: Page) -> dict[str, dict[str, Any]]:
    """Every node the tree shows: its classes, step number, chips, owner pill, box."""
    found: list[dict[str, Any]] = page.evaluate(
        """() => [...document.querySelectorAll('#tree [data-node]')].map((el) => {
            const head = el.querySelector(':scope > .head');
            const step = head.querySelector(':scope > .step');
            const r = el.getBoundingClientRect();
            return {id: el.dataset.node, classes: [...el.classList], step: step ? step.textContent : null,
                    chips: [...head.querySelectorAll(':scope > .chip')].map((c) => c.textContent),
                    owner: el.dataset.owner || null, status: el.dataset.status,
                    box: {x: r.x, y: r.y, w: r.width, h: r.height}};
        })"""
    )
    return {n["id"]: n for n in found}


def wait_until_shown(page: Page, version: int) -> None:
    expect(page.get_by_test_id("version")).to_have_text(f"version {version}")
    expect(page.get_by_test_id("goal")).to_have_attribute("data-state", re.compile("belief|waiting|off"))


# -- the screen against the board ---------------------------------------------------------------------------


@pytest.mark.parametrize("size", SIZES)
def test_the_screen_shows_the_board_as_it_is(
    size: str, open_page: Callable[..., Page], board_server: Any, headers: Headers, snap: Callable[..., Any]
) -> None:
    url = board_server.url
    mid_task(url, headers)
    board, version = board_of(url, headers)
    viewport = SIZES[size]
    page = open_page(url, "tok-screen", viewport)
    wait_until_shown(page, version)
    expect(page.get_by_test_id("social-empty")).to_be_hidden()
    picture = snap(page, f"lab-screen-{size}")
    shown = rendered(page)
    colour = colours(page)

    # the whole screen fits: no scrolling, and the chair's tree fits its panel
    sizes = page.evaluate(
        """() => { const t = document.getElementById('tree'), d = document.documentElement;
            return [d.scrollHeight, d.scrollWidth, t.scrollHeight, t.clientHeight, t.scrollWidth, t.clientWidth]; }"""
    )
    assert sizes[0] <= viewport["height"] and sizes[1] <= viewport["width"], sizes
    assert sizes[2] <= sizes[3] + 1 and sizes[4] <= sizes[5] + 1, sizes
    for drawn in shown.values():
        box = drawn["box"]
        assert box["x"] >= 0 and box["y"] >= 0, drawn
        assert box["x"] + box["w"] <= viewport["width"] and box["y"] + box["h"] <= viewport["height"], drawn

    # one colour per agent that claims, in the legend; none for the observer
    assert set(colour) == set(CLAIMERS) and len(set(colour.values())) == len(CLAIMERS)

    # now: each agent's card, from the board
    for agent in CLAIMERS:
        now = expected_now(board, agent)
        expect(page.get_by_test_id(f"now-{agent}-doing")).to_have_text(now["doing"])
        if "count" in now:
            expect(page.get_by_test_id(f"now-{agent}-count")).to_have_text(now["count"])
            expect(page.get_by_test_id(f"now-{agent}-next")).to_have_text(now["next"])
        card = page.get_by_test_id(f"now-{agent}").bounding_box()
        assert card is not None
        assert pixel(picture, card["x"] + 3, card["y"] + card["height"] / 2) == colour[agent]
    free = free_now(board)
    expected_next = [f"{name} in " for name in free[:4]] or ["Nothing free can start now."]
    items = page.get_by_test_id("next").locator("li")
    expect(items).to_have_count(len(expected_next))
    for item, text in zip(items.all(), expected_next, strict=True):
        assert (item.text_content() or "").startswith(text)
    expect(page.get_by_test_id("blocked")).to_contain_text("Mount front support (alice) waits for Prepare side frames")
    total = sum(n.kind == "action" for n in board.nodes)
    done = sum(n.kind == "action" and n.done for n in board.nodes)
    expect(page.get_by_test_id("overall-label")).to_have_text(
        f"{done} of {total} steps done · {math.floor(100 * done / total + 0.5)} %"
    )

    # the tree: done subtrees folded to one line, what is under way or may start open, chains numbered,
    # cliques marked, each claim in its agent's colour (the picture's pixels), done work grey
    byid = {n.id: n for n in board.nodes}
    for node in board.nodes:
        parent = byid[node.parent] if node.parent else None
        if node.done and (parent is None or not parent.done):
            assert node.id in shown, node
            assert node.kind == "action" or "folded" in shown[node.id]["classes"], node
            assert not any(d.id in shown for d in board.subtree(node.id)[1:]), node
        if node.kind == "action" and not node.done and (node.owner or board.ready(node.id)):
            assert node.id in shown, node
        if node.id in shown and parent is not None and parent.kind == "chain":
            assert shown[node.id]["step"] == str(parent.children.index(node.id) + 1), node
        if node.id in shown and node.kind == "clique" and "folded" not in shown[node.id]["classes"]:
            assert "any order" in shown[node.id]["chips"], node
        if node.id in shown and node.lead_only:
            assert "lead only" in shown[node.id]["chips"], node
    for ident, drawn in shown.items():
        box = drawn["box"]
        edge = pixel(picture, box["x"] + 2, box["y"] + box["h"] / 2)
        owner = byid[ident].owner
        if byid[ident].done:
            assert edge == DONE_GREY, (ident, edge)
        elif owner:
            assert edge == colour[owner], (ident, edge)

    # goal inference: the belief the API has, in words, with bars
    goal = httpx.get(f"{url}/api/insight", headers=headers("screen")).json()["goal"]
    texts = load("ikea-chair").texts()
    current = [e for i, e in enumerate(goal["current"]) if i == 0 or e["probability"] >= 0.005][:3]
    rows = page.get_by_test_id("goal-current").locator("li")
    expect(rows).to_have_count(len(current))
    for row, entry in zip(rows.all(), current, strict=True):
        assert row.locator(".label").text_content() == texts[entry["action"]]
        assert float(row.get_attribute("data-probability") or "nan") == pytest.approx(entry["probability"])
    expect(page.get_by_test_id("goal-subtask").locator("li").first.locator(".label")).to_have_text(
        goal["subtasks"][0]["name"]
    )

    # social force to scale: each hand where the API says, in its agent's colour
    social = httpx.get(f"{url}/api/social", headers=headers("screen")).json()
    canvas = page.get_by_test_id("social")
    where = canvas.bounding_box()
    assert where is not None
    scale = float(canvas.get_attribute("data-scale") or "nan")
    margin = float(canvas.get_attribute("data-margin") or "nan")
    width, depth = social["workspace"]
    assert where["width"] == pytest.approx(width * scale + 2 * margin, abs=1)
    assert where["height"] == pytest.approx(depth * scale + 2 * margin, abs=1)  # one scale for x and y
    for agent in social["agents"]:
        x, y = agent["hand"]
        at = pixel(picture, where["x"] + margin + x * scale, where["y"] + margin + (depth - y) * scale)
        assert at == colour[agent["id"]], agent

    # readable from across the workcell (on the workcell's monitor)
    if size == "1920x1080":
        font = page.evaluate(
            """() => ['now-robot-doing', 'overall-label', 'tree'].map((id) =>
                parseFloat(getComputedStyle(document.querySelector(`[data-testid=${id}]`)).fontSize))"""
        )
        assert font[0] >= 28 and font[1] >= 24 and font[2] >= 15, font


def test_a_fresh_board_says_there_is_no_hand_data_yet(
    open_page: Callable[..., Page], untouched_board: Any, headers: Headers, snap: Callable[..., Any]
) -> None:
    page = open_page(untouched_board.url, "tok-screen")
    wait_until_shown(page, 0)
    expect(page.get_by_test_id("social-empty")).to_be_visible()
    expect(page.get_by_test_id("social-empty")).to_have_text("No hand data yet")
    expect(page.get_by_test_id("goal")).to_have_attribute("data-state", "waiting")  # configured, nothing seen
    expect(page.get_by_test_id("goal")).to_contain_text("waiting for the first contact events")
    for agent in CLAIMERS:
        expect(page.get_by_test_id(f"now-{agent}-doing")).to_have_text("no subtask claimed")
    board, _ = board_of(untouched_board.url, headers)
    assert all(n.id in rendered(page) for n in board.nodes)  # nothing done: the whole chair, open
    snap(page, "lab-screen-fresh")


def test_agents_colours_stay_apart_with_colour_blindness(
    open_page: Callable[..., Page], untouched_board: Any
) -> None:
    """Under protanopia, deuteranopia and tritanopia (full severity, Machado et al. via colorspacious), every
    two agents' colours, and each against the grey of done work, stay at least 10 apart in CAM02-UCS. The
    palette's first six colours are checked (the page's order), through a board with six claiming agents."""
    page = open_page(untouched_board.url, "tok-screen")
    palette = page.evaluate("async () => (await import('/static/model.js')).PALETTE")[:6]
    found = colours(page)
    assert list(found.values()) == [p.lower() for p in palette[: len(found)]]

    def rgb(code: str) -> np.ndarray:
        return np.array([int(code[i : i + 2], 16) for i in (1, 3, 5)]) / 255

    for deficiency in (None, "protanomaly", "deuteranomaly", "tritanomaly"):
        seen = {
            c: rgb(c)
            if deficiency is None
            else np.clip(
                cspace_convert(rgb(c), {"name": "sRGB1+CVD", "cvd_type": deficiency, "severity": 100}, "sRGB1"),
                0,
                1,
            )
            for c in [*palette, DONE_GREY]
        }
        for a, b in itertools.combinations(seen, 2):
            assert deltaE(seen[a], seen[b], input_space="sRGB1") >= 10, (deficiency, a, b)


def insight_payload(goal: dict[str, Any] | None, belief: list[dict[str, Any]] | None = None) -> dict[str, Any]:
    return {"inference": True, "belief": belief, "goal": goal, "behaviors": []}


GOAL = {
    "step": 7,
    "subtasks": [{"name": "Fasten front left bolt", "probability": 0.9}],
    "current": [{"action": "insert_bolt_fl", "text": "insert the front left bolt", "probability": 0.8}],
    "next": [{"action": "tighten_nut_fl", "text": "tighten the front left nut", "probability": 0.7}],
    "recent": [
        {"step": 6, "action": "get_seat", "text": "pick up the seat", "off_script": True},
        {"step": 7, "action": "insert_bolt_fl", "text": "insert the front left bolt", "off_script": False},
    ],
}


@pytest.mark.parametrize(
    ("payload", "flagged"),
    [
        (insight_payload({**GOAL, "surprise": 0.92}), True),  # a model that reports surprise
        (insight_payload({**GOAL, "surprise": 0.1, "off_script": False}), False),
        (insight_payload({k: v for k, v in GOAL.items() if k != "recent"}), False),  # no surprise at all
        (insight_payload(None, [{"name": "insert_bolt_fl", "probability": 0.8}]), False),  # the older shape
    ],
)
def test_off_script_steps_are_flagged_and_a_payload_without_surprise_still_shows(
    payload: dict[str, Any],
    flagged: bool,
    open_page: Callable[..., Page],
    untouched_board: Any,
    snap: Callable[..., Any],
) -> None:
    page = open_page(untouched_board.url, "tok-screen")

    def answer(route: Route) -> None:
        route.fulfill(json=payload)

    page.route("**/api/insight", answer)
    expect(page.get_by_test_id("goal")).to_have_attribute("data-state", "belief")
    expect(page.get_by_test_id("off-script")).to_have_count(1 if flagged else 0)
    expect(page.get_by_test_id("goal-current").locator(".label").first).to_have_text(
        "insert the front left bolt" if payload["goal"] else "insert_bolt_fl"
    )
    if flagged:
        expect(page.get_by_test_id("off-script")).to_contain_text("surprise 0.92")
        expect(page.get_by_test_id("goal-recent").locator("li.flagged")).to_have_text("⚠ pick up the seat")
        snap(page, "lab-screen-off-script")


def test_a_mistake_is_on_the_screen_within_one_update_of_the_step_that_caused_it(
    open_page: Callable[..., Page], board_server: Any, headers: Headers, snap: Callable[..., Any]
) -> None:
    """The chair built with "stand the right side frame on the table" skipped: once the step after it is
    observed, and with nothing sent after it, the screen lists the mistake the service raised (its kind,
    the reminder the robot says, the board node it concerns)."""
    url = board_server.url
    spec = load("ikea-chair")
    contacts = {a.id: [event for event, _ in a.observations] for a in spec.actions}
    shown = list(spec.demonstrations[0].actions)
    skipped = shown.index("place_right_frame")
    page = open_page(url, "tok-screen")
    for action in [*shown[:skipped], shown[skipped + 1]]:
        answer = httpx.post(f"{url}/api/observations", headers=headers("robot"), json={"events": contacts[action]})
        assert answer.status_code == 200
    mistake = answer.json()["mistake"]
    assert mistake is not None and mistake["kind"] == "missing"
    shown_mistake = page.get_by_test_id("mistake")
    expect(shown_mistake).to_have_count(1)
    expect(shown_mistake).to_have_attribute("data-kind", "missing")
    expect(shown_mistake).to_have_attribute("data-nodes", " ".join(mistake["nodes"]))
    expect(shown_mistake.locator(".say")).to_have_text(mistake["help"]["say"])
    snap(page, "lab-screen-mistake")


def test_while_disconnected_the_controls_are_off_and_a_banner_says_so(
    open_page: Callable[..., Page],
    board_server: Any,
    server_factory: Callable[..., Any],
    headers: Headers,
    snap: Callable[..., Any],
) -> None:
    page = open_page(board_server.url, "tok-alice")
    buttons = page.locator("button.op")
    assert buttons.count() > 0
    expect(page.get_by_test_id("banner")).to_be_hidden()
    board_server.stop()
    expect(page.get_by_test_id("banner")).to_be_visible()
    expect(page.get_by_test_id("live")).to_have_text("offline")
    for button in buttons.all():
        expect(button).to_be_disabled()
    expect(page.get_by_test_id("banner")).to_contain_text("attempt 2", timeout=10_000)  # retrying
    snap(page, "lab-screen-disconnected")
    again = server_factory(board_server.database, board_server.port)
    expect(page.get_by_test_id("banner")).to_be_hidden(timeout=20_000)
    expect(page.get_by_test_id("live")).to_have_text("live")
    for button in page.locator("button.op").all():
        expect(button).to_be_enabled()
    rails = next(n.id for n in board_of(again.url, headers)[0].nodes if n.name == "Mount back support")
    assert httpx.post(f"{again.url}/api/nodes/{rails}/claim", headers=headers("robot")).status_code == 200
    expect(page.get_by_test_id(f"node-{rails}")).to_have_attribute("data-owner", "robot")


def test_claiming_the_whole_task_or_a_lead_only_subtask_asks_first(
    open_page: Callable[..., Page], board_server: Any, headers: Headers, snap: Callable[..., Any]
) -> None:
    url = board_server.url
    page = open_page(url, "tok-alice")
    dialog = page.get_by_test_id("confirm")
    page.get_by_test_id("claim-n0").click()
    expect(dialog).to_be_visible()
    expect(dialog).to_contain_text("Claim the whole task?")
    expect(dialog).to_contain_text("all 24 remaining steps")
    snap(page, "lab-screen-confirm")
    page.get_by_test_id("confirm-no").click()
    expect(dialog).to_be_hidden()
    board, version = board_of(url, headers)
    assert version == 0 and board.nodes[0].owner is None  # cancelled: nothing sent
    seat = next(n for n in board.nodes if n.name == "Attach seat")
    page.get_by_test_id(f"claim-{seat.id}").click()
    expect(dialog).to_contain_text("“Attach seat” is reserved for leads")
    page.get_by_test_id("confirm-yes").click()
    expect(page.get_by_test_id(f"node-{seat.id}")).to_have_attribute("data-owner", "alice")
    assert board_of(url, headers)[0].node(seat.id).owner == "alice"
    frame = next(n for n in board.nodes if n.name == "Prepare left frame")
    page.get_by_test_id(f"claim-{frame.id}").click()  # an ordinary subtask: claimed at once
    expect(dialog).to_be_hidden()
    expect(page.get_by_test_id(f"node-{frame.id}")).to_have_attribute("data-owner", "alice")
    robot = open_page(url, "tok-robot")
    expect(robot.get_by_test_id(f"claim-{seat.id}")).to_have_count(0)  # an assistant is not offered it


def test_the_api_docs_work_offline(open_page: Callable[..., Page], untouched_board: Any, browser: Any) -> None:
    """Every request the docs page makes goes to the board's own address (anything else is refused), and
    Swagger UI still lists every operation."""
    page = browser.new_page()
    elsewhere: list[str] = []

    def only_here(route: Route) -> None:
        if route.request.url.startswith(untouched_board.url):
            route.continue_()
        else:
            elsewhere.append(route.request.url)
            route.abort()

    page.route("**/*", only_here)
    page.goto(f"{untouched_board.url}/docs")
    operations = page.locator(".opblock")
    expect(operations.first).to_be_visible(timeout=15_000)
    schema = httpx.get(f"{untouched_board.url}/openapi.json").json()
    count = sum(len(methods) for methods in schema["paths"].values())
    expect(operations).to_have_count(count)
    expect(page.locator(".opblock-summary-path", has_text="/api/board").first).to_be_visible()
    assert elsewhere == []
    page.close()
