// viewer_start.test.mjs: the viewer when its 3D view comes late or not at
// all.  A file chosen right after the page opens, while three.js is still
// on its way (held back 150 ms: it arrives while the upload is segmented;
// 3 s: after the result), must end with the result drawn, no error; a
// browser that cannot create a WebGL context gets a clear message, and the
// legend, hierarchy and downloads still work.
//   node tests/browser/viewer_start.test.mjs BUILD

import { readFileSync } from 'node:fs';
import { LONG, assert, check, colourDigest, finish, handXyz, launchChromium, shot, sleep, startDaemon } from './harness.mjs';

const GREY = 170;

async function openPage(context) {
  const page = await context.newPage();
  const errors = [];
  page.on('console', (m) => m.type() === 'error' && errors.push(m.text()));
  page.on('pageerror', (e) => errors.push(e.message));
  await page.setViewportSize({ width: 1280, height: 800 });
  return { page, errors };
}

async function uploadHand(page) {
  await page.setInputFiles('#file', { name: 'hand.xyz', mimeType: 'text/plain', buffer: Buffer.from(handXyz()) });
  await page.waitForSelector('body[data-state=done], body[data-state=error]', { timeout: LONG });
  const error = await page.$eval('#error', (e) => (e.hidden ? '' : e.textContent));
  assert(!error, `the page shows an error: ${error}`);
}

function earlyFile(context, base, delayMs) {
  return check(`file-before-viewer-${delayMs}ms`, async () => {
    const { page, errors } = await openPage(context);
    await page.route('**/vendor/three.module.js', async (route) => {
      await sleep(delayMs);
      await route.continue();
    });
    await page.goto(base + '/');
    await uploadHand(page);
    await page.waitForFunction(() => window.pointseg.state.viewer, null, { timeout: LONG });
    const drawn = await colourDigest(page);
    const coloured = await page.evaluate((grey) => {
      const { viewer, doc } = window.pointseg.state;
      return viewer.colors.length === 3 * doc.n_points && viewer.colors.some((c) => c !== grey);
    }, GREY);
    await shot(page, `file-before-viewer-${delayMs}ms`);
    const state = await page.evaluate(() => document.body.dataset.state);
    assert(state === 'done', `the page ended in state '${state}'`);
    assert(coloured, 'the 3D view has no segment colours');
    assert(drawn.drawn > 2000, `only ${drawn.drawn} pixels drawn`);
    assert(!errors.length, errors.join(' | '));
    await page.close();
  });
}

// Every WebGL context request fails, as on a machine without a usable GPU.
function refuseWebgl() {
  const getContext = HTMLCanvasElement.prototype.getContext;
  HTMLCanvasElement.prototype.getContext = function (type, ...rest) {
    return /webgl/.test(type) ? null : getContext.call(this, type, ...rest);
  };
}

function noWebgl(context, base) {
  return check('no-webgl', async () => {
    const { page } = await openPage(context);
    await page.addInitScript(refuseWebgl);
    await page.goto(base + '/');
    await page.waitForSelector('body[data-state=ready]', { timeout: 20000 });
    const notice = await page.textContent('#no-view');
    assert(await page.isVisible('#no-view') && notice.includes('WebGL'), `notice: '${notice}'`);
    await uploadHand(page);
    const id = await page.evaluate(() => window.pointseg.state.jobId);
    const doc = await (await fetch(`${base}/jobs/${id}/result`)).json();
    const rows = await page.$$eval('#legend tbody tr', (r) => r.length);
    assert(rows === doc.n_segments, `legend rows ${rows}, n_segments ${doc.n_segments}`);
    await page.$eval('#level', (el) => {
      el.value = '0';
      el.dispatchEvent(new Event('input'));
    });
    const level = await page.textContent('#level-label');
    assert(/1 part\b/.test(level), `hierarchy level 0 shows '${level}'`);
    const [labels] = await Promise.all([page.waitForEvent('download'), page.click('#dl-labels')]);
    const lines = readFileSync(await labels.path(), 'utf8').trim().split('\n');
    assert(lines.length === doc.n_points && lines.every((l, i) => Number(l) === doc.labels[i]),
      `${lines.length} labels downloaded for ${doc.n_points} points`);
    assert(await page.isVisible('#no-view'), 'the notice went away');
    await shot(page, 'no-webgl');
    await page.close();
  });
}

async function main() {
  const { proc, base } = await startDaemon();
  const { context, close } = await launchChromium();
  try {
    await earlyFile(context, base, 150);
    await earlyFile(context, base, 3000);
    await noWebgl(context, base);
  } finally {
    await close();
    proc.kill('SIGTERM');
  }
}

finish(main);
