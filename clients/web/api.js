// api.js: the daemon's HTTP interface as the page uses it: the parameter
// specs from /openapi.json, POST /jobs (FormData, or a gzip file with
// Content-Encoding: gzip), polling GET /jobs/{id},
// GET /jobs/{id}/result, and RFC 9457 problem+json turned into readable
// errors.

// Parameters the page shows (the rest: threads, output, include, it sets).
const SHOWN = ['k', 'centrality', 'samples', 'persistence', 'ncut_threshold', 'feature_threshold', 'minima', 'f2'];
const INCLUDE = 'centrality,point_supernode';
const POLL_MS = 200;

export class ServerError extends Error {
  constructor(status, title, detail) {
    super(detail ? `${title}: ${detail}` : title);
    this.status = status;
    this.title = title;
    this.detail = detail;
  }
}

// A readable error from a non-2xx response (problem+json or anything else).
async function errorOf(resp) {
  const text = await resp.text();
  try {
    const p = JSON.parse(text);
    return new ServerError(p.status || resp.status, p.title || resp.statusText, p.detail || '');
  } catch {
    return new ServerError(resp.status, `HTTP ${resp.status} ${resp.statusText}`, text.slice(0, 300));
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
      default: p.schema.default,
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

const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// Polls until the job ends; onProgress({phase, fraction, status}).
// Returns {doc, text} of the result document.  Once isCancelled() is true
// (before or between polls) the job is deleted on the server and the poll
// ends with a 'Cancelled' ServerError.
export async function waitForJob(id, onProgress, isCancelled) {
  const stopIfCancelled = async () => {
    if (!isCancelled()) return;
    await request(`jobs/${id}`, { method: 'DELETE' });
    throw new ServerError(0, 'Cancelled', `job ${id} was cancelled`);
  };
  for (;;) {
    await stopIfCancelled();
    const st = await (await request(`jobs/${id}`)).json();
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
