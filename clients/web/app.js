// app.js: the viewer page's controller.  Reads the chosen file (in a
// worker: read_file.js) or makes a synthetic example, posts it to /jobs,
// follows the job, then shows the result: colours by segment, by a level
// of the hierarchy or by centrality, the legend, merges, sinks and
// downloads.  Hovering a point in the 3D view, or hovering or focusing
// (Tab) a legend row, lights that segment.  Its state is exposed as
// window.pointseg for scripted checks (tests/browser/viewer.test.mjs).

import { JobCancelled, fetchParamSpecs, submitJob, waitForJob } from './api.js';
import { paint, rampCss, rampIndex, rampTable, segmentTable } from './colours.js';
import { colouredPlyBlob, jsonBlob, labelsBlob, pointsPlyBlob, saveBlob } from './downloads.js';
import { levelTable, nodeDepths } from './hierarchy.js';
import { buildParamsForm, fillLegend, fillMerges, markLegendRow, segmentSize } from './panels.js';
import { ReadCancelled, readPointFile } from './read_file.js';
import { makeDumbbell, makeHand } from './shapes.js';

const $ = (id) => document.getElementById(id);

const state = {
  input: null,      // {name, blob, gzip, count, positions, faces}; blob as chosen (gzip when gzip)
  doc: null,        // the result document
  text: '',         // ... as the server sent it
  depth: null,      // {depth: Int32Array, max} of the hierarchy
  level: 0,         // 0..depth.max = a tree level; depth.max + 1 = final segments
  highlight: -1,    // hovered segment
  hoverPoint: -1,   // the point under the cursor in the 3D view
  job: null,        // {cancelled} of the job the page follows; a new run replaces it
  reading: null,    // {promise, cancel} of the file being read; a new file replaces it
  viewer: null,
  params: null,
  ramp: null,       // {index, lo, hi} of centrality
};

function setState(name) {
  document.body.dataset.state = name;
}

function showError(err) {
  const box = $('error');
  box.replaceChildren();
  const title = document.createElement('strong');
  title.textContent = err.title || 'Error';
  const detail = document.createElement('span');
  detail.textContent = err.title ? err.detail || '' : err.message;
  // A busy or draining service says when to come back (429, 503).
  if (err.retryAfter != null) detail.textContent += ` (try again in ${Math.max(1, Math.ceil(err.retryAfter))} s)`;
  box.append(title, detail);
  box.hidden = false;
  box.scrollIntoView({ block: 'nearest' });
  setState('error');
}

function clearError() {
  $('error').hidden = true;
}

// A cancel the user asked for: said where the progress goes, no error.
function showCancelled(message) {
  $('progress').hidden = false;
  $('progress').className = 'ended';
  $('phase').textContent = message;
  $('percent').textContent = '';
  setState('cancelled');
}

// ---- colours ---------------------------------------------------------------

function finalLevel() {
  return state.depth.max + 1;
}

// The per-point index and colour table of the current view.
function colourSource() {
  const doc = state.doc;
  if ($('show-centrality').checked && state.ramp) return { index: state.ramp.index, table: rampTable() };
  if (state.level >= finalLevel() || !doc.point_supernode)
    return { index: doc.labels, table: segmentTable(doc.n_segments) };
  return { index: doc.point_supernode, table: levelTable(doc, state.depth.depth, state.level).table };
}

function repaint() {
  const viewer = state.viewer;
  if (!viewer || !viewer.colors || !state.doc) return;
  const { index, table } = colourSource();
  paint(viewer.colors, index, table, state.doc.labels, state.highlight);
  viewer.colorsChanged();
  const sinks = state.doc.supernodes.map((s) => s.sink);
  const rgb = new Uint8Array(3 * sinks.length);
  sinks.forEach((p, i) => rgb.set(viewer.colors.subarray(3 * p, 3 * p + 3), 3 * i));
  viewer.setSinks(sinks, rgb, $('show-sinks').checked);
}

function updateLevelLabel() {
  const label = $('level-label');
  if (state.level >= finalLevel()) {
    label.textContent = `final: ${state.doc.n_segments} segments`;
    return;
  }
  const { parts } = levelTable(state.doc, state.depth.depth, state.level);
  label.textContent = `level ${state.level}: ${parts} part${parts === 1 ? '' : 's'}`;
}

