// The panels around the tree: the legend and overall progress, each agent's "now", what is next and what is
// blocked, the goal-inference belief, the social-force view of the workbench and the suggested behaviors.
"use strict";

import { agentNow, blocked, overall, upNext } from "./model.js";
import { el } from "./tree.js";

const SHOWN = 4;
const MISTAKES_SHOWN = 2;  // the newest mistakes the goal view lists
const OFF_SCRIPT = 0.5;
const MAX_TABLE_HEIGHT = 190;  // px: the social view leaves the goal view its room
const NEGLIGIBLE = 0.005;  // belief entries below this (but the first) are left out  // a numeric `surprise` at or above this flags the step as off-script

export function renderLegend(target, agents, colours) {
  target.replaceChildren(...agents.filter((a) => colours.has(a.id)).map((a) => {
    const item = el("li", "legend-item");
    item.dataset.testid = `legend-${a.id}`;
    item.style.setProperty("--agent", colours.get(a.id));
    item.append(el("span", "swatch"), el("span", "who", a.id), el("span", "what", `${a.kind}, ${a.role}`));
    return item;
  }));
}

export function renderOverall(target, byId, colours) {
  const { total, done, byAgent } = overall(byId);
  const bar = el("div", "stacked");
  for (const [agent, count] of byAgent) {
    const part = el("i");
    part.style.width = `${(100 * count) / total}%`;
    part.style.background = colours.get(agent) || "#777";
    part.title = `${agent}: ${count}`;
    bar.append(part);
  }
  const percent = total ? Math.round((100 * done) / total) : 0;
  const label = el("span", "overall-label", `${done} of ${total} steps done · ${percent} %`);
  label.dataset.testid = "overall-label";
  target.replaceChildren(bar, label);
}

export function renderNow(target, byId, agents, colours) {
  const cards = agents.filter((a) => colours.has(a.id)).map((a) => {
    const now = agentNow(byId, a.id);
    const card = el("article", "agent-card");
    card.dataset.testid = `now-${a.id}`;
    card.style.setProperty("--agent", colours.get(a.id));
    const head = el("header");
    head.append(el("span", "swatch"), el("span", "agent-name", a.id), el("span", "role", `${a.kind} ${a.role}`));
    card.append(head);
    if (now.idle) {
      card.classList.add("idle");
      card.append(line("doing", "no subtask claimed", `now-${a.id}-doing`));
      return card;
    }
    const count = el("span", "card-count", `${now.done}/${now.total} steps`);
    count.dataset.testid = `now-${a.id}-count`;
    head.append(count);
    card.append(line("doing", now.current ? now.current.name : now.root.name, `now-${a.id}-doing`));
    const within = now.current && now.current.id !== now.root.id ? `in ${now.root.name}` : "";
    const more = now.more ? `+${now.more} more claimed` : "";
    if (within || more) card.append(line("within", [within, more].filter(Boolean).join(" · ")));
    const bar = el("div", "bar");
    const fill = el("i");
    fill.style.width = `${(100 * now.done) / now.total}%`;
    bar.append(fill);
    card.append(bar);
    if (now.blockedBy.length) {
      card.classList.add("waiting");
      card.append(line("then blocked-why", `waiting for ${names(now.blockedBy)}`, `now-${a.id}-next`));
    } else if (now.next) {
      card.append(line("then", `then: ${now.next.name}`, `now-${a.id}-next`));
    } else {
      card.append(line("then", "then: this subtask is finished", `now-${a.id}-next`));
    }
    return card;
  });
  target.replaceChildren(...cards);
}

export function renderQueue(nextTarget, blockedTarget, byId) {
  const next = upNext(byId);
  nextTarget.replaceChildren(...listed(next, (item) => {
    const li = el("li");
    li.dataset.node = item.node.id;
    li.append(el("span", "what", item.node.name));
    if (item.within) li.append(el("span", "where", ` in ${item.within.name}`));
    return li;
  }, byId.get("n0").done ? "The task is done." : "Nothing free can start now."));
  const stuck = blocked(byId);
  blockedTarget.replaceChildren(...listed(stuck, (item) => {
    const li = el("li");
    li.dataset.node = item.node.id;
    if (item.owner) li.classList.add("claimed");
    li.append(el("span", "what", item.owner ? `${item.node.name} (${item.owner})` : item.node.name));
    li.append(el("span", "where", ` waits for ${names(item.waitsFor)}`));
    return li;
  }, "Nothing is blocked."));
}

