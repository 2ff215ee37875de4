// The lab screen: the board for everyone in the workcell (observers) and, with the same page, controls for the
// signed-in agent. No build step. Reads the board over HTTP, follows it over a WebSocket (reconnecting with
// back-off, controls off while disconnected), polls the social-force and insight panels.
"use strict";

import { agentColours, ancestorsOf, claimable, descendantsOf, indexed, isCurrent, leavesOf } from "./model.js";
import { drawSocial, renderBehaviors, renderGoal, renderLegend, renderNow, renderOverall, renderQueue } from "./panels.js";
import { el, fitTree, renderTree } from "./tree.js";

const TOKEN_KEY = "supportive-token";
const RETRY_FIRST = 500, RETRY_MOST = 10_000;
const POLL = 1000;

const state = {
  token: null, me: null, agents: [], colours: new Map(), board: null, byId: null, version: -1,
  socket: null, connected: false, retry: RETRY_FIRST, attempt: 0, reconnectAt: 0, timer: null,
  opened: new Set(), social: null,
};

const $ = (id) => document.getElementById(id);

// -- sign-in: the token is read once from the address (#token=…), then kept in this tab only ----------------

function tokenFromPage() {
  const hash = new URLSearchParams(location.hash.slice(1));
  const token = hash.get("token");
  if (token) {
    sessionStorage.setItem(TOKEN_KEY, token);
    history.replaceState(null, "", location.pathname + location.search);  // not left in the address bar
  }
  return token || sessionStorage.getItem(TOKEN_KEY);
}

async function api(path, options = {}) {
  let response;
  try {
    response = await fetch(path, {
      ...options,
      headers: { "Authorization": `Bearer ${state.token}`, "Content-Type": "application/json", ...(options.headers || {}) },
    });
  } catch (error) {
    disconnected();
    throw new Error("the board service cannot be reached");
  }
  const body = await response.json().catch(() => ({}));
  if (!response.ok) {
    const error = new Error(typeof body.detail === "string" ? body.detail
      : Array.isArray(body.detail) ? body.detail.map((item) => item.msg).join("; ")
      : `${response.status} ${response.statusText}`);
    error.status = response.status;
    throw error;
  }
  return body;
}

function signIn(problem) {
  sessionStorage.removeItem(TOKEN_KEY);
  $("live").textContent = "signed out";  // not "offline": the service answered, it wants a token
  $("live").className = "badge idle";
  $("goal").replaceChildren(el("p", "muted", "Sign in with an agent's token to see the board."));
  $("signin").hidden = false;
  $("signin-error").textContent = problem || "";
  $("token").focus();
}

async function start(token) {
  state.token = token;
  $("live").textContent = "connecting";
  try {
    state.me = await api("/api/me");
    state.agents = await api("/api/agents");
  } catch (error) {
    return error.status === 401 ? signIn(error.message) : retryStart(token, error);
  }
  sessionStorage.setItem(TOKEN_KEY, token);
  $("signin").hidden = true;
  document.body.dataset.role = state.me.role;
  $("me").textContent = `${state.me.id} (${state.me.kind}, ${state.me.role})`;
  $("signout").hidden = false;
  state.colours = agentColours(state.agents);
  renderLegend($("legend"), state.agents, state.colours);
  show(await api("/api/board"));
  connect();
  poll();
  setInterval(poll, POLL);
}

function retryStart(token, error) {
  message(`${error.message}: trying again`);
  setTimeout(() => start(token), RETRY_MOST / 2);
}

// -- the board -------------------------------------------------------------------------------------------------

function show(board) {
  if (!board || board.version < state.version) return;  // an older message arriving late
  state.board = board;
  state.version = board.version;
  state.byId = indexed(board);
  draw();
}

function draw() {
  if (!state.byId) return;
  const byId = state.byId;
  $("task").textContent = state.board.task;
  $("version").textContent = `version ${state.board.version}`;
  renderOverall($("overall"), byId, state.colours);
  renderNow($("now"), byId, state.agents, state.colours);
  renderQueue($("next"), $("blocked"), byId);
  const tree = $("tree");
  const options = {
    colours: state.colours, controls, opened: state.opened,
    onToggle: (id) => { state.opened.has(id) ? state.opened.delete(id) : state.opened.add(id); draw(); },
  };
  const foldable = [...byId.values()]
    .filter((n) => n.kind !== "action" && n.parent !== null && !n.done && !isCurrent(byId, n.id))
    .sort((a, b) => ancestorsOf(byId, b.id).length - ancestorsOf(byId, a.id).length)
    .map((n) => n.id);
  const fitted = fitTree(tree, (layout) => tree.replaceChildren(renderTree(byId, { ...options, ...layout })), foldable);
  tree.dataset.scale = String(fitted.scale);
}

function controls(node) {
  const me = state.me;
  if (!me || me.role === "observer" || node.done) return [];
  const byId = state.byId;
  const out = [];
  const worthIt = node.kind !== "action" || node.ready;  // a waiting action is claimed with its subtask
  if (worthIt && claimable(byId, node.id, me.id, me.role)) out.push(button(node.parent === null ? "claim whole task" : "claim", "claim", node));
  const claimedHere = node.owner === me.id && (node.parent === null || byId.get(node.parent).owner !== me.id);
  if (claimedHere) out.push(button("release", "release", node));
  if (node.kind === "action" && node.owner === me.id && node.ready) out.push(button("done", "complete", node));
  return out;
}

