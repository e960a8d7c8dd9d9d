#!/usr/bin/env node
// The preview of a real slice (`tranche slice --export-preview`, a 20 x 10 x 5 mm block with the
// rules of run.sh), opened from file:// in headless Chromium: it loads without a console error
// or a network request, has the slice's layers, and clicking an outer wall (found in the
// slice's own G-code) shows the rule that halved its speed with its file:line.
// Usage: node real_slice_test.js NODE_MODULES PAGE.html SLICE.gcode RULES_FILE
'use strict';
const fs = require('fs');
const os = require('os');
const path = require('path');

const [modules, pagePath, gcodePath, rulesFile] = process.argv.slice(2);
const puppeteer = require(path.join(path.resolve(modules), 'puppeteer-core'));

let passed = 0, failed = 0;
function check(ok, what, detail) {
  if (ok) passed++;
  else { failed++; console.log('FAIL: ' + what + (detail !== undefined ? ' — ' + detail : '')); }
}

// The G-code's layers, and on `layer` the middle of the first extruding move of the outer wall.
function fromGcode(text, layer) {
  const lines = text.split('\n');
  let layers = 0, current = -1, type = '', x = 0, y = 0, wall = null;
  for (const line of lines) {
    const l = /^;LAYER:(\d+)/.exec(line);
    if (l) { layers++; current = Number(l[1]); continue; }
    const t = /^;TYPE:(.*)/.exec(line);
    if (t) { type = t[1].trim(); continue; }
    if (!/^G1 /.test(line)) continue;
    const word = (c) => { const m = new RegExp(' ' + c + '(-?[0-9.]+)').exec(line); return m ? Number(m[1]) : null; };
    const nx = word('X') ?? x, ny = word('Y') ?? y, e = word('E');
    if (!wall && current === layer && type === 'External perimeter' && e !== null && e > 0 && (nx !== x || ny !== y))
      wall = { x: (x + nx) / 2, y: (y + ny) / 2 };
    x = nx; y = ny;
  }
  return { layers, wall };
}

async function main() {
  const layer = 3;
  const g = fromGcode(fs.readFileSync(gcodePath, 'utf8'), layer);
  check(g.wall !== null, 'the G-code has an outer wall on layer ' + layer);
  if (!g.wall) return;
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'tranche-chromium-'));
  const browser = await puppeteer.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    headless: true,
    userDataDir: profile,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  try {
    const page = await browser.newPage();
    await page.setViewport({ width: 1100, height: 700, deviceScaleFactor: 1 });
    const errors = [], requests = [];
    page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
    page.on('pageerror', (e) => errors.push(String(e)));
    page.on('request', (r) => { if (!/^(file|data|blob):/.test(r.url())) requests.push(r.url()); });
    await page.goto('file://' + path.resolve(pagePath), { waitUntil: 'load' });
    await page.waitForFunction('window.tranchePreview && (window.tranchePreview.ready || window.tranchePreview.error)', { timeout: 30000 });
    const state = await page.evaluate(() => ({ error: tranchePreview.error, layers: tranchePreview.layerCount }));
    check(!state.error, 'the page reads its data', state.error);
    check(state.layers === g.layers, 'the page has the G-code\'s ' + g.layers + ' layers', state.layers);
    await page.evaluate((l) => { tranchePreview.setStack(false); tranchePreview.setLayer(l); }, layer);
    const pos = await page.evaluate((x, y) => tranchePreview.toPage(x, y), g.wall.x, g.wall.y);
    await page.mouse.click(pos.x, pos.y);
    const text = await page.$eval('#info', (el) => el.innerText);
    check(/outer.perimeter|External perimeter/i.test(text), 'the click picks the outer wall', text.slice(0, 200));
    check(text.includes("'slow walls'") && text.includes(rulesFile + ':2'), "the panel names 'slow walls' at " + rulesFile + ':2', text.slice(0, 600));
    check(text.includes('M900 K0.045'), "the panel shows the executor's G-code", text.slice(0, 600));
    check(/seam\naligned — schema default/.test(text) && /outer_first\nfalse — /.test(text), 'enum and bool values are shown by name', text);
    check(errors.length === 0, 'no console error', errors.join(' | '));
    check(requests.length === 0, 'no network request', requests.join(' '));
  } finally {
    await browser.close();
    fs.rmSync(profile, { recursive: true, force: true });
  }
}

main()
  .catch((e) => { failed++; console.log('FAIL: ' + (e.stack || e)); })
  .finally(() => {
    console.log('real slice: ' + passed + ' passed, ' + failed + ' failed');
    process.exit(failed ? 1 : 0);
  });
