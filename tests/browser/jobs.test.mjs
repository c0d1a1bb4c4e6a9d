// jobs.test.mjs: how the viewer follows a job, against /jobs answers the
// test scripts (page.route) with result documents the real pointsegd made:
// a second file chosen while the first is segmented (the first job is
// deleted on the server and no longer polled, whether it would have run on
// or ended first), the Cancel button (DELETE /jobs/{id}, polling stops,
// a status says so and the error box stays empty; a failing run after it
// shows its error, which the next run clears; a refused DELETE is an
// error), a 503 with Retry-After while polling (waited out, not an error),
// and a 503 to POST /jobs (the error says when to try again).
//   node tests/browser/jobs.test.mjs BUILD

import { makeDumbbell, makeHand } from '../../clients/web/shapes.js';
import { LONG, assert, check, finish, launchChromium, sleep, startDaemon } from './harness.mjs';

function xyzText(positions) {
  const lines = [];
  for (let i = 0; i < positions.length; i += 3) lines.push(`${positions[i]} ${positions[i + 1]} ${positions[i + 2]}`);
  return lines.join('\n') + '\n';
}

const FILES = {
  hand: { name: 'hand.xyz', text: xyzText(makeHand()) },
  dumbbell: { name: 'dumbbell.xyz', text: xyzText(makeDumbbell()) },
};

// The real result document of each file (what GET /jobs/{id}/result gives).
async function realDocs(base) {
  const docs = {};
  for (const [key, file] of Object.entries(FILES)) {
    const resp = await fetch(`${base}/segment?include=centrality,point_supernode`, {
      method: 'POST', body: file.text, headers: { 'Content-Type': 'application/octet-stream' },
    });
    assert(resp.ok, `POST /segment of ${file.name}: ${resp.status}`);
    docs[key] = await resp.text();
  }
  return docs;
}

// Answers the page's /jobs requests.  plan: {ids: job id of each POST in
// turn, status(id, polls, log): 'running' | 'done' | {problem, retryAfter},
// result: {id: document text}, refuse: {problem, retryAfter, detail} to
// answer every POST with, refuseDelete: the same for DELETE}, read at each
// request.  Resolves the log: [{method, id, t}].
async function mockJobs(page, plan) {
  const log = [];
  const cancelled = new Set();
  let posts = 0;
  const json = (route, status, body, headers = {}) =>
    route.fulfill({ status, headers: { 'Content-Type': 'application/json', ...headers }, body: JSON.stringify(body) });
  const problem = (route, st) => route.fulfill({
    status: st.problem, headers: { 'Content-Type': 'application/problem+json', 'Retry-After': String(st.retryAfter) },
    body: JSON.stringify({ type: 'about:blank', title: 'Service Unavailable', status: st.problem,
      detail: st.detail || 'too many connections' }),
  });
  const statusDoc = (id, status) => ({ id, status, progress: { phase: 'knn', fraction: status === 'done' ? 1 : 0.3 }, points: 0 });
  await page.route(/\/jobs([/?]|$)/, async (route) => {
    const req = route.request();
    const m = new URL(req.url()).pathname.match(/\/jobs(?:\/([^/]+))?(\/result)?$/);
    const id = m[1] || plan.ids[posts++];
    const entry = { method: req.method(), id, result: Boolean(m[2]), t: Date.now() };
    log.push(entry);
    if (req.method() === 'POST' && plan.refuse) return problem(route, plan.refuse);
    if (req.method() === 'POST') return json(route, 202, { id, status: 'queued' }, { Location: `/jobs/${id}` });
    if (req.method() === 'DELETE' && plan.refuseDelete) return problem(route, plan.refuseDelete);
    if (req.method() === 'DELETE') {
      cancelled.add(id);
      return json(route, 202, statusDoc(id, 'cancelled'));
    }
    if (entry.result) return route.fulfill({ status: 200, contentType: 'application/json', body: plan.result[id] });
    if (cancelled.has(id)) return json(route, 200, statusDoc(id, 'cancelled'));
    const polls = log.filter((e) => e.method === 'GET' && e.id === id && !e.result).length;
    const st = plan.status(id, polls, log);
    if (typeof st === 'object') return problem(route, st);
    return json(route, 200, statusDoc(id, st));
  });
  return log;
}

async function openPage(context, base) {
  const page = await context.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  await page.goto(base + '/');
  await page.waitForSelector('body[data-state=ready]', { timeout: 20000 });
  return { page, errors };
}

function chooseFile(page, key) {
  const f = FILES[key];
  return page.setInputFiles('#file', { name: f.name, mimeType: 'text/plain', buffer: Buffer.from(f.text) });
}

const polls = (log, id) => log.filter((e) => e.method === 'GET' && e.id === id && !e.result).length;