// ---- hovering ---------------------------------------------------------------

// Lights segment id (-1: none), from the legend or from point `point` in
// the 3D view: greys the others, marks its legend row and names it over
// the view.
function setHighlight(id, point = -1) {
  state.hoverPoint = point;
  const seg = id >= 0 && state.doc ? state.doc.segments.find((s) => s.id === id) : null;
  const info = $('hover-info');
  info.hidden = !seg;
  if (seg) info.textContent = `segment #${id}: ${segmentSize(seg, state.doc.n_points, ' points')}` +
    (point >= 0 ? ` · point ${point}` : '');
  if (id === state.highlight) return;
  state.highlight = id;
  const row = markLegendRow($('legend').querySelector('tbody'), id);
  if (row && point >= 0) row.scrollIntoView({ block: 'nearest' });
  repaint();
}

// Picks the point under the cursor once per animation frame while it moves
// over the canvas (not while dragging: that orbits); leaving clears.
function wireCanvasHover(viewer) {
  const canvas = viewer.renderer.domElement;
  let at = null, queued = false;
  const pickNow = () => {
    queued = false;
    if (!at || !state.doc) return;
    const point = viewer.pick(at.x, at.y);
    setHighlight(point >= 0 ? state.doc.labels[point] : -1, point);
  };
  canvas.addEventListener('pointermove', (e) => {
    if (e.buttons) return;
    const box = canvas.getBoundingClientRect();
    at = { x: e.clientX - box.left, y: e.clientY - box.top };
    if (!queued) requestAnimationFrame(pickNow);
    queued = true;
  });
  canvas.addEventListener('pointerleave', () => {
    at = null;
    if (state.doc) setHighlight(-1);
  });
}

// ---- showing a result -------------------------------------------------------

function showSummary(doc) {
  const t = doc.timings_ms;
  $('summary').textContent =
    `${doc.n_points.toLocaleString('en')} points · ${doc.n_segments} segments · ` +
    `${doc.supernodes.length} supernodes · ${(t.total / 1000).toFixed(2)} s`;
}

function showResult(doc, text) {
  if (doc.n_points !== state.input.count)
    throw new Error(`the page read ${state.input.count} points but the server ${doc.n_points}`);
  Object.assign(state, { doc, text, highlight: -1, depth: nodeDepths(doc.hierarchy.nodes) });
  state.level = finalLevel();
  state.ramp = doc.centrality ? rampIndex(doc.centrality) : null;
  const level = $('level');
  level.max = String(finalLevel());
  level.value = String(state.level);
  $('show-centrality').disabled = !state.ramp;
  $('segment-count').textContent = String(doc.n_segments);
  $('merge-count').textContent = String(doc.merges.length);
  fillLegend($('legend').querySelector('tbody'), doc, (id) => setHighlight(id));
  fillMerges($('merges'), doc);
  showSummary(doc);
  updateLevelLabel();
  updateRamp();
  for (const id of ['view-box', 'legend-box', 'download-box']) $(id).hidden = false;
  repaint();
  setState('done');
}

function updateRamp() {
  const on = $('show-centrality').checked && state.ramp;
  $('ramp').hidden = !on;
  $('level').disabled = Boolean(on);
  if (!on) return;
  $('ramp-lo').textContent = state.ramp.lo.toPrecision(3);
  $('ramp-hi').textContent = state.ramp.hi.toPrecision(3);
}

// ---- running a job ---------------------------------------------------------

function showProgress({ status, phase, fraction }) {
  $('progress').hidden = false;
  $('progress').className = '';
  $('phase').textContent = status === 'queued' ? 'queued' : phase;
  $('percent').textContent = status === 'queued' ? '' : `${Math.round(100 * fraction)}%`;
  $('bar-fill').style.width = `${Math.round(100 * fraction)}%`;
}

// Stops following the job the page follows, if any: it is deleted on the
// server and its poll no longer touches the page.
function dropJob() {
  if (state.job) state.job.cancelled = true;
  state.job = null;
}

