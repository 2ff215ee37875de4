// The task board page: no build step. Reads the board over HTTP, follows it over a WebSocket, and lets the
// signed-in agent claim, release and complete subtasks.
"use strict";

const state = { token: null, me: null, board: null, version: -1, socket: null, retry: 500 };

function tokenFromPage() {
  const hash = new URLSearchParams(location.hash.slice(1));
  return hash.get("token") || sessionStorage.getItem("supportive-token");
}

async function api(path, options = {}) {
  const response = await fetch(path, {
    ...options,
    headers: { "Authorization": `Bearer ${state.token}`, "Content-Type": "application/json", ...(options.headers || {}) },
  });
  const body = await response.json().catch(() => ({}));
  const detail = Array.isArray(body.detail) ? body.detail.map((item) => item.msg).join("; ") : body.detail;
  if (!response.ok) throw new Error(detail || `${response.status} ${response.statusText}`);
  return body;
}

function show(board) {
  if (!board || board.version < state.version) return;  // an older message arriving late
  state.board = board;
  state.version = board.version;
  document.getElementById("task").textContent = board.task;
  document.getElementById("version").textContent = `version ${board.version}`;
  const byId = new Map(board.nodes.map((n) => [n.id, n]));
  const tree = document.getElementById("tree");
  tree.replaceChildren(render(byId.get("n0"), byId));
}

function render(node, byId) {
  const li = document.createElement("li");
  li.className = "node";
  li.dataset.node = node.id;
  li.dataset.testid = `node-${node.id}`;
  if (node.done) li.classList.add("done");
  else if (node.owner && state.me && node.owner === state.me.id) li.classList.add("mine");
  else if (node.owner) li.classList.add("other");
  const row = document.createElement("div");
  row.className = "row";
  row.append(span("kind", node.kind), span("name", node.name));
  if (node.lead_only) row.append(span("lead-only", "lead only"));
  const status = node.done ? "done" : node.owner ? `claimed by ${node.owner}` : node.ready ? "free" : "waiting";
  const statusEl = span("status", status);
  statusEl.dataset.testid = `status-${node.id}`;
  row.append(statusEl);
  if (node.kind === "action" && !node.done) {
    const bar = document.createElement("progress");
    bar.max = 1; bar.value = node.progress; row.append(bar);
  }
  if (state.me && state.me.role !== "observer" && !node.done) {
    if (!node.owner) row.append(button("claim", node));
    if (node.owner === state.me.id) {
      row.append(button("release", node));
      if (node.kind === "action" && node.ready) row.append(button("complete", node));
    }
  }
  li.append(row);
  if (node.children.length) {
    const ul = document.createElement("ul");
    for (const child of node.children) ul.append(render(byId.get(child), byId));
    li.append(ul);
  }
  return li;
}

function span(cls, text) {
  const el = document.createElement("span");
  el.className = cls;
  el.textContent = text;
  return el;
}

function button(op, node) {
  const el = document.createElement("button");
  el.textContent = op;
  el.dataset.testid = `${op}-${node.id}`;
  el.addEventListener("click", async () => {
    try {
      const result = await api(`/api/nodes/${node.id}/${op}`, { method: "POST" });
      message("");
      show(result.board);
    } catch (error) {
      message(error.message);
    }
  });
  return el;
}

function message(text) {
  document.getElementById("message").textContent = text;
}

function connect() {
  const scheme = location.protocol === "https:" ? "wss" : "ws";
  const socket = new WebSocket(`${scheme}://${location.host}/api/ws?token=${encodeURIComponent(state.token)}`);
  state.socket = socket;
  const live = document.getElementById("live");
  socket.addEventListener("open", () => { live.textContent = "live"; live.className = "badge on"; state.retry = 500; });
  socket.addEventListener("message", (event) => {
    const data = JSON.parse(event.data);
    if (data.board) show(data.board);
  });
  socket.addEventListener("close", (event) => {
    live.textContent = "offline"; live.className = "badge off";
    if (event.code === 4401) return signIn("that token is not known here");
    setTimeout(connect, state.retry);
    state.retry = Math.min(state.retry * 2, 8000);
  });
}

async function poll() {
  for (const panel of ["social", "insight"]) {
    try {
      const data = await api(`/api/${panel}`);
      if (panel === "social") drawSocial(data); else showInsight(data);
    } catch (error) { /* the panel is optional */ }
  }
}

function drawSocial(data) {
  const canvas = document.getElementById("social");
  const ctx = canvas.getContext("2d");
  const [w, h] = data.workspace;
  const sx = canvas.width / w, sy = canvas.height / h;
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  if (data.field) {
    const { values, nx, ny } = data.field;
    for (let j = 0; j < ny; j++) for (let i = 0; i < nx; i++) {
      const v = values[j * nx + i];
      if (v <= 0) continue;
      ctx.fillStyle = `rgba(21, 101, 192, ${Math.min(1, v)})`;
      ctx.fillRect(i * canvas.width / nx, canvas.height - (j + 1) * canvas.height / ny, canvas.width / nx + 1, canvas.height / ny + 1);
    }
  }
  for (const agent of data.agents) {
    if (!agent.hand) continue;
    const [x, y] = agent.hand;
    ctx.fillStyle = agent.kind === "robot" ? "#37474f" : "#c62828";
    ctx.fillRect(x * sx - 4, canvas.height - y * sy - 4, 8, 8);
    ctx.fillText(agent.id, x * sx + 6, canvas.height - y * sy - 6);
    if (agent.ellipse) {
      const e = agent.ellipse;
      ctx.strokeStyle = ctx.fillStyle;
      ctx.beginPath();
      ctx.ellipse(e.center[0] * sx, canvas.height - e.center[1] * sy, e.half_axes[0] * sx, e.half_axes[1] * sy, -e.angle, 0, 2 * Math.PI);
      ctx.stroke();
    }
  }
}

function showInsight(data) {
  const belief = document.getElementById("belief");
  if (data.belief) {
    belief.replaceChildren(...data.belief.map((b) => span("belief", `${b.name}: ${(100 * b.probability).toFixed(0)} %`)).flatMap((el) => [el, document.createElement("br")]));
  }
  const behaviors = document.getElementById("behaviors");
  behaviors.replaceChildren(...(data.behaviors || []).map((b) => {
    const p = document.createElement("p");
    p.textContent = `Suggested: ${b.text} (${b.category})`;
    return p;
  }));
}

function signIn(problem) {
  document.getElementById("signin").hidden = false;
  document.getElementById("signin-error").textContent = problem || "";
}

async function start(token) {
  state.token = token;
  try {
    state.me = await api("/api/me");
  } catch (error) {
    return signIn(error.message);
  }
  sessionStorage.setItem("supportive-token", token);
  document.getElementById("signin").hidden = true;
  document.getElementById("me").textContent = `${state.me.id} (${state.me.kind}, ${state.me.role})`;
  show(await api("/api/board"));
  connect();
  poll();
  setInterval(poll, 1000);
}

document.getElementById("signin-form").addEventListener("submit", (event) => {
  event.preventDefault();
  start(document.getElementById("token").value.trim());
});

const initial = tokenFromPage();
if (initial) start(initial); else signIn("");
