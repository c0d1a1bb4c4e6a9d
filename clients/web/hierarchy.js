// hierarchy.js: levels of the bisection tree of a result document
// (doc.hierarchy.nodes, node 0 the root).  Level d cuts the tree at depth d:
// every node of depth d, and every leaf above it, is one part.  Parts are
// coloured like the final segment they mostly became, so moving the level
// keeps colours steady.

import { segmentRgb } from './colours.js';

// Depth of every node (Int32Array #nodes) and the largest depth.
export function nodeDepths(nodes) {
  const depth = new Int32Array(nodes.length);
  let max = 0;
  for (const node of nodes) {
    let d = 0;
    for (let up = node.parent; up >= 0; up = nodes[up].parent) d++;
    depth[node.id] = d;
    max = Math.max(max, d);
  }
  return { depth, max };
}

// The nodes forming the cut at `level` (array of node objects).
export function cutAt(nodes, depth, level) {
  return nodes.filter((n) => depth[n.id] === level || (depth[n.id] < level && n.children.length === 0));
}

// Colour per supernode (Uint8Array #S*3) at `level`, and the part count.
export function levelTable(doc, depth, level) {
  const parts = cutAt(doc.hierarchy.nodes, depth, level);
  const table = new Uint8Array(3 * Math.max(doc.supernodes.length, 1));
  const used = new Set();
  let spare = doc.n_segments;
  for (const part of parts) {
    let colour = Math.min(...part.supernodes.map((s) => doc.supernodes[s].segment));
    if (used.has(colour)) colour = spare++;
    used.add(colour);
    const rgb = segmentRgb(colour);
    for (const s of part.supernodes) table.set(rgb, 3 * s);
  }
  return { table, parts: parts.length };
}

// The final segment holding tree node `nodeId` (via its first supernode).
export function segmentOfNode(doc, nodeId) {
  const node = doc.hierarchy.nodes[nodeId];
  return node && node.supernodes.length ? doc.supernodes[node.supernodes[0]].segment : -1;
}
