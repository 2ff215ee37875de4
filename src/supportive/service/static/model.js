// What the page reads off a board: pure functions over the board's nodes (no DOM). A node is the API's
// {id, name, kind, parent, children, action, lead_only, owner, done, progress, ready, occurrence}.
"use strict";

// Okabe & Ito's palette (Color Universal Design), ordered so that the first six stay apart from each other and
// from the grey of done work under protanopia, deuteranopia and tritanopia (tests/service/test_lab_screen.py
// measures it). Done work is grey with a tick, so no agent's colour doubles as "done"; every claim also
// carries its agent's name, so colour is never the only cue.
export const PALETTE = ["#0072B2", "#E69F00", "#009E73", "#D55E00", "#56B4E9", "#F0E442", "#CC79A7"];

export function indexed(board) {
  return new Map(board.nodes.map((n) => [n.id, n]));
}

export function rootOf(byId) {
  return byId.get("n0");
}

// One colour per agent that can claim (observers only watch), in the board's agent order.
export function agentColours(agents) {
  const colours = new Map();
  agents.filter((a) => a.role !== "observer").forEach((a, i) => colours.set(a.id, PALETTE[i % PALETTE.length]));
  return colours;
}

export function leavesOf(byId, id) {
  const node = byId.get(id);
  if (node.kind === "action") return [node];
  return node.children.flatMap((child) => leavesOf(byId, child));
}

export function ancestorsOf(byId, id) {
  const out = [];
  let parent = byId.get(id).parent;
  while (parent !== null && parent !== undefined) {
    out.push(byId.get(parent));
    parent = byId.get(parent).parent;
  }
  return out;
}

// What must be done before `id` can start: every earlier sibling in every chain above it (as the board says).
export function prerequisitesOf(byId, id) {
  const out = [];
  let current = byId.get(id);
  while (current.parent !== null) {
    const parent = byId.get(current.parent);
    if (parent.kind === "chain") {
      const position = parent.children.indexOf(current.id);
      out.push(...parent.children.slice(0, position).map((c) => byId.get(c)));
    }
    current = parent;
  }
  return out;
}

export function waitingFor(byId, id) {
  return prerequisitesOf(byId, id).filter((n) => !n.done);
}

// The nodes an agent claimed itself (not just inherited from a claimed parent), unfinished, in tree order.
export function claimRoots(byId, agent) {
  return [...byId.values()].filter(
    (n) => n.owner === agent && !n.done && (n.parent === null || byId.get(n.parent).owner !== agent),
  );
}

// An agent's "now": the subtask it claimed, the action it is on (the one under way, else the first it may
// start), what comes after, how far it got, and what it waits for when it cannot start anything.
export function agentNow(byId, agent) {
  const roots = claimRoots(byId, agent);
  if (!roots.length) return { agent, idle: true };
  const root = roots[0];
  const leaves = leavesOf(byId, root.id);
  const open = leaves.filter((l) => !l.done);
  const current = open.find((l) => l.ready && l.progress > 0) || open.find((l) => l.ready) || null;
  const after = current ? open.slice(open.indexOf(current) + 1) : open;
  const next = after.find((l) => l !== current) || open.find((l) => l !== current) || null;
  return {
    agent,
    idle: false,
    root,
    current,
    next: current ? next : null,
    done: leaves.length - open.length,
    total: leaves.length,
    blockedBy: current ? [] : waitingFor(byId, open[0].id),
    more: roots.length - 1,
  };
}

// Actions nobody has claimed that may be started now, in tree order, each with the subtask it belongs to.
export function upNext(byId) {
  return [...byId.values()]
    .filter((n) => n.kind === "action" && !n.done && !n.owner && n.ready)
    .map((n) => ({ node: n, within: n.parent === null ? null : byId.get(n.parent) }));
}

// What cannot go on, and why: claimed work with nothing its owner may start, then subtasks that are next in
// line but wait for an earlier step (shallowest first).
export function blocked(byId) {
  const claimed = [...byId.values()]
    .filter((n) => n.owner && !n.done && (n.parent === null || byId.get(n.parent).owner !== n.owner))
    .filter((n) => !leavesOf(byId, n.id).some((l) => !l.done && l.ready))
    .map((n) => ({ node: n, owner: n.owner, waitsFor: waitingFor(byId, leavesOf(byId, n.id).find((l) => !l.done).id) }));
  const depth = (n) => ancestorsOf(byId, n.id).length;
  const inside = (outer, inner) => inner.id === outer.id || ancestorsOf(byId, inner.id).some((a) => a.id === outer.id);
  const waiting = [...byId.values()]
    .filter((n) => n.kind !== "action" && !n.done && !n.owner && !n.ready && n.parent !== null && byId.get(n.parent).ready)
    .filter((n) => !claimed.some((c) => inside(n, c.node)))
    .sort((a, b) => depth(a) - depth(b))
    .map((n) => ({ node: n, owner: null, waitsFor: waitingFor(byId, n.id) }));
  return [...claimed, ...waiting];
}

// How much of the task is done, and by whom.
export function overall(byId) {
  const leaves = leavesOf(byId, "n0");
  const byAgent = new Map();
  for (const leaf of leaves) {
    if (leaf.done && leaf.owner) byAgent.set(leaf.owner, (byAgent.get(leaf.owner) || 0) + 1);
  }
  return { total: leaves.length, done: leaves.filter((l) => l.done).length, byAgent };
}

// Whether `agent` (with `role`) may claim `id` now, by the board's rules: not done, nobody else owns it, a
// node above or below it, and an assistant never takes what is reserved for leads.
export function claimable(byId, id, agent, role) {
  const node = byId.get(id);
  if (role === "observer" || node.done || node.owner === agent) return false;
  const subtree = [node, ...descendantsOf(byId, id)];
  if (role === "assistant" && subtree.some((n) => n.lead_only)) return false;
  const others = (n) => n.owner && n.owner !== agent && !n.done;
  return !subtree.some(others) && !ancestorsOf(byId, id).some(others);
}

export function descendantsOf(byId, id) {
  return byId.get(id).children.flatMap((child) => [byId.get(child), ...descendantsOf(byId, child)]);
}

// A subtask is "current" when work in it is under way or may start now: it stays open on the screen.
export function isCurrent(byId, id) {
  const node = byId.get(id);
  if (node.done) return false;
  return leavesOf(byId, id).some((l) => !l.done && (l.ready || l.owner || l.progress > 0));
}
