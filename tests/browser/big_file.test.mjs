// big_file.test.mjs: the viewer while it reads a big scan.  A generated
// 100 MB XYZ file (3.7 million points) is chosen; a 50 ms interval timer
// in the page must keep firing while the file is read and parsed (the
// longest gap under 1 s; parsed on the main thread it was 2 to 4 s), and
// the page must end with the file's point count, and show what it is
// doing; Cancel stops the reading.  Files that do not parse show the
// parser's message as before.
//   node tests/browser/big_file.test.mjs BUILD

import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { LONG, assert, check, finish, launchChromium, shot, startDaemon } from './harness.mjs';

const MAX_GAP_MS = 1000;

// About `mb` MB of XYZ text, points on a sphere; {path, count}.
function writeBigXyz(dir, mb) {
  const chunks = [];
  let size = 0, i = 0;
  while (size < mb * 1024 * 1024) {
    const lines = [];
    for (let k = 0; k < 10000; k++, i++) {
      const z = Math.sin(i * 0.001), r = Math.sqrt(1 - z * z), phi = i * 2.399963;
      lines.push(`${(r * Math.cos(phi)).toFixed(6)} ${(r * Math.sin(phi)).toFixed(6)} ${z.toFixed(6)}\n`);
    }
    const chunk = lines.join('');
    chunks.push(chunk);
    size += chunk.length;
  }
  const path = join(dir, 'big.xyz');
  writeFileSync(path, chunks.join(''));
  return { path, count: i };
}

async function openPage(context, base) {
  const page = await context.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  // Nothing is segmented here: the upload is refused at once.
  await page.route(/\/jobs\?/, (r) => r.abort());
  await page.goto(base + '/');
  await page.waitForSelector('body[data-state=ready]', { timeout: 20000 });
  return { page, errors };
}

// Ticks every 50 ms and notes when a file is chosen, the phases shown
// and when the page leaves the 'reading' state, in window.probe.
function installProbe(page) {
  return page.evaluate(() => {
    const probe = { ticks: [], chosen: null, read: null, phases: [] };
    window.probe = probe;
    setInterval(() => probe.ticks.push(performance.now()), 50);
    document.getElementById('file').addEventListener('change', () => (probe.chosen = performance.now()));
    const phase = document.getElementById('phase');
    new MutationObserver(() => probe.phases.push(phase.textContent)).observe(phase, { childList: true });
    new MutationObserver(() => {
      if (probe.chosen !== null && probe.read === null && document.body.dataset.state !== 'reading')
        probe.read = performance.now();
    }).observe(document.body, { attributes: true, attributeFilter: ['data-state'] });
  });
}

// {ms: from choosing to leaving 'reading', gap: the longest time without a
// tick in between, ticks: how many fired}.
function probeResult(page) {
  return page.evaluate(() => {
    const { ticks, chosen, read } = window.probe;
    const inside = ticks.filter((t) => t > chosen && t < read);
    const times = [chosen, ...inside, read];
    let gap = 0;
    for (let i = 1; i < times.length; i++) gap = Math.max(gap, times[i] - times[i - 1]);
    return { ms: Math.round(read - chosen), gap: Math.round(gap), ticks: inside.length, phases: window.probe.phases };
  });
}

async function responsive(context, base, big) {
  await check('big-file-stays-responsive', async () => {
    const { page, errors } = await openPage(context, base);
    await installProbe(page);
    await page.setInputFiles('#file', big.path);
    await page.waitForFunction(() => window.probe.read !== null, null, { timeout: LONG });
    const got = await probeResult(page);
    const count = await page.evaluate(() => window.pointseg.state.input && window.pointseg.state.input.count);
    const name = await page.textContent('#input-name');
    console.log(`  100 MB XYZ: read in ${got.ms} ms, ${got.ticks} ticks, longest gap ${got.gap} ms`);
    assert(got.gap < MAX_GAP_MS, `the page did not run a timer for ${got.gap} ms while reading`);
    assert(got.phases.includes('parsing big.xyz'), `phases shown: ${JSON.stringify(got.phases)}`);
    assert(count === big.count, `the page read ${count} points, the file has ${big.count}`);
    assert(name.includes(big.count.toLocaleString('en')), `input shown as '${name}'`);
    assert(!errors.length, errors.join(' | '));
    await page.close();
  });
}

// Cancel while the big file is read: the reading stops, the page says so
// (a status, not an error), and the next file is read as usual.
async function cancelReading(context, base, big) {
  await check('big-file-cancel', async () => {
    const { page, errors } = await openPage(context, base);
    await page.setInputFiles('#file', big.path);
    await page.waitForFunction(() => /^parsing big\.xyz/.test(document.getElementById('phase').textContent),
      null, { timeout: LONG });
    const shown = await page.isVisible('#progress') && await page.isVisible('#cancel');
    assert(shown, 'no progress or Cancel while reading');
    await shot(page, 'reading');
    await page.click('#cancel');
    await page.waitForSelector('body[data-state=cancelled], body[data-state=error]', { timeout: 5000 });
    const error = await page.$eval('#error', (e) => (e.hidden ? '' : e.textContent));
    assert(!error, `a cancel shown as an error: '${error}'`);
    const status = await page.textContent('#phase');
    assert(await page.isVisible('#phase') && status === 'reading big.xyz was cancelled', `status: '${status}'`);
    const input = await page.evaluate(() => window.pointseg.state.input);
    assert(input === null && await page.isHidden('#cancel'), 'the cancelled file was used, or Cancel still shown');
    const small = '0 0 0\n1 0 0\n0 1 0\n';
    await page.setInputFiles('#file', { name: 'small.xyz', mimeType: 'text/plain', buffer: Buffer.from(small) });
    await page.waitForFunction(() => window.pointseg.state.input, null, { timeout: LONG });
    assert(await page.evaluate(() => window.pointseg.state.input.count) === 3, 'the next file was not read');
    assert(!errors.length, errors.join(' | '));
    await page.close();
  });
}

// [file name, content, the message shown]
const BAD_FILES = [
  ['bad.xyz', '1 2 3\n4 five 6\n', 'XYZ: a value is not a number'],
  ['bad.ply', 'ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n', 'PLY: no end_header line'],
  ['bad.off', 'OFF\n9 1 0\n0 0 0\n', 'OFF: bad vertex or face count'],
];

async function parseErrors(context, base) {
  for (const [name, text, message] of BAD_FILES) await check(`parse-error-${name}`, async () => {
    const { page, errors } = await openPage(context, base);
    await page.setInputFiles('#file', { name, mimeType: 'text/plain', buffer: Buffer.from(text) });
    await page.waitForSelector('body[data-state=error]', { timeout: LONG });
    const shown = await page.textContent('#error');
    assert(shown === `Cannot read ${name}${message}`, `error box: '${shown}'`);
    assert(!errors.length, errors.join(' | '));
    await page.close();
  });
}

async function main() {
  const dir = mkdtempSync(join(tmpdir(), 'pointseg-big-'));
  const { proc, base } = await startDaemon();
  const { context, close } = await launchChromium();
  try {
    await parseErrors(context, base);
    const big = writeBigXyz(dir, 100);
    await responsive(context, base, big);
    await cancelReading(context, base, big);
  } finally {
    await close();
    proc.kill('SIGTERM');
    rmSync(dir, { recursive: true, force: true });
  }
}

finish(main);
