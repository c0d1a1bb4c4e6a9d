// api.js: the daemon's HTTP interface as the page uses it: the parameter
// specs from /openapi.json, POST /jobs (FormData, or a gzip file with
// Content-Encoding: gzip), polling GET /jobs/{id} (a 429 or 503 with
// Retry-After waited out), GET /jobs/{id}/result, DELETE /jobs/{id} when
// the page cancels, and RFC 9457 problem+json turned into readable errors.

// Parameters the page shows (the rest: threads, output, include, it sets).
const SHOWN = ['method', 'k', 'centrality', 'samples', 'persistence', 'ncut_threshold', 'feature_threshold',
  'minima', 'f2', 'smooth_normals'];
const INCLUDE = 'centrality,point_supernode';
const POLL_MS = 200;
const RETRY_MS_MAX = 30000;   // the longest Retry-After waited out while polling
const RETRIES = 10;           // 429/503 answers in a row before a poll gives up

export class ServerError extends Error {
  constructor(status, title, detail, retryAfter = null) {
    super(detail ? `${title}: ${detail}` : title);
    this.status = status;
    this.title = title;
    this.detail = detail;
    this.retryAfter = retryAfter;   // seconds of a Retry-After header, or null
  }
}

// Seconds of a Retry-After header (delay-seconds or an HTTP date), or null.
function retryAfterOf(resp) {
  const h = resp.headers.get('Retry-After');
  if (h === null) return null;
  if (/^\s*\d+\s*$/.test(h)) return Number(h);
  const at = Date.parse(h);
  return Number.isNaN(at) ? null : Math.max(0, (at - Date.now()) / 1000);
}

// A readable error from a non-2xx response (problem+json or anything else).
async function errorOf(resp) {
  const text = await resp.text();
  const retry = retryAfterOf(resp);
  try {
    const p = JSON.parse(text);
    return new ServerError(p.status || resp.status, p.title || resp.statusText, p.detail || '', retry);
  } catch {
    return new ServerError(resp.status, `HTTP ${resp.status} ${resp.statusText}`, text.slice(0, 300), retry);
  }
}

async function request(url, options) {
  let resp;
  try {
    resp = await fetch(url, options);
  } catch (e) {
    throw new ServerError(0, 'The server cannot be reached', e.message);
  }
  if (!resp.ok) throw await errorOf(resp);
  return resp;
}

// [{name, type, default, min, max, choices, help}] of the shown parameters.
export async function fetchParamSpecs() {
  const doc = await (await request('openapi.json')).json();
  const params = doc.paths['/jobs'].post.parameters || [];
  return SHOWN.map((name) => params.find((p) => p.name === name))
    .filter(Boolean)
    .map((p) => ({
      name: p.name,
      type: p.schema.type,
      default: String(p.schema.default),   // typed in the document (7, true): text, as inputs hold it
      min: p.schema.minimum,
      max: p.schema.maximum,
      choices: p.schema.enum || null,
      help: p.description,
    }));
}

// Posts the file as a job; params: {name: text}.  A plain file goes as a
// form (params as fields); a gzip file (gzip true) goes as it is, with
// Content-Encoding: gzip so the daemon inflates it, and params in the
// query.  Returns the job id.
export async function submitJob(blob, filename, params, gzip = false) {
  let url = `jobs?include=${INCLUDE}`;
  let options;
  if (gzip) {
    const query = new URLSearchParams(params).toString();
    if (query) url += `&${query}`;
    options = {
      method: 'POST', body: blob,
      headers: { 'Content-Type': 'application/octet-stream', 'Content-Encoding': 'gzip' },
    };
  } else {
    const form = new FormData();
    form.append('file', blob, filename);
    for (const [name, value] of Object.entries(params)) form.append(name, value);
    options = { method: 'POST', body: form };
  }
  const resp = await request(url, options);
  return (await resp.json()).id;
}

// The end of a job the page cancelled itself (waitForJob's isCancelled),
// which is no failure; a job cancelled by someone else is a ServerError.
export class JobCancelled extends Error {}

const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// GET /jobs/{id}: the status document, or null after waiting out a 429 or
// 503 with Retry-After (a busy or restarting service; the job is still
// there), up to RETRIES of them in a row (busy.count).
async function pollStatus(id, busy) {
  try {
    const st = await (await request(`jobs/${id}`)).json();
    busy.count = 0;
    return st;
  } catch (err) {
    const wait = err.status === 429 || err.status === 503 ? err.retryAfter : null;
    if (wait === null || ++busy.count > RETRIES) throw err;
    await sleep(Math.min(Math.max(1000 * wait, POLL_MS), RETRY_MS_MAX));
    return null;
  }
}

// Polls until the job ends; onProgress({phase, fraction, status}).
// Returns {doc, text} of the result document.  Once isCancelled() is true
// (before or between polls) the job is deleted on the server and the poll
// ends with JobCancelled (with a ServerError if the DELETE fails).
export async function waitForJob(id, onProgress, isCancelled) {
  const stopIfCancelled = async () => {
    if (!isCancelled()) return;
    await request(`jobs/${id}`, { method: 'DELETE' });
    throw new JobCancelled(`job ${id} was cancelled`);
  };
  const busy = { count: 0 };
  for (;;) {
    await stopIfCancelled();
    const st = await pollStatus(id, busy);
    if (!st) continue;
    await stopIfCancelled();
    onProgress({ status: st.status, phase: st.progress.phase, fraction: st.progress.fraction });
    if (st.status === 'done') break;
    if (st.status === 'failed') throw new ServerError(st.error.status, 'The segmentation failed', st.error.detail);
    if (st.status === 'cancelled') throw new ServerError(0, 'Cancelled', `job ${id} was cancelled`);
    await sleep(POLL_MS);
  }
  const text = await (await request(`jobs/${id}/result`)).text();
  return { doc: JSON.parse(text), text };
}
