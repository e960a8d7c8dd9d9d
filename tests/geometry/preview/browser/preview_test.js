#!/usr/bin/env node
// Opens the fixture's preview (make_fixture.cpp) from file:// in headless Chromium, as a person
// would, and checks: it loads without a console error or a network request; the slider and the
// keys change the layer drawn; the screenshot's pixels have the kinds' colours at the probes;
// clicking a path shows the rule that decided it with its file:line, its value chain, executors
// and replacer; colouring by rule and by speed paints what the legend says.
// Usage: node preview_test.js NODE_MODULES PAGE.html PROBES.json [SCREENSHOT.png]
'use strict';
const fs = require('fs');
const os = require('os');
const path = require('path');
const { decodePng, encodePng } = require('./png');

const [modules, pagePath, probesPath, screenshotOut] = process.argv.slice(2);
const puppeteer = require(path.join(path.resolve(modules), 'puppeteer-core'));
const fixture = JSON.parse(fs.readFileSync(probesPath, 'utf8'));
const probe = (name) => fixture.probes.find((p) => p.name === name);

let passed = 0, failed = 0;
function check(ok, what, detail) {
  if (ok) passed++;
  else { failed++; console.log('FAIL: ' + what + (detail !== undefined ? ' — ' + detail : '')); }
}
const hex = (h) => [1, 3, 5].map((i) => parseInt(h.slice(i, i + 2), 16));
const near = (a, b, tol = 14) => a.every((v, i) => Math.abs(v - b[i]) <= tol);
const rgbText = (c) => 'rgb(' + c.join(', ') + ')';

async function main() {
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'tranche-chromium-'));
  const browser = await puppeteer.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    headless: true,
    userDataDir: profile,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  try {
    await run(browser);
  } finally {
    await browser.close();
    fs.rmSync(profile, { recursive: true, force: true });
  }
}