async function waitFor(what, cond, ms = 10000) {
  const end = Date.now() + ms;
  while (!cond()) {
    assert(Date.now() < end, `timed out waiting for ${what}`);
    await sleep(50);
  }
}

// The page after a second file: its result shown, no error, the first job
// deleted and no longer polled.
async function checkSecondWins(page, errors, log, docs) {
  await page.waitForSelector('body[data-state=done], body[data-state=error]', { timeout: LONG });
  await sleep(1000);
  const before = polls(log, 'a');
  await sleep(1000);
  const after = polls(log, 'a');
  const error = await page.$eval('#error', (e) => (e.hidden ? '' : e.textContent));
  const shown = await page.evaluate(() => ({
    n: window.pointseg.state.doc && window.pointseg.state.doc.n_points, state: document.body.dataset.state,
  }));
  assert(!error, `the page shows an error: ${error}`);
  assert(shown.state === 'done' && shown.n === JSON.parse(docs.dumbbell).n_points,
    `state ${shown.state}, result of ${shown.n} points`);
  assert(log.some((e) => e.method === 'DELETE' && e.id === 'a'), 'the first job was never deleted on the server');
  assert(after === before, `the first job is still polled (${before} then ${after} polls)`);
  assert(!errors.length, errors.join(' | '));
}

async function secondFile(context, base, docs) {
  await check('second-file-cancels-first', async () => {
    const { page, errors } = await openPage(context, base);
    const log = await mockJobs(page, {
      ids: ['a', 'b'], result: { a: docs.hand, b: docs.dumbbell },
      status: (id, n) => (id === 'b' && n >= 3 ? 'done' : 'running'),
    });
    await chooseFile(page, 'hand');
    await waitFor('two polls of the first job', () => polls(log, 'a') >= 2);
    await chooseFile(page, 'dumbbell');
    await checkSecondWins(page, errors, log, docs);
    await page.close();
  });
  await check('second-file-first-ends-late', async () => {
    const { page, errors } = await openPage(context, base);
    // The first job ends once the second is posted; the second takes 5 polls.
    const log = await mockJobs(page, {
      ids: ['a', 'b'], result: { a: docs.hand, b: docs.dumbbell },
      status: (id, n, all) => (id === 'b' ? (n >= 5 ? 'done' : 'running')
        : all.some((e) => e.method === 'POST' && e.id === 'b') ? 'done' : 'running'),
    });
    await chooseFile(page, 'hand');
    await waitFor('two polls of the first job', () => polls(log, 'a') >= 2);
    await chooseFile(page, 'dumbbell');
    await waitFor('the second job posted', () => log.some((e) => e.method === 'POST' && e.id === 'b'));
    await sleep(300);
    const running = await page.evaluate(() => ({
      cancel: !document.getElementById('cancel').hidden, progress: !document.getElementById('progress').hidden,
    }));
    assert(running.cancel && running.progress, `while the second job runs: cancel ${running.cancel}, progress ${running.progress}`);
    await checkSecondWins(page, errors, log, docs);
    await page.close();
  });
}

async function cancelButton(context, base, docs) {
  await check('cancel-deletes-job', async () => {
    const { page, errors } = await openPage(context, base);
    const log = await mockJobs(page, { ids: ['a'], result: { a: docs.hand }, status: () => 'running' });
    await chooseFile(page, 'hand');
    await waitFor('two polls', () => polls(log, 'a') >= 2);
    const t = Date.now();
    await page.click('#cancel');
    await waitFor('DELETE /jobs/a', () => log.some((e) => e.method === 'DELETE' && e.id === 'a'), 2000);
    const deleted = log.find((e) => e.method === 'DELETE').t - t;
    await page.waitForSelector('body[data-state=cancelled], body[data-state=error]', { timeout: 5000 });
    const n = polls(log, 'a');
    await sleep(1000);
    assert(polls(log, 'a') === n, 'still polled after the cancel');
    await checkCancelled(page, 'job a was cancelled');
    assert(await page.isEnabled('#run') && await page.isHidden('#cancel'), 'Segment not enabled again, or Cancel still shown');
    console.log(`  DELETE sent ${deleted} ms after the click`);
    assert(!errors.length, errors.join(' | '));
    await page.close();
  });
}

// A cancel the user asked for is a status where the progress goes, not
// an error: the error box hidden and empty.
async function checkCancelled(page, status) {
  const shown = await page.evaluate(() => ({
    state: document.body.dataset.state, error: document.getElementById('error').textContent,
    errorHidden: document.getElementById('error').hidden, progressHidden: document.getElementById('progress').hidden,
    phase: document.getElementById('phase').textContent,
  }));
  assert(shown.errorHidden && !shown.error, `error box (${shown.errorHidden ? 'hidden' : 'shown'}): '${shown.error}'`);
  assert(shown.state === 'cancelled', `page state ${shown.state}`);
  assert(!shown.progressHidden && shown.phase === status, `status (${shown.progressHidden ? 'hidden' : 'shown'}): '${shown.phase}'`);
}

