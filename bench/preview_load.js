#!/usr/bin/env node
// Loads preview pages in headless Chromium and prints, per page, the best of RUNS loads: the
// time from navigation to the first complete drawing (data decoded, top layer drawn with the
// stack of the layers below), and the mean time of one redraw when stepping through 20 layers.
// Usage: node preview_load.js NODE_MODULES RUNS PAGE.html...    (prints "page load_ms decode_ms step_ms")
'use strict';
const fs = require('fs');
const os = require('os');
const path = require('path');

const [modules, runsArg, ...pages] = process.argv.slice(2);
const puppeteer = require(path.join(path.resolve(modules), 'puppeteer-core'));

(async () => {
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'tranche-chromium-'));
  const browser = await puppeteer.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    headless: true,
    userDataDir: profile,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  try {
    for (const page of pages) {
      let best = null;
      for (let r = 0; r < Number(runsArg); r++) {
        const tab = await browser.newPage();
        await tab.setViewport({ width: 1280, height: 800, deviceScaleFactor: 1 });
        await tab.goto('file://' + path.resolve(page), { waitUntil: 'load', timeout: 60000 });
        await tab.waitForFunction('window.tranchePreview && (window.tranchePreview.ready || window.tranchePreview.error)', { timeout: 60000 });
        const m = await tab.evaluate(async () => {
          const api = window.tranchePreview;
          if (api.error) return { error: api.error };
          const top = api.layer(), t0 = performance.now();
          for (let i = 1; i <= 20; i++) api.setLayer(top - i);
          await new Promise(requestAnimationFrame);
          return { load: api.readyAt, decode: api.timings.decodeMs, step: (performance.now() - t0) / 20 };
        });
        await tab.close();
        if (m.error) throw new Error(page + ': ' + m.error);
        if (!best || m.load < best.load) best = m;
      }
      console.log([page, best.load.toFixed(0), best.decode.toFixed(0), best.step.toFixed(1)].join(' '));
    }
  } finally {
    await browser.close();
    fs.rmSync(profile, { recursive: true, force: true });
  }
})().catch((e) => { console.error(String(e.stack || e)); process.exit(1); });
