// The task tree as nested boxes: the top level left to right, chains numbered in order, cliques marked "any
// order" with their children side by side, done subtrees folded to one line. `fitTree` shrinks the type and
// folds subtasks that are not under way until the tree fits its panel.
"use strict";

import { isCurrent, leavesOf, rootOf } from "./model.js";

const STEP_ARROW = "→";

// Options: colours (agent -> colour), controls(node) -> [buttons] or [], folded (Set of ids to fold beyond
// the done ones), opened (Set of ids the viewer unfolded), onToggle(id).
export function renderTree(byId, options) {
  const box = renderNode(byId, rootOf(byId), null, options);
  box.classList.add("tree-root");
  return box;
}

function renderNode(byId, node, position, options) {
  const box = el("div", `node kind-${node.kind}`);
  box.dataset.node = node.id;
  box.dataset.testid = `node-${node.id}`;
  decorate(box, node, options);
  box.append(header(byId, node, position, options));
  if (node.kind === "action") {
    if (!node.done && node.progress > 0) {
      const bar = el("div", "progress");
      const fill = el("i");
      fill.style.width = `${Math.round(100 * node.progress)}%`;
      bar.append(fill);
      box.append(bar);
    }
    return box;
  }
  if (isFolded(byId, node, options)) {
    box.classList.add("folded");
    return box;
  }
  // A chain of subtasks reads left to right, in columns (numbered, with arrows); a chain of actions top to
  // bottom (numbered); a clique's children sit side by side where there is room, under "any order".
  const across = isAcross(byId, node, options);
  const body = el("div", `body ${node.kind}${across ? " across" : ""}`);
  node.children.forEach((childId, i) => {
    const child = byId.get(childId);
    if (across && i) body.append(el("div", "arrow", STEP_ARROW));
    const part = renderNode(byId, child, node.kind === "chain" ? i + 1 : null, options);
    if (across) part.style.flexGrow = String(options.byLeaves ? openLeaves(byId, child, options) : columns(byId, child, options));
    body.append(part);
  });
  box.append(body);
  return box;
}

function isAcross(byId, node, options) {
  return node.kind === "chain" && !isFolded(byId, node, options) && node.children.every((c) => byId.get(c).kind !== "action");
}

// A part's unfinished actions (a folded part needs one line).
function openLeaves(byId, node, options) {
  if (isFolded(byId, node, options)) return 1;
  return Math.max(1, leavesOf(byId, node.id).filter((l) => !l.done).length);
}

// How many columns a part spreads over: a chain of subtasks, its parts' columns side by side; a clique of
// three or more open subtasks, two when `wideCliques` (its children two by two); anything else, one.
function columns(byId, node, options) {
  if (isAcross(byId, node, options)) return node.children.reduce((sum, c) => sum + columns(byId, byId.get(c), options), 0);
  if (!options.wideCliques) return 1;
  const open = node.children.filter((c) => byId.get(c).kind !== "action" && !isFolded(byId, byId.get(c), options));
  return node.kind === "clique" && !isFolded(byId, node, options) && open.length >= 3 ? 2 : 1;
}

function isFolded(byId, node, options) {
  if (options.opened.has(node.id)) return false;
  return node.done || (options.folded.has(node.id) && !isCurrent(byId, node.id));
}

function decorate(box, node, options) {
  if (node.done) box.classList.add("done");
  if (node.owner) {
    box.classList.add("owned");
    box.style.setProperty("--owner", options.colours.get(node.owner) || "#555");
    box.dataset.owner = node.owner;
  }
  box.dataset.status = status(node);
}

export function status(node) {
  if (node.done) return "done";
  if (node.owner) return "claimed";
  return node.ready ? "free" : "waiting";
}

function statusText(node) {
  if (node.done) return "";
  if (node.owner) return node.ready ? "▶ now" : "";
  return node.ready ? "free" : "";
}

function header(byId, node, position, options) {
  const row = el("div", "head");
  if (node.kind !== "action" && !node.done) {
    row.addEventListener("click", () => options.onToggle(node.id));
    row.classList.add("toggles");
  }
  if (position !== null) row.append(el("span", "step", String(position)));
  row.append(el("span", "name", node.name));
  if (node.kind === "clique") row.append(el("span", "chip any", "any order"));
  if (node.kind === "chain" && node.children.length > 1 && node.parent === null) row.append(el("span", "chip order", "in order"));
  if (node.lead_only) row.append(el("span", "chip lead", "lead only"));
  if (node.kind !== "action") {
    const leaves = leavesOf(byId, node.id);
    const done = leaves.filter((l) => l.done).length;
    row.append(el("span", "count", `${done}/${leaves.length}`));
  }
  if (node.owner && !(node.parent !== null && byId.get(node.parent).owner === node.owner)) {
    const pill = el("span", "owner", node.owner);
    pill.dataset.testid = `owner-${node.id}`;
    row.append(pill);
  }
  const state = el("span", "status", statusText(node));
  state.dataset.testid = `status-${node.id}`;
  row.append(state);
  row.append(...options.controls(node));
  return row;
}

// The largest type at which the tree fits its panel. Three ways to share the width among a chain's parts
// are tried (by their columns, with cliques of three or more subtasks two columns wide, or by their
// unfinished actions), each with the largest scale that fits (bisection); if none fits at SMALLEST, every
// subtask not under way is folded (deepest first) and the search runs again. `draw(layout)` renders with
// {folded, wideCliques, byLeaves}. Returns the layout it settled on (drawn).
const LARGEST = 1, SMALLEST = 0.62, STEPS = 6;

export function fitTree(container, draw, foldable) {
  const overflows = () => container.scrollHeight > container.clientHeight + 1 || container.scrollWidth > container.clientWidth + 1;
  const fits = (layout) => {
    container.style.setProperty("--fit", String(layout.scale));
    draw(layout);
    return !overflows();
  };
  const shares = [{ wideCliques: false, byLeaves: false }, { wideCliques: true, byLeaves: false }, { wideCliques: false, byLeaves: true }];
  let best = null;
  for (const folded of [new Set(), new Set(foldable)]) {
    for (const share of shares) {
      const at = (scale) => ({ ...share, folded, scale });
      if (fits(at(LARGEST))) { best = at(LARGEST); break; }
      if (!fits(at(SMALLEST))) continue;
      let low = SMALLEST, high = LARGEST;
      for (let i = 0; i < STEPS; i++) {
        const mid = (low + high) / 2;
        if (fits(at(mid))) low = mid; else high = mid;
      }
      if (!best || low > best.scale) best = at(low);
    }
    if (best) break;
  }
  best = best || { wideCliques: false, byLeaves: false, folded: new Set(foldable), scale: SMALLEST };
  fits(best);
  return best;
}

export function el(tag, cls, text) {
  const node = document.createElement(tag);
  if (cls) node.className = cls;
  if (text !== undefined) node.textContent = text;
  return node;
}
