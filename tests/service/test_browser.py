"""The web page in Debian's chromium, driven by Playwright (no browser download): sign in, claim and release,
see another agent's claim arrive live, see completion propagate. Screenshots go to test-artifacts/."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest
from playwright.sync_api import Browser, Page, expect, sync_playwright

CHROMIUM = "/usr/bin/chromium"
FLAGS = [
    "--headless=new",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
ARTIFACTS = Path(__file__).resolve().parents[2] / "test-artifacts"


@pytest.fixture(scope="module")
def browser() -> Iterator[Browser]:
    if not Path(CHROMIUM).exists():
        raise RuntimeError("Debian's chromium is not installed: run `make test` (it installs it)")
    with sync_playwright() as playwright:
        launched = playwright.chromium.launch(executable_path=CHROMIUM, args=FLAGS)
        yield launched
        launched.close()


@pytest.fixture
def board_server(tmp_path: Path, server_factory: Callable[..., Any]) -> Any:
    return server_factory(f"sqlite:///{tmp_path / 'board.db'}")


def open_page(browser: Browser, url: str, token: str) -> Page:
    page = browser.new_page(viewport={"width": 1280, "height": 900})
    page.goto(f"{url}/#token={token}")
    expect(page.get_by_test_id("live")).to_have_text("live", timeout=15_000)
    return page


def snap(page: Page, name: str) -> None:
    ARTIFACTS.mkdir(exist_ok=True)
    page.screenshot(path=str(ARTIFACTS / f"{name}.png"), full_page=True)


def node_id(url: str, headers: Callable[[str], dict[str, str]], name: str) -> str:
    nodes = httpx.get(f"{url}/api/board", headers=headers("screen")).json()["nodes"]
    return str(next(n["id"] for n in nodes if n["name"] == name))


def test_claim_and_release_with_the_buttons(browser: Browser, board_server: Any) -> None:
    page = open_page(browser, board_server.url, "tok-alice")
    expect(page.get_by_test_id("me")).to_have_text("alice (human, lead)")
    page.get_by_test_id("claim-n1").click()
    expect(page.get_by_test_id("status-n1")).to_have_text("claimed by alice")
    expect(page.get_by_test_id("release-n1")).to_be_visible()
    snap(page, "claimed")
    page.get_by_test_id("release-n1").click()
    expect(page.get_by_test_id("status-n1")).to_have_text("free")
    page.close()


def test_another_agents_claim_appears_live(
    browser: Browser, board_server: Any, headers: Callable[[str], dict[str, str]]
) -> None:
    page = open_page(browser, board_server.url, "tok-alice")
    version = page.get_by_test_id("version").text_content()
    response = httpx.post(f"{board_server.url}/api/nodes/n22/claim", headers=headers("robot"))
    assert response.status_code == 200
    expect(page.get_by_test_id("status-n22")).to_have_text("claimed by robot")
    assert page.get_by_test_id("version").text_content() != version
    expect(page.get_by_test_id("claim-n22")).to_have_count(0)  # no button to take it from the robot
    snap(page, "robot-claim-live")
    refused = page.get_by_test_id("claim-n0")
    refused.click()  # the root contains the robot's subtask: the page shows why it was refused
    expect(page.get_by_test_id("message")).to_contain_text("claimed by robot")
    page.close()


def test_completion_propagates_up_the_tree(
    browser: Browser, board_server: Any, headers: Callable[[str], dict[str, str]]
) -> None:
    url = board_server.url
    left = httpx.get(f"{url}/api/board", headers=headers("screen")).json()["nodes"]
    pegs = next(n for n in left if n["name"] == "Add left pegs")
    chain = pegs["parent"]
    steps = [n for n in left if n["parent"] == chain]
    leaves = [s["id"] for s in steps if s["kind"] == "action"] + list(pegs["children"])
    page = open_page(browser, url, "tok-bob")
    page.get_by_test_id(f"claim-{chain}").click()
    expect(page.get_by_test_id(f"status-{chain}")).to_have_text("claimed by bob")
    watcher = open_page(browser, url, "tok-screen")
    expect(watcher.get_by_test_id(f"claim-{chain}")).to_have_count(0)  # an observer only reads
    for leaf in leaves:
        page.get_by_test_id(f"complete-{leaf}").click()
        expect(page.get_by_test_id(f"status-{leaf}")).to_have_text("done")
    expect(page.get_by_test_id(f"status-{pegs['id']}")).to_have_text("done")
    expect(page.get_by_test_id(f"status-{chain}")).to_have_text("done")
    expect(watcher.get_by_test_id(f"status-{chain}")).to_have_text("done")
    snap(page, "completion")
    snap(watcher, "observer")
    page.close()
    watcher.close()


def test_a_wrong_token_asks_to_sign_in(browser: Browser, board_server: Any) -> None:
    page = browser.new_page()
    page.goto(f"{board_server.url}/#token=wrong")
    expect(page.locator("#signin-error")).to_have_text("unknown token")
    page.get_by_test_id("token").fill("tok-robot")
    page.get_by_role("button", name="Sign in").click()
    expect(page.get_by_test_id("me")).to_have_text("robot (robot, assistant)")
    page.close()