function listed(items, make, empty) {
  if (!items.length) return [el("li", "muted", empty)];
  const shown = items.slice(0, items.length > SHOWN ? SHOWN - 1 : SHOWN).map(make);
  if (items.length > SHOWN) shown.push(el("li", "muted", `+${items.length - SHOWN + 1} more`));
  return shown;
}

function names(nodes) {
  const shown = nodes.slice(0, 2).map((n) => n.name);
  return shown.join(" and ") + (nodes.length > 2 ? ` (+${nodes.length - 2})` : "");
}

function line(cls, text, testid) {
  const div = el("div", cls, text);
  if (testid) div.dataset.testid = testid;
  return div;
}

// -- goal inference ----------------------------------------------------------------------------------------

export function renderGoal(target, data) {
  const goal = data.goal || (data.belief ? { current: data.belief.map((b) => ({ text: b.name, probability: b.probability })) } : null);
  if (!goal) {
    const text = data.inference
      ? "Goal inference is on: waiting for the first contact events."
      : "This task has no goal inference (its actions declare no contact events, or it has no demonstrations).";
    target.replaceChildren(el("p", "muted", text));
    target.dataset.state = data.inference ? "waiting" : "off";
    return;
  }
  target.dataset.state = "belief";
  const parts = [];
  if (goal.step !== undefined && goal.step !== null) parts.push(el("p", "goal-step", `after ${goal.step} observation${goal.step === 1 ? "" : "s"}`));
  if (offScript(goal)) {
    const flag = el("p", "off-script", `⚠ Off script: the latest step does not fit the task as taught${surpriseText(goal.surprise)}`);
    flag.dataset.testid = "off-script";
    parts.push(flag);
  }
  if (data.mistakes && data.mistakes.length) parts.push(mistakeList(data.mistakes));
  if (goal.recent && goal.recent.some((step) => step.off_script)) {
    const list = el("ol", "recent");
    list.dataset.testid = "goal-recent";
    for (const step of goal.recent) {
      const li = el("li", step.off_script ? "flagged" : "", `${step.off_script ? "⚠ " : ""}${step.text}`);
      list.append(li);
    }
    parts.push(list);
  }
  parts.push(...bars("Likely subtask", goal.subtasks, "goal-subtask", 2));
  parts.push(...bars("Doing now", goal.current, "goal-current", 3));
  parts.push(...bars("Next", goal.next, "goal-next", 3));
  target.replaceChildren(...parts);
}

// The newest mistakes noticed: when each was raised, its kind, and what the robot says and offers to do.
function mistakeList(mistakes) {
  const list = el("ol", "mistakes");
  list.dataset.testid = "mistakes";
  for (const mistake of mistakes.slice(0, MISTAKES_SHOWN)) {
    const li = el("li", "mistake");
    li.dataset.testid = "mistake";
    li.dataset.kind = mistake.kind || "";
    li.dataset.nodes = (mistake.nodes || []).join(" ");
    const when = new Date(1000 * Number(mistake.raised)).toLocaleTimeString([], { hour12: false });
    li.append(el("span", "when", when), el("span", "kind", mistake.kind || "mistake"));
    const say = mistake.help ? mistake.help.say : `${mistake.text}: a mistake`;
    li.append(el("span", "say", say));
    list.append(li);
  }
  return list;
}

function offScript(goal) {
  if (typeof goal.off_script === "boolean") return goal.off_script;
  if (typeof goal.surprise === "boolean") return goal.surprise;
  return typeof goal.surprise === "number" && goal.surprise >= OFF_SCRIPT;
}

function surpriseText(surprise) {
  return typeof surprise === "number" ? ` (surprise ${surprise.toFixed(2)})` : "";
}

function bars(title, entries, testid, most) {
  entries = (entries || []).filter((e, i) => i === 0 || Number(e.probability) >= NEGLIGIBLE).slice(0, most);
  if (!entries.length) return [];
  const list = el("ul", "bars");
  list.dataset.testid = testid;
  for (const entry of entries) {
    const p = Number(entry.probability) || 0;
    const li = el("li");
    li.dataset.probability = String(p);
    const bar = el("span", "bar");
    const fill = el("i");
    fill.style.width = `${Math.round(100 * p)}%`;
    bar.append(fill);
    li.append(el("span", "label", entry.text || entry.name || entry.action || "?"), bar, el("span", "pct", percent(p)));
    list.append(li);
  }
  return [el("h3", "", title), list];
}

function percent(p) {
  if (p > 0 && p < 0.01) return "<1 %";
  return `${Math.round(100 * p)} %`;
}