// Ends the job the page follows: Segment again, no Cancel or progress.
function endRun() {
  state.job = null;
  $('run').disabled = false;
  $('cancel').hidden = true;
  $('progress').hidden = true;
}

// Segments state.input.  A job still followed (a file chosen while
// another is segmented) is dropped first (dropJob).  Its end shows the
// result, the failure, or the cancel the user asked for.
async function run() {
  if (!state.input) return;
  dropJob();
  const job = { cancelled: false };
  state.job = job;
  const current = () => state.job === job;
  clearError();
  setState('running');
  $('run').disabled = true;
  $('cancel').hidden = false;
  showProgress({ status: 'queued', phase: '', fraction: 0 });
  let end = null;   // what the job ended with, if not a result
  try {
    const params = state.params ? state.params.values() : {};
    const id = await submitJob(state.input.blob, state.input.name, params, state.input.gzip);
    if (current()) state.jobId = id;
    const { doc, text } = await waitForJob(id, (p) => current() && showProgress(p), () => job.cancelled);
    if (current()) showResult(doc, text);
  } catch (err) {
    end = err;
  }
  if (!current()) return;
  endRun();
  if (end instanceof JobCancelled) showCancelled(end.message);
  else if (end) showError(end);
}

// Gives the input's shape to the 3D view, grey (a result recolours it),
// once both are there: a file may be chosen before three.js has loaded.
function shapeToViewer() {
  const { viewer, input } = state;
  if (!viewer || !input) return;
  viewer.setShape(input.positions, input.faces).fill(170);
  viewer.colorsChanged();
  $('surface-toggle').hidden = !input.faces;
}

// Shows the new input at once (grey), then segments it.  gzip: blob is
// gzip-compressed (parsed from its decompressed bytes).
function useInput(name, blob, parsed, gzip = false) {
  state.input = { name, blob, gzip, ...parsed };
  state.doc = null;
  state.hoverPoint = -1;
  $('hover-info').hidden = true;
  $('input-name').textContent = `${name}: ${parsed.count.toLocaleString('en')} points` +
    (parsed.faces ? `, ${(parsed.faces.length / 3).toLocaleString('en')} triangles` : '') +
    (gzip ? ' (gzip)' : '');
  $('placeholder').hidden = true;
  for (const id of ['view-box', 'legend-box', 'download-box']) $(id).hidden = true;
  $('summary').textContent = '';
  shapeToViewer();
  $('run').disabled = false;
  return run();
}

// While a file is read: the phase (reading, decompressing, parsing) and
// its size over a moving bar, and Cancel.
function showReading(file, phase) {
  $('progress').hidden = false;
  $('progress').className = 'busy';
  $('phase').textContent = `${phase} ${file.name}`;
  $('percent').textContent = `${(file.size / 1e6).toFixed(file.size < 1e7 ? 1 : 0)} MB`;
  $('cancel').hidden = false;
}

// Stops reading a file, if one is being read: its result is dropped.
function dropReading() {
  if (state.reading) state.reading.cancel();
  state.reading = null;
}

// Reads and parses the file in a worker (the page stays responsive), then
// segments it.  The job followed until now is cancelled at once; a file
// or example chosen meanwhile replaces this one; Cancel stops the reading.
async function useFile(file) {
  dropReading();
  dropJob();
  clearError();
  setState('reading');
  $('run').disabled = true;
  showReading(file, 'reading');
  let reading = null;
  const current = () => state.reading === reading;
  reading = readPointFile(file, (phase) => current() && showReading(file, phase));
  state.reading = reading;
  let parsed;
  try {
    parsed = await reading.promise;
  } catch (err) {
    if (!current()) return;
    state.reading = null;
    $('run').disabled = !state.input;
    $('cancel').hidden = true;
    $('progress').hidden = true;
    if (err instanceof ReadCancelled) showCancelled(err.message);
    else showError({ title: `Cannot read ${file.name}`, detail: err.message });
    return;
  }
  if (!current()) return;
  state.reading = null;
  const { gzip, ...points } = parsed;
  try {
    await useInput(file.name, file, points, gzip);
  } catch (err) {
    showError({ title: `Cannot read ${file.name}`, detail: err.message });
  }
}

