// forms.test.mjs: multipart uploads as real clients send them, with
// parameter fields (numbers and text) before and after the file part: Node's
// own fetch + FormData, headless Chromium submitting a real
// <form enctype="multipart/form-data">, and the viewer's own upload (and
// an input there for every parameter /openapi.json lists).  Each
// answer must carry the fields' values in its "params" (a body read in
// pieces once cut a field in two: 422 "got ''").
//   node tests/browser/forms.test.mjs BUILD

import { LONG, assert, check, finish, handXyz, launchChromium, startDaemon } from './harness.mjs';

// The fields and what the answer's params must then say.
const BEFORE = [['k', '6'], ['centrality', 'exact']];
const AFTER = [['persistence', '0.25'], ['minima', 'false']];
const EXPECTED = { k: 6, centrality: 'exact', persistence: 0.25, minima: false };
const TRIES = 20;

function checkParams(doc, expected, what) {
  for (const [name, value] of Object.entries(expected))
    assert(doc.params[name] === value, `${what}: params.${name} is ${doc.params[name]}, sent ${value}`);
}

// Small enough for exact centrality to be quick: the hand's first 400 points.
function smallXyz() {
  return handXyz().split('\n').slice(0, 400).join('\n') + '\n';
}

async function nodeFetch(base) {
  await check('node-fetch-formdata', async () => {
    const xyz = smallXyz();
    for (let i = 0; i < TRIES; i++) {
      const fd = new FormData();
      for (const [name, value] of BEFORE) fd.append(name, value);
      fd.append('file', new Blob([xyz]), 'hand.xyz');
      for (const [name, value] of AFTER) fd.append(name, value);
      const resp = await fetch(`${base}/segment`, { method: 'POST', body: fd });
      const text = await resp.text();
      assert(resp.status === 200, `upload ${i + 1} of ${TRIES}: ${resp.status} ${text.slice(0, 200)}`);
      checkParams(JSON.parse(text), EXPECTED, `upload ${i + 1}`);
    }
  });
}

// A page with a plain HTML form posting to /segment.
function formPage(base) {
  const field = ([name, value]) => `<input name="${name}" value="${value}">`;
  return `<!doctype html><form method="post" enctype="multipart/form-data" action="${base}/segment">
    ${BEFORE.map(field).join('')}<input type="file" name="file">${AFTER.map(field).join('')}
    <button id="go">Segment</button></form>`;
}

async function htmlForm(context, base) {
  await check('chromium-html-form', async () => {
    const page = await context.newPage();
    const buffer = Buffer.from(smallXyz());
    for (let i = 0; i < 5; i++) {
      await page.setContent(formPage(base));
      await page.setInputFiles('input[type=file]', { name: 'hand.xyz', mimeType: 'text/plain', buffer });
      const [resp] = await Promise.all([page.waitForNavigation({ timeout: LONG }), page.click('#go')]);
      const text = await page.textContent('body');
      assert(resp.status() === 200, `form ${i + 1}: ${resp.status()} ${text.slice(0, 200)}`);
      checkParams(JSON.parse(text), EXPECTED, `form ${i + 1}`);
    }
    await page.close();
  });
}

// The viewer's parameter inputs, then its own upload (POST /jobs, FormData).
async function viewerUpload(context, base) {
  await check('viewer-upload-params', async () => {
    const page = await context.newPage();
    await page.goto(base + '/');
    await page.waitForSelector('body[data-state=ready]', { timeout: 20000 });
    await page.click('#params-box summary');
    await page.fill('#param-k', '6');
    await page.selectOption('#param-centrality', 'exact');
    await page.fill('#param-persistence', '0.25');
    await page.setChecked('#param-minima', false);
    await page.fill('#param-ncut_threshold', '0.5');
    const buffer = Buffer.from(smallXyz());
    for (let i = 0; i < 3; i++) {
      await page.setInputFiles('#file', { name: `hand${i}.xyz`, mimeType: 'text/plain', buffer });
      await page.waitForSelector('body[data-state=done], body[data-state=error]', { timeout: LONG });
      const error = await page.$eval('#error', (e) => (e.hidden ? '' : e.textContent));
      assert(!error, `upload ${i + 1}: the page shows an error: ${error}`);
      const id = await page.evaluate(() => window.pointseg.state.jobId);
      const doc = await (await fetch(`${base}/jobs/${id}/result`)).json();
      checkParams(doc, { ...EXPECTED, ncut_threshold: 0.5 }, `viewer upload ${i + 1}`);
    }
    await page.close();
  });
}

// Every parameter /openapi.json lists for POST /jobs has an input in the
// page, but those the page sets itself; method=paper and smooth_normals
// off are among the fields sent, and the latter is in the answer's params
// (which do not list method).
async function viewerEveryParam(context, base) {
  await check('viewer-every-param', async () => {
    const doc = await (await fetch(`${base}/openapi.json`)).json();
    const names = doc.paths['/jobs'].post.parameters.map((p) => p.name)
      .filter((n) => !['threads', 'output', 'include'].includes(n));
    const page = await context.newPage();
    await page.goto(base + '/');
    await page.waitForSelector('body[data-state=ready]', { timeout: 20000 });
    const shown = await page.$$eval('#params [name]', (els) => els.map((e) => e.name));
    const missing = names.filter((n) => !shown.includes(n));
    assert(!missing.length, `no input for ${missing.join(', ')}`);
    await page.click('#params-box summary');
    await page.selectOption('#param-method', 'paper');
    await page.setChecked('#param-smooth_normals', false);
    const values = await page.evaluate(() => window.pointseg.state.params.values());
    assert(values.method === 'paper' && values.smooth_normals === 'false', `sends ${JSON.stringify(values)}`);
    await page.setInputFiles('#file', { name: 'hand.xyz', mimeType: 'text/plain', buffer: Buffer.from(smallXyz()) });
    await page.waitForSelector('body[data-state=done], body[data-state=error]', { timeout: LONG });
    const error = await page.$eval('#error', (e) => (e.hidden ? '' : e.textContent));
    assert(!error, `the page shows an error: ${error}`);
    const id = await page.evaluate(() => window.pointseg.state.jobId);
    const result = await (await fetch(`${base}/jobs/${id}/result`)).json();
    checkParams(result, { smooth_normals: false }, 'viewer upload');
    await page.close();
  });
}

async function main() {
  const { proc, base } = await startDaemon();
  try {
    await nodeFetch(base);
    const { context, close } = await launchChromium();
    try {
      await htmlForm(context, base);
      await viewerUpload(context, base);
      await viewerEveryParam(context, base);
    } finally {
      await close();
    }
  } finally {
    proc.kill('SIGTERM');
  }
}

finish(main);