export function renderBehaviors(target, behaviors) {
  target.replaceChildren(...(behaviors || []).map((b) => {
    const li = el("li");
    li.append(el("span", "what", b.text), el("span", "where", b.category));
    return li;
  }));
  if (!target.children.length) target.append(el("li", "muted", "None right now."));
}

// -- social force --------------------------------------------------------------------------------------------

// The workbench from above, to scale (one scale for x and y), with the table's outline, a 10 cm grid, a
// scale bar, the combined force, and each agent's hand and ellipse in its colour.
export function drawSocial(canvas, empty, data, colours) {
  const [width, depth] = data.workspace;
  const box = canvas.parentElement.getBoundingClientRect();
  const margin = 24;
  const scale = Math.min((box.width - 2 * margin) / width, MAX_TABLE_HEIGHT / depth);
  const cssW = Math.round(width * scale + 2 * margin), cssH = Math.round(depth * scale + 2 * margin);
  const ratio = window.devicePixelRatio || 1;
  canvas.style.width = `${cssW}px`;
  canvas.style.height = `${cssH}px`;
  canvas.width = Math.round(cssW * ratio);
  canvas.height = Math.round(cssH * ratio);
  canvas.dataset.scale = String(scale);
  canvas.dataset.margin = String(margin);
  const ctx = canvas.getContext("2d");
  ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
  const X = (x) => margin + x * scale, Y = (y) => margin + (depth - y) * scale;
  ctx.fillStyle = "#ffffff";
  ctx.fillRect(X(0), Y(depth), width * scale, depth * scale);
  const { values, nx, ny } = data.field;
  for (let j = 0; j < ny; j++) for (let i = 0; i < nx; i++) {
    const v = values[j * nx + i];
    if (v <= 0) continue;
    ctx.fillStyle = `rgba(60, 60, 60, ${Math.min(0.45, 0.45 * v)})`;
    ctx.fillRect(X((i * width) / nx), Y(((j + 1) * depth) / ny), (width / nx) * scale + 0.5, (depth / ny) * scale + 0.5);
  }
  ctx.strokeStyle = "#e3e6e8";
  ctx.lineWidth = 1;
  for (let x = 0.1; x < width; x += 0.1) line2(ctx, X(x), Y(0), X(x), Y(depth));
  for (let y = 0.1; y < depth; y += 0.1) line2(ctx, X(0), Y(y), X(width), Y(y));
  ctx.strokeStyle = "#263238";
  ctx.lineWidth = 3;
  ctx.strokeRect(X(0), Y(depth), width * scale, depth * scale);
  ctx.fillStyle = "#263238";
  const rem = parseFloat(getComputedStyle(document.documentElement).fontSize);
  ctx.font = `${Math.round(0.75 * rem)}px system-ui, sans-serif`;
  ctx.textBaseline = "top";
  line2(ctx, X(0), Y(0) + 12, X(0.5), Y(0) + 12, 3);
  ctx.fillText("50 cm", X(0.5) + 6, Y(0) + 4);
  ctx.textBaseline = "bottom";
  ctx.fillText(`table ${width.toFixed(2)} m × ${depth.toFixed(2)} m`, X(0), Y(depth) - 4);
  const withHands = data.agents.filter((a) => a.hand);
  empty.hidden = withHands.length > 0;
  for (const agent of withHands) {
    const colour = colours.get(agent.id) || "#555";
    ctx.strokeStyle = colour;
    ctx.fillStyle = colour;
    if (agent.ellipse) {
      const e = agent.ellipse;
      ctx.lineWidth = 4;
      ctx.beginPath();
      ctx.ellipse(X(e.center[0]), Y(e.center[1]), Math.max(1, e.half_axes[0] * scale), Math.max(1, e.half_axes[1] * scale), -e.angle, 0, 2 * Math.PI);
      ctx.stroke();
    }
    const [x, y] = agent.hand;
    ctx.beginPath();
    ctx.arc(X(x), Y(y), 11, 0, 2 * Math.PI);
    ctx.fill();
    ctx.font = `bold ${Math.round(0.95 * rem)}px system-ui, sans-serif`;
    ctx.textBaseline = "middle";
    ctx.fillStyle = "#111";
    ctx.fillText(agent.id, X(x) + 16, Y(y));
  }
}

function line2(ctx, x0, y0, x1, y1, width) {
  if (width) ctx.lineWidth = width;
  ctx.beginPath();
  ctx.moveTo(x0, y0);
  ctx.lineTo(x1, y1);
  ctx.stroke();
}