function useExample(shape) {
  dropReading();
  const positions = shape === 'hand' ? makeHand() : makeDumbbell();
  return useInput(`${shape}.ply`, pointsPlyBlob(positions), { count: positions.length / 3, positions, faces: null });
}

// ---- wiring -----------------------------------------------------------------

function baseName() {
  return state.input.name.replace(/\.gz$/i, '').replace(/\.[^.]*$/, '');
}

function wireDownloads() {
  $('dl-labels').onclick = () => saveBlob(labelsBlob(state.doc.labels), `${baseName()}-labels.txt`);
  $('dl-json').onclick = () => saveBlob(jsonBlob(state.text), `${baseName()}.json`);
  $('dl-ply').onclick = () => {
    const rgb = new Uint8Array(3 * state.doc.n_points);
    paint(rgb, state.doc.labels, segmentTable(state.doc.n_segments), state.doc.labels, -1);
    saveBlob(colouredPlyBlob(state.input.positions, rgb, state.input.faces), `${baseName()}-segments.ply`);
  };
}

function wireView() {
  $('level').oninput = (e) => {
    state.level = Number(e.target.value);
    updateLevelLabel();
    repaint();
  };
  $('point-size').oninput = (e) => state.viewer && state.viewer.setPointScale(Number(e.target.value));
  $('show-sinks').onchange = (e) => state.viewer && state.viewer.showSinks(e.target.checked);
  $('show-centrality').onchange = () => {
    updateRamp();
    repaint();
  };
  $('show-surface').onchange = (e) => state.viewer && state.viewer.showSurface(e.target.checked);
  $('fit').onclick = () => state.viewer && state.viewer.fit();
  document.querySelector('.ramp-bar').style.background = rampCss();
}

function wireInput() {
  $('file').onchange = (e) => e.target.files[0] && useFile(e.target.files[0]);
  for (const b of document.querySelectorAll('.example')) b.onclick = () => useExample(b.dataset.shape);
  $('run').onclick = run;
  $('cancel').onclick = () => {
    if (state.reading) state.reading.cancel();
    else if (state.job) state.job.cancelled = true;
  };
  $('reset-params').onclick = () => state.params && state.params.reset();
  document.addEventListener('dragover', (e) => {
    e.preventDefault();
    $('drop').classList.add('over');
  });
  document.addEventListener('dragleave', () => $('drop').classList.remove('over'));
  document.addEventListener('drop', (e) => {
    e.preventDefault();
    $('drop').classList.remove('over');
    if (e.dataTransfer.files[0]) useFile(e.dataTransfer.files[0]);
  });
}

// three.js is copied into vendor/ by `make web`; say so when it is missing.
async function loadViewer() {
  let module;
  try {
    module = await import('./viewer.js');
  } catch (err) {
    const vendor = await fetch('vendor/three.module.js', { method: 'HEAD' }).catch(() => null);
    if (!vendor || !vendor.ok)
      throw { title: 'three.js is missing', detail: 'clients/web/vendor/ is empty: run `make web`, then reload.' };
    throw { title: 'The 3D view failed to load', detail: err.message };
  }
  try {
    return new module.Viewer($('canvas'));
  } catch (err) {
    throw { title: 'WebGL is not available', detail: err.message, noWebgl: true };
  }
}

// Without WebGL the page still segments: the legend, hierarchy and
// downloads work; the stage says why there is no 3D view.
function showNoView(err) {
  $('no-view-detail').textContent = err.detail;
  $('no-view').hidden = false;
}

async function start() {
  wireInput();
  wireView();
  wireDownloads();
  window.pointseg = { state, repaint };
  try {
    state.params = buildParamsForm($('params'), await fetchParamSpecs());
  } catch (err) {
    showError({ title: 'Cannot read the parameters from /openapi.json', detail: err.message });
  }
  // Ready, unless a file chosen meanwhile is already being read or segmented.
  const settle = () => state.input || document.body.dataset.state === 'reading' || setState('ready');
  try {
    state.viewer = await loadViewer();
  } catch (err) {
    if (!err.noWebgl) return showError(err);
    showNoView(err);
    settle();
    return;
  }
  wireCanvasHover(state.viewer);
  shapeToViewer();
  repaint();
  settle();
}

start();
