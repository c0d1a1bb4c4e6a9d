// harness.mjs: what the browser test files share: paths, the PASS/FAIL
// lines and count, pointsegd on a free port serving clients/web, headless
// Chromium, screenshots, a digest of what the viewer drew, and the
// synthetic hand as XYZ text.
//   import { check, assert, startDaemon, launchChromium, finish } from './harness.mjs';

import { spawn } from 'node:child_process';
import { mkdirSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { makeHand } from '../../clients/web/shapes.js';

export const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
export const BUILD = resolve(ROOT, process.argv[2] || 'build');
export const ARTIFACTS = join(BUILD, 'browser-artifacts');
export const SHARED = process.env.POINTSEG_SHARED || resolve(ROOT, '../shared/data');
export const LONG = 60000;
const CHROMIUM_ARGS = [
  '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync',
];

const counts = { passed: 0, failed: 0 };

// Runs one named check: "PASS browser:<name>" or "FAIL browser:<name>: why".
export async function check(name, fn) {
  try {
    await fn();
    console.log(`PASS browser:${name}`);
    counts.passed++;
  } catch (err) {
    console.log(`FAIL browser:${name}: ${String(err.message || err).split('\n')[0]}`);
    counts.failed++;
  }
}

export function assert(cond, why) {
  if (!cond) throw new Error(why);
}

export const sleep = (ms) => new Promise((ok) => setTimeout(ok, ms));

// Starts pointsegd on a free port serving clients/web; resolves {proc, base}.
export function startDaemon() {
  const proc = spawn(join(BUILD, 'pointsegd'),
    ['--port', '0', '--static-dir', join(ROOT, 'clients/web'), '--quiet', '--threads', '1'],
    { stdio: ['ignore', 'inherit', 'pipe'] });
  process.on('exit', () => proc.kill('SIGKILL'));
  return new Promise((ok, fail) => {
    const timer = setTimeout(() => fail(new Error('pointsegd did not say where it listens')), 10000);
    let out = '';
    proc.stderr.on('data', (chunk) => {
      out += chunk;
      const m = out.match(/listening on (http:\/\/[\d.]+:\d+)/);
      if (m) {
        clearTimeout(timer);
        ok({ proc, base: m[1] });
      }
    });
    proc.on('exit', (code) => fail(new Error(`pointsegd exited with ${code}`)));
  });
}

// Headless Chromium (SwiftShader WebGL) with a throw-away profile;
// resolves {context, close}.
export async function launchChromium() {
  mkdirSync(ARTIFACTS, { recursive: true });
  const profile = mkdtempSync(join(tmpdir(), 'pointseg-chromium-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true, args: CHROMIUM_ARGS,
    acceptDownloads: true,
  });
  const close = async () => {
    await context.close();
    rmSync(profile, { recursive: true, force: true });
  };
  return { context, close };
}

export async function shot(page, name) {
  await page.screenshot({ path: join(ARTIFACTS, `${name}.png`) });
}

// Digest of the colours the app computed and of the canvas pixels, and the
// count of pixels unlike the corner one (the background).
export function colourDigest(page) {
  return page.evaluate(() => new Promise((ok) => requestAnimationFrame(() => requestAnimationFrame(() => {
    const c = window.pointseg.state.viewer.colors;
    let h = 0;
    for (let i = 0; i < c.length; i++) h = (h * 31 + c[i]) >>> 0;
    const gl = document.querySelector('#canvas canvas');
    const probe = document.createElement('canvas');
    probe.width = gl.width;
    probe.height = gl.height;
    const g = probe.getContext('2d');
    g.drawImage(gl, 0, 0);
    const px = g.getImageData(0, 0, probe.width, probe.height).data;
    let p = 0, drawn = 0;
    for (let i = 0; i < px.length; i += 4) {
      p = (p * 31 + px[i] + 7 * px[i + 1] + 13 * px[i + 2]) >>> 0;
      if (Math.abs(px[i] - px[0]) + Math.abs(px[i + 1] - px[1]) + Math.abs(px[i + 2] - px[2]) > 12) drawn++;
    }
    ok({ colours: h, pixels: p, drawn });
  }))));
}

// The synthetic hand as XYZ text (one point a line).
export function handXyz() {
  const p = makeHand();
  const lines = [];
  for (let i = 0; i < p.length; i += 3) lines.push(`${p[i]} ${p[i + 1]} ${p[i + 2]}`);
  return lines.join('\n') + '\n';
}

// Runs main, then prints "N passed, N failed" and exits 1 on any failure.
export function finish(main) {
  main().then(() => {
    console.log(`${counts.passed} passed, ${counts.failed} failed`);
    process.exit(counts.failed ? 1 : 0);
  }, (err) => {
    console.log(`FAIL browser:setup: ${err.message}`);
    console.log(`${counts.passed} passed, ${counts.failed + 1} failed`);
    process.exit(1);
  });
}