function button(label, op, node) {
  const b = el("button", `op op-${op}`, label);
  b.dataset.testid = `${op}-${node.id}`;
  b.disabled = !state.connected;
  b.addEventListener("click", async (event) => {
    event.stopPropagation();
    if (op === "claim" && !(await confirmClaim(node))) return;
    try {
      const result = await api(`/api/nodes/${node.id}/${op}`, { method: "POST" });
      message("");
      show(result.board);
    } catch (error) {
      message(error.message);
    }
  });
  return b;
}

// Claiming the whole task, or anything reserved for leads, is asked about first.
async function confirmClaim(node) {
  const byId = state.byId;
  const steps = leavesOf(byId, node.id).filter((l) => !l.done).length;
  const reserved = [node, ...descendantsOf(byId, node.id)].filter((n) => n.lead_only);
  if (node.parent !== null && !reserved.length) return true;
  const title = node.parent === null ? "Claim the whole task?" : `Claim “${node.name}”?`;
  const lines = [];
  if (node.parent === null) lines.push(`You would own all ${steps} remaining steps of ${state.board.task}; nobody else could take any of them until you release it.`);
  else lines.push(`You would own its ${steps} remaining step${steps === 1 ? "" : "s"}.`);
  if (reserved.length) lines.push(`${reserved.map((n) => `“${n.name}”`).slice(0, 2).join(" and ")} ${reserved.length === 1 ? "is" : "are"} reserved for leads.`);
  return ask(title, lines.join(" "), node.parent === null ? "Claim the whole task" : "Claim it");
}

function ask(title, text, yes) {
  const dialog = $("confirm");
  $("confirm-title").textContent = title;
  $("confirm-text").textContent = text;
  $("confirm-yes").textContent = yes;
  dialog.returnValue = "";
  dialog.showModal();
  return new Promise((resolve) => dialog.addEventListener("close", () => resolve(dialog.returnValue === "ok"), { once: true }));
}

function message(text) {
  $("message").textContent = text;
}

// -- live updates and an honest connection state ---------------------------------------------------------

function connect() {
  clearTimeout(state.timer);
  const scheme = location.protocol === "https:" ? "wss" : "ws";
  const socket = new WebSocket(`${scheme}://${location.host}/api/ws?token=${encodeURIComponent(state.token)}`);
  state.socket = socket;
  socket.addEventListener("open", () => {
    state.retry = RETRY_FIRST;
    state.attempt = 0;
    setConnected(true);
  });
  socket.addEventListener("message", (event) => {
    const data = JSON.parse(event.data);
    if (data.board) show(data.board);
    if (data.type === "belief" || data.type === "mistake") pollInsight();
  });
  socket.addEventListener("close", (event) => {
    if (state.socket !== socket) return;
    if (event.code === 4401) { setConnected(false); return signIn("that token is not known here, or was revoked"); }
    scheduleReconnect();
  });
}

function disconnected() {
  if (state.connected && state.socket) state.socket.close();
}

function scheduleReconnect() {
  setConnected(false);
  state.attempt += 1;
  const wait = Math.round(state.retry * (0.8 + 0.4 * Math.random()));  // jitter: screens do not reconnect in step
  state.retry = Math.min(state.retry * 2, RETRY_MOST);
  state.reconnectAt = Date.now() + wait;
  clearTimeout(state.timer);
  state.timer = setTimeout(connect, wait);
  updateBanner();
}

function setConnected(on) {
  state.connected = on;
  document.body.classList.toggle("offline", !on);
  $("live").textContent = on ? "live" : "offline";
  $("live").className = `badge ${on ? "on" : "off"}`;
  for (const b of document.querySelectorAll("button.op")) b.disabled = !on;
  updateBanner();
}

function updateBanner() {
  const banner = $("banner");
  banner.hidden = state.connected;
  if (state.connected) return;
  const seconds = Math.max(0, Math.ceil((state.reconnectAt - Date.now()) / 1000));
  $("banner-text").textContent =
    `Disconnected from the board: what you see may be out of date, and the controls are off. ` +
    `Reconnecting${seconds ? ` in ${seconds} s` : " now"} (attempt ${state.attempt}).`;
}

setInterval(() => { if (!state.connected && state.token && state.me) updateBanner(); }, 500);

$("banner-retry").addEventListener("click", () => { state.retry = RETRY_FIRST; connect(); });

// -- polled panels ---------------------------------------------------------------------------------------------

async function poll() {
  if (!state.connected) return;
  try {
    state.social = await api("/api/social");
    drawSocial($("social"), $("social-empty"), state.social, state.colours);
  } catch (error) { /* shown by the banner when the service is gone */ }
  pollInsight();
}

async function pollInsight() {
  try {
    const data = await api("/api/insight");
    renderGoal($("goal"), data);
    renderBehaviors($("behaviors"), data.behaviors);
  } catch (error) { /* as above */ }
}

window.addEventListener("resize", () => {
  draw();
  if (state.social) drawSocial($("social"), $("social-empty"), state.social, state.colours);
});

$("signin-form").addEventListener("submit", (event) => {
  event.preventDefault();
  start($("token").value.trim());
});

$("signout").addEventListener("click", () => {
  sessionStorage.removeItem(TOKEN_KEY);
  location.reload();
});

const initial = tokenFromPage();
if (initial) start(initial); else signIn("");