// Opens the page on plan's jobs (mockJobs), chooses the hand and clicks
// Cancel once job a is polled; resolves {page, errors} once the run ended.
async function cancelJobA(context, base, plan) {
  const { page, errors } = await openPage(context, base);
  const log = await mockJobs(page, plan);
  await chooseFile(page, 'hand');
  await waitFor('a poll', () => polls(log, 'a') >= 1);
  await page.click('#cancel');
  await page.waitForSelector('body[data-state=cancelled], body[data-state=error]', { timeout: 5000 });
  return { page, errors };
}

// After a cancel, a run that fails shows its error (the status gone), and
// the run after it clears that error.
async function cancelThenFailure(context, base, docs) {
  await check('cancel-then-failure', async () => {
    const plan = { ids: ['a', 'b', 'c'], result: { c: docs.hand }, status: (id) => (id === 'c' ? 'done' : 'running') };
    const { page, errors } = await cancelJobA(context, base, plan);
    await checkCancelled(page, 'job a was cancelled');
    plan.refuse = { problem: 503, retryAfter: 7, detail: 'the job queue is full' };
    await page.click('#run');
    await page.waitForSelector('body[data-state=error]', { timeout: 5000 });
    const text = await page.textContent('#error');
    assert(await page.isVisible('#error') && text.includes('the job queue is full'), `error box: '${text}'`);
    assert(await page.isHidden('#progress'), 'the cancelled status is still shown beside the error');
    plan.refuse = null;
    await page.click('#run');
    await page.waitForSelector('body[data-state=done]', { timeout: LONG });
    assert(await page.isHidden('#error'), 'the error of the run before is still shown');
    assert(!errors.length, errors.join(' | '));
    await page.close();
  });
}

// A cancel whose DELETE the server refuses is a failure: the job may run
// on, and the error box says so.
async function cancelRefused(context, base, docs) {
  await check('cancel-delete-refused', async () => {
    const { page, errors } = await cancelJobA(context, base, {
      ids: ['a'], result: { a: docs.hand }, status: () => 'running',
      refuseDelete: { problem: 503, retryAfter: 2, detail: 'shutting down' },
    });
    const text = await page.textContent('#error');
    assert(await page.isVisible('#error') && text.includes('shutting down'), `error box: '${text}'`);
    assert(await page.isHidden('#progress'), 'a status is shown beside the error');
    assert(!errors.length, errors.join(' | '));
    await page.close();
  });
}

async function retryAfter(context, base, docs) {
  await check('poll-503-retry-after', async () => {
    const { page, errors } = await openPage(context, base);
    // The second and third polls get a 503 with Retry-After: 1, then the job ends.
    const log = await mockJobs(page, {
      ids: ['a'], result: { a: docs.hand },
      status: (id, n) => (n === 2 || n === 3 ? { problem: 503, retryAfter: 1 } : n >= 5 ? 'done' : 'running'),
    });
    await chooseFile(page, 'hand');
    await page.waitForSelector('body[data-state=done], body[data-state=error]', { timeout: LONG });
    const error = await page.$eval('#error', (e) => (e.hidden ? '' : e.textContent));
    assert(!error, `a 503 with Retry-After while polling gave: ${error}`);
    const times = log.filter((e) => e.method === 'GET' && !e.result).map((e) => e.t);
    assert(times[2] - times[1] >= 900 && times[3] - times[2] >= 900,
      `polled again ${times[2] - times[1]} and ${times[3] - times[2]} ms after the 503s (Retry-After: 1)`);
    assert(!errors.length, errors.join(' | '));
    await page.close();
  });
}

async function busyService(context, base, docs) {
  await check('submit-503-says-when', async () => {
    const { page, errors } = await openPage(context, base);
    await mockJobs(page, {
      ids: ['a'], result: { a: docs.hand }, status: () => 'running',
      refuse: { problem: 503, retryAfter: 7, detail: 'the job queue is full' },
    });
    await chooseFile(page, 'hand');
    await page.waitForSelector('body[data-state=error]', { timeout: LONG });
    const text = await page.textContent('#error');
    assert(text.includes('the job queue is full') && text.includes('try again in 7 s'), `error box: '${text}'`);
    assert(!errors.length, errors.join(' | '));
    await page.close();
  });
}

async function main() {
  const { proc, base } = await startDaemon();
  const { context, close } = await launchChromium();
  try {
    const docs = await realDocs(base);
    await secondFile(context, base, docs);
    await cancelButton(context, base, docs);
    await cancelThenFailure(context, base, docs);
    await cancelRefused(context, base, docs);
    await retryAfter(context, base, docs);
    await busyService(context, base, docs);
  } finally {
    await close();
    proc.kill('SIGTERM');
  }
}

finish(main);
