"""The page's controls in Debian's chromium, driven by Playwright: sign in, claim and release, another agent's
claim arriving live, completion propagating and folding the finished subtree, observers without buttons, a
wrong token, the token leaving the address. Screenshots go to test-artifacts/."""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

import httpx
from playwright.sync_api import Browser, Page, expect

Headers = Callable[[str], dict[str, str]]


def nodes(url: str, headers: Headers) -> list[dict[str, Any]]:
    data: list[dict[str, Any]] = httpx.get(f"{url}/api/board", headers=headers("screen")).json()["nodes"]
    return data


def named(url: str, headers: Headers, name: str) -> dict[str, Any]:
    return next(n for n in nodes(url, headers) if n["name"] == name)


def test_claim_and_release_with_the_buttons(
    open_page: Callable[..., Page], board_server: Any, headers: Headers, snap: Callable[..., Any]
) -> None:
    page = open_page(board_server.url, "tok-alice")
    expect(page.get_by_test_id("me")).to_have_text("alice (human, lead)")
    frame = named(board_server.url, headers, "Prepare left frame")["id"]
    page.get_by_test_id(f"claim-{frame}").click()  # an ordinary subtask: no question asked
    expect(page.get_by_test_id(f"node-{frame}")).to_have_attribute("data-owner", "alice")
    expect(page.get_by_test_id(f"owner-{frame}")).to_have_text("alice")
    expect(page.get_by_test_id(f"release-{frame}")).to_be_visible()
    expect(page.get_by_test_id("now-alice-doing")).to_have_text("pick up the left side frame")
    assert named(board_server.url, headers, "Prepare left frame")["owner"] == "alice"
    snap(page, "claimed")
    page.get_by_test_id(f"release-{frame}").click()
    expect(page.get_by_test_id(f"node-{frame}")).to_have_attribute("data-status", "free")
    expect(page.get_by_test_id("now-alice-doing")).to_have_text("no subtask claimed")
    assert named(board_server.url, headers, "Prepare left frame")["owner"] is None


def test_another_agents_claim_appears_live(
    open_page: Callable[..., Page], board_server: Any, headers: Headers, snap: Callable[..., Any]
) -> None:
    page = open_page(board_server.url, "tok-alice")
    version = page.get_by_test_id("version").text_content()
    rails = named(board_server.url, headers, "Mount front support")["id"]
    response = httpx.post(f"{board_server.url}/api/nodes/{rails}/claim", headers=headers("robot"))
    assert response.status_code == 200
    expect(page.get_by_test_id(f"node-{rails}")).to_have_attribute("data-owner", "robot")
    assert page.get_by_test_id("version").text_content() != version
    expect(page.get_by_test_id(f"claim-{rails}")).to_have_count(0)  # no button to take it from the robot
    expect(page.get_by_test_id("claim-n0")).to_have_count(0)  # nor the whole task, which contains it
    expect(page.get_by_test_id("now-robot-doing")).to_have_text("Mount front support")
    expect(page.get_by_test_id("now-robot-next")).to_have_text("waiting for Prepare side frames")
    snap(page, "robot-claim-live")


def test_completion_propagates_and_the_done_subtree_folds(
    open_page: Callable[..., Page], board_server: Any, headers: Headers, snap: Callable[..., Any]
) -> None:
    url = board_server.url
    pegs = named(url, headers, "Add left pegs")
    chain = pegs["parent"]
    steps = [n for n in nodes(url, headers) if n["parent"] == chain]
    leaves = [s["id"] for s in steps if s["kind"] == "action"] + list(pegs["children"])
    page = open_page(url, "tok-bob")
    page.get_by_test_id(f"claim-{chain}").click()
    expect(page.get_by_test_id(f"node-{chain}")).to_have_attribute("data-owner", "bob")
    watcher = open_page(url, "tok-screen")
    expect(watcher.get_by_test_id(f"node-{chain}")).to_have_attribute("data-owner", "bob")
    expect(watcher.locator("button.op")).to_have_count(0)  # an observer only reads
    for leaf in leaves[:-1]:
        page.get_by_test_id(f"complete-{leaf}").click()
        expect(page.get_by_test_id(f"node-{leaf}")).to_have_attribute("data-status", "done")
    expect(page.get_by_test_id("now-bob-count")).to_have_text(f"{len(leaves) - 1}/{len(leaves)} steps")
    page.get_by_test_id(f"complete-{leaves[-1]}").click()
    for view in (page, watcher):
        expect(view.get_by_test_id(f"node-{chain}")).to_have_attribute("data-status", "done")
        expect(view.get_by_test_id(f"node-{chain}")).to_have_class(re.compile(r"\bfolded\b"))
        for leaf in leaves:  # folded: the finished subtree is one line
            expect(view.get_by_test_id(f"node-{leaf}")).to_have_count(0)
    assert all(n["done"] for n in nodes(url, headers) if n["id"] in {chain, pegs["id"], *leaves})
    expect(watcher.get_by_test_id("overall-label")).to_have_text("4 of 24 steps done · 17 %")
    snap(page, "completion")
    snap(watcher, "observer")


def test_a_wrong_token_asks_to_sign_in(browser: Browser, untouched_board: Any) -> None:
    page = browser.new_page()
    page.goto(f"{untouched_board.url}/#token=wrong")
    expect(page.locator("#signin-error")).to_have_text("unknown token")
    expect(page.get_by_test_id("live")).to_have_text("signed out")  # the service is up: not "offline"
    expect(page.get_by_test_id("goal")).to_have_text("Sign in with an agent's token to see the board.")
    page.get_by_test_id("token").fill("tok-robot")
    page.get_by_role("button", name="Sign in").click()
    expect(page.get_by_test_id("me")).to_have_text("robot (robot, assistant)")
    page.close()


def test_the_token_leaves_the_address_after_sign_in(open_page: Callable[..., Page], untouched_board: Any) -> None:
    page = open_page(untouched_board.url, "tok-alice")
    assert "token" not in page.url and "tok-alice" not in page.url
    page.reload()  # kept for this tab only, so a reload stays signed in
    expect(page.get_by_test_id("me")).to_have_text("alice (human, lead)")
    assert "tok-alice" not in page.url


def test_the_signed_out_page_is_neither_offline_nor_loading_and_has_an_icon(browser: Browser, untouched_board: Any) -> None:
    """Issue 26: the signed-out page showed a red "offline" badge and "Loading…" while the server was up, and
    /favicon.ico was a 404."""
    page = browser.new_page()
    missing: list[str] = []
    page.on("response", lambda response: missing.append(response.url) if response.status >= 400 else None)
    page.goto(f"{untouched_board.url}/")
    expect(page.get_by_test_id("token")).to_be_visible()
    expect(page.get_by_test_id("live")).to_have_text("signed out")
    assert "off" not in (page.get_by_test_id("live").get_attribute("class") or "").split()
    expect(page.get_by_test_id("goal")).not_to_contain_text("Loading")
    icon = httpx.get(f"{untouched_board.url}/favicon.ico", timeout=10)
    assert icon.status_code == 200 and icon.headers["content-type"] == "image/vnd.microsoft.icon"
    assert icon.content[:4] == b"\x00\x00\x01\x00"  # an ICO file's header
    assert missing == []
    page.close()