async function run(browser) {
  const page = await browser.newPage();
  await page.setViewport({ width: 1100, height: 700, deviceScaleFactor: 1 });
  const errors = [], requests = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('request', (r) => { if (!/^(file|data|blob):/.test(r.url())) requests.push(r.url()); });
  await page.goto('file://' + path.resolve(pagePath), { waitUntil: 'load' });
  await page.waitForFunction('window.tranchePreview && (window.tranchePreview.ready || window.tranchePreview.error)', { timeout: 30000 });
  const state = await page.evaluate(() => ({ error: tranchePreview.error, layers: tranchePreview.layerCount, layer: tranchePreview.layer() }));
  check(!state.error, 'the page reads its data', state.error);
  if (state.error) return;
  check(state.layers === fixture.layers, 'every layer is there', state.layers);
  check(state.layer === fixture.layers - 1, 'the page opens on the top layer', state.layer);

  const api = (fn, ...args) => page.evaluate(fn, ...args);
  const setLayerBySlider = (li) => page.$eval('#layer', (el, v) => { el.value = String(v); el.dispatchEvent(new Event('input', { bubbles: true })); }, li);
  const pagePos = (p) => api((x, y) => tranchePreview.toPage(x, y), p.x, p.y);
  const pixel = async (p) => {
    const pos = await pagePos(p);
    const img = decodePng(Buffer.from(await page.screenshot({ type: 'png' })));
    return img.at(Math.round(pos.x), Math.round(pos.y));
  };
  const infoText = () => page.$eval('#info', (el) => el.innerText);
  const clickAt = async (p) => { const pos = await pagePos(p); await page.mouse.click(pos.x, pos.y); return infoText(); };

  await api(() => tranchePreview.setStack(false));  // top-down: probes are exact bed points

  // The kinds' colours where the paths are.
  for (const name of ['outer wall, slow', 'outer wall, default', 'infill', 'top solid']) {
    const p = probe(name);
    await setLayerBySlider(p.layer);
    const c = await pixel(p);
    check(near(c, hex(p.colour)), name + ': ' + p.kind + ' is drawn in ' + p.colour + ' at (' + p.x.toFixed(2) + ', ' + p.y.toFixed(2) + ')', rgbText(c));
  }

  // The slider changes the layer drawn: the infill probe's spot is infill on its layer, not on the top one.
  const inf = probe('infill'), top = probe('top solid');
  await setLayerBySlider(inf.layer);
  const before = await pixel(inf);
  await setLayerBySlider(top.layer);
  const after = await pixel(inf), label = await page.$eval('#layer-label', (el) => el.textContent);
  check(near(before, hex(inf.colour)) && !near(after, hex(inf.colour)), 'moving the slider redraws another layer', rgbText(before) + ' then ' + rgbText(after));
  check(label.startsWith('layer ' + top.layer + ' '), 'the layer label follows the slider', label);

  // Keys step through the layers.
  await page.focus('#view');
  await page.keyboard.press('ArrowDown');
  check((await api(() => tranchePreview.layer())) === top.layer - 1, 'ArrowDown shows the layer below');
  await page.keyboard.press('Home');
  check((await api(() => tranchePreview.layer())) === 0, 'Home shows the first layer');
  await page.keyboard.press('End');
  check((await api(() => tranchePreview.layer())) === fixture.layers - 1, 'End shows the top layer');

  // Clicking a path shows who decided it.
  for (const name of ['outer wall, slow', 'outer wall, top', 'outer wall, default', 'overhang piece', 'infill', 'top solid']) {
    const p = probe(name);
    await setLayerBySlider(p.layer);
    const text = await clickAt(p);
    check(text.includes("'" + p.rule + "'") && text.includes(p.where), name + ': the panel names ' + p.rule + ' at ' + p.where, text.slice(0, 300));
    const decider = await page.$eval('#info ol.chain li.decider', (el) => el.innerText).catch(() => '');
    check(decider.includes(p.rule), name + ': the speed chain ends at the deciding rule', decider);
  }
  const slow = probe('outer wall, slow');
  await setLayerBySlider(slow.layer);
  let text = await clickAt(slow);
  check(/25\.00 mm\/s[^\n]*outer perimeter speed[\s\S]*12\.50 mm\/s[^\n]*slow walls/.test(text), 'the chain shows 25 mm/s from the default, then 12.5 from slow walls', text);
  check(text.includes('speed = speed * 50%'), 'the chain shows the assignment as written');
  check(/100\.0 % — schema default\n.*95\.0 % — --set flow=0\.95/.test(text), 'the flow chain shows the --set override, in percent', text);
  text = await clickAt({ x: slow.x, y: slow.y + 0.45 });  // the inner perimeter, just inside
  check(text.includes("'pressure advance'") && text.includes('M900 K0.045') && text.includes('before path'), 'an executor shows its rule and G-code', text.slice(0, 400));
  await setLayerBySlider(top.layer);
  text = await clickAt(top);
  check(/generated by replacer 'ironing pass' fixture\.rules:14/.test(text), 'a replaced path names its replacer', text.slice(-200));
  text = await clickAt({ x: 123, y: 100 });  // outside the vase, inside the view
  check(text.includes('Click a path'), 'clicking beside every path clears the panel');

  // Colour by deciding rule: the pixel has the legend's colour for that rule.
  await api(() => tranchePreview.setColour('rule', 'speed'));
  await setLayerBySlider(slow.layer);
  const swatch = await page.$$eval('#legend li', (lis) => {
    const li = lis.find((l) => l.textContent.includes("'slow walls' (fixture.rules:4)"));
    return li ? getComputedStyle(li.querySelector('.swatch')).backgroundColor : null;
  });
  const ruleC = await pixel(slow);
  check(swatch && swatch === rgbText(ruleC), "colour by rule: the slow wall has the legend's colour for 'slow walls'", swatch + ' vs ' + rgbText(ruleC));

  // Colour by speed: slowest (the overhang, 10 mm/s) at the bottom of the scale, fastest (infill, 80) at the top.
  await api(() => tranchePreview.setColour('speed'));
  const ranges = await api(() => JSON.parse(document.getElementById('tranche-data').textContent).ranges);
  const ov = probe('overhang piece');
  await setLayerBySlider(ov.layer);
  const slowest = await pixel(ov);
  await setLayerBySlider(inf.layer);
  const fastest = await pixel(inf);
  check(near(slowest, hex(ranges[0])), 'colour by speed: 10 mm/s is the scale\'s first colour', rgbText(slowest));
  check(near(fastest, hex(ranges[ranges.length - 1])), 'colour by speed: 80 mm/s is the scale\'s last colour', rgbText(fastest));
  const legend = await page.$eval('#legend', (el) => el.innerText);
  check(legend.includes('80.0 mm/s') && legend.includes('10.0 mm/s'), 'the speed legend spans 10 to 80 mm/s', legend);

  // Retractions on request.
  await api(() => tranchePreview.setColour('kind'));
  const retract = await api(() => ({ x: 105, y: 90 }));
  const noDot = await pixel(retract);
  await page.click('#retractions');
  const dot = await pixel(retract);
  check(!near(noDot, [0xcd, 0x22, 0xd6]) && near(dot, [0xcd, 0x22, 0xd6]), 'retractions are marked on request', rgbText(noDot) + ' then ' + rgbText(dot));
  await page.click('#retractions');

  // Zoom: the wheel zooms about the pointer, and the probe stays under its pixel's colour.
  const pos = await pagePos(inf);
  await page.mouse.move(pos.x, pos.y);
  await page.mouse.wheel({ deltaY: -400 });
  const after2 = await pagePos(inf);
  check(Math.abs(after2.x - pos.x) < 1 && Math.abs(after2.y - pos.y) < 1, 'the wheel zooms about the pointer');
  check(near(await pixel(inf), hex(inf.colour)), 'after zooming the infill is still drawn in its colour');

  check(errors.length === 0, 'no console error', errors.join(' | '));
  check(requests.length === 0, 'no network request', requests.join(' '));

  // A print with no layers opens and says so.
  const empty = await browser.newPage();
  const emptyErrors = [];
  empty.on('pageerror', (e) => emptyErrors.push(String(e)));
  empty.on('console', (m) => { if (m.type() === 'error') emptyErrors.push(m.text()); });
  await empty.goto('file://' + path.join(path.dirname(path.resolve(pagePath)), 'empty.html'), { waitUntil: 'load' });
  await empty.waitForFunction('window.tranchePreview && (window.tranchePreview.ready || window.tranchePreview.error)', { timeout: 30000 });
  const e = await empty.evaluate(() => ({ error: tranchePreview.error, layers: tranchePreview.layerCount, label: document.getElementById('layer-label').textContent }));
  check(!e.error && e.layers === 0 && e.label === 'no layers' && emptyErrors.length === 0, 'an empty print opens without an error', JSON.stringify(e) + emptyErrors.join(' | '));
  await empty.close();

  if (screenshotOut) {  // the README's picture: the stacked view, a wall's provenance open
    await page.setViewport({ width: 960, height: 560, deviceScaleFactor: 1 });
    await api(() => { tranchePreview.setColour('kind'); tranchePreview.setStack(true); });
    const wall = probe('outer wall, top');
    await setLayerBySlider(wall.layer);
    await clickAt(wall);
    await page.$eval('#side', (side) => { side.scrollTop = side.querySelector('#info table').offsetTop + 80; });  // the chain in view
    const shot = decodePng(Buffer.from(await page.screenshot({ type: 'png' })));
    fs.writeFileSync(screenshotOut, encodePng(shot));
    const back = decodePng(fs.readFileSync(screenshotOut));
    check(back.width === shot.width && near(back.at(500, 300), shot.at(500, 300), 6), 'the saved screenshot reads back');
    console.log('screenshot: ' + screenshotOut);
  }
}

main()
  .catch((e) => { failed++; console.log('FAIL: ' + (e.stack || e)); })
  .finally(() => {
    console.log(passed + ' passed, ' + failed + ' failed');
    process.exit(failed ? 1 : 0);
  });
