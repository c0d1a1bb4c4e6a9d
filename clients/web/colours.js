// colours.js: per-point colours as Uint8Array #P*3 (0..255 RGB) for the
// three ways of looking at a result: final segments, a level of the
// bisection tree, and the centrality ramp; plus the legend's palette.

const BASE = [
  '#4e79a7', '#f28e2b', '#59a14f', '#e15759', '#76b7b2', '#edc948', '#b07aa1', '#ff9da7',
  '#9c755f', '#86bcb6', '#d4a6c8', '#8cd17d', '#a0cbe8', '#ffbe7d', '#f1ce63', '#499894',
  '#d37295', '#b6992d', '#79706e', '#fabfd2',
];

function hexToRgb(hex) {
  const v = parseInt(hex.slice(1), 16);
  return [(v >> 16) & 255, (v >> 8) & 255, v & 255];
}

function hslToRgb(h, s, l) {
  const f = (n) => {
    const k = (n + h * 12) % 12;
    const a = s * Math.min(l, 1 - l);
    return Math.round(255 * (l - a * Math.max(-1, Math.min(k - 3, 9 - k, 1))));
  };
  return [f(0), f(8), f(4)];
}

// Colour of segment id (distinct for the first 20, golden-angle hues after).
export function segmentRgb(id) {
  if (id < BASE.length) return hexToRgb(BASE[id]);
  return hslToRgb(((id * 0.618033988749895) % 1 + 1) % 1, 0.55, 0.55);
}

export function rgbCss([r, g, b]) {
  return `rgb(${r}, ${g}, ${b})`;
}

// table: Uint8Array #T*3 of colours; index: per-point Int32Array (or any
// array-like) into table.  highlight: a label to keep bright (others are
// greyed) or -1; labels: the per-point segment labels it refers to.
export function paint(out, index, table, labels, highlight) {
  const n = index.length;
  for (let i = 0; i < n; i++) {
    const t = 3 * index[i];
    if (highlight >= 0 && labels[i] !== highlight) {
      out[3 * i] = 60 + (table[t] >> 3);
      out[3 * i + 1] = 60 + (table[t + 1] >> 3);
      out[3 * i + 2] = 64 + (table[t + 2] >> 3);
    } else {
      out[3 * i] = table[t];
      out[3 * i + 1] = table[t + 1];
      out[3 * i + 2] = table[t + 2];
    }
  }
}

// Colour table of segments 0..count-1 (Uint8Array #count*3).
export function segmentTable(count) {
  const t = new Uint8Array(3 * Math.max(count, 1));
  for (let s = 0; s < count; s++) t.set(segmentRgb(s), 3 * s);
  return t;
}

const RAMP = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];

// The centrality ramp (viridis-like), 256 entries.
export function rampTable() {
  const t = new Uint8Array(3 * 256);
  for (let i = 0; i < 256; i++) {
    const x = (i / 255) * (RAMP.length - 1);
    const k = Math.min(Math.floor(x), RAMP.length - 2);
    const w = x - k;
    for (let c = 0; c < 3; c++) t[3 * i + c] = Math.round(RAMP[k][c] * (1 - w) + RAMP[k + 1][c] * w);
  }
  return t;
}

export function rampCss() {
  return `linear-gradient(to right, ${RAMP.map(rgbCss).join(', ')})`;
}

// Per-point ramp index 0..255 of f (Uint8Array #P).
export function rampIndex(f) {
  let lo = Infinity, hi = -Infinity;
  for (const v of f) {
    if (v < lo) lo = v;
    if (v > hi) hi = v;
  }
  const scale = hi > lo ? 255 / (hi - lo) : 0;
  const out = new Uint8Array(f.length);
  for (let i = 0; i < f.length; i++) out[i] = Math.round((f[i] - lo) * scale);
  return { index: out, lo, hi };
}
