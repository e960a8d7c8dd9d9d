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

  const t = helpers(page);
  await t.api(() => tranchePreview.setStack(false));  // top-down: probes are exact bed points
  await kindColours(t);
  await sliderAndKeys(t, page);
  await provenance(t);
  await colouring(t, page);
  await retractionsAndZoom(t, page);
  check(errors.length === 0, 'no console error', errors.join(' | '));
  check(requests.length === 0, 'no network request', requests.join(' '));
  await emptyPrint(browser);
  if (screenshotOut) await readmePicture(t, page);
}

function helpers(page) {
  const api = (fn, ...args) => page.evaluate(fn, ...args);
  const pagePos = (p) => api((x, y) => tranchePreview.toPage(x, y), p.x, p.y);
  const infoText = () => page.$eval('#info', (el) => el.innerText);
  return {
    api,
    pagePos,
    infoText,
    // As a user's drag of the slider does: set its value, fire `input`.
    setLayer: (li) => page.$eval('#layer', (el, v) => { el.value = String(v); el.dispatchEvent(new Event('input', { bubbles: true })); }, li),
    // The screenshot's pixel at bed point p on the current layer.
    pixel: async (p) => {
      const pos = await pagePos(p);
      const img = decodePng(Buffer.from(await page.screenshot({ type: 'png' })));
      return img.at(Math.round(pos.x), Math.round(pos.y));
    },
    clickAt: async (p) => { const pos = await pagePos(p); await page.mouse.click(pos.x, pos.y); return infoText(); },
  };
}

async function kindColours(t) {
  for (const name of ['outer wall, slow', 'outer wall, default', 'infill', 'top solid']) {
    const p = probe(name);
    await t.setLayer(p.layer);
    const c = await t.pixel(p);
    check(near(c, hex(p.colour)), name + ': ' + p.kind + ' is drawn in ' + p.colour + ' at (' + p.x.toFixed(2) + ', ' + p.y.toFixed(2) + ')', rgbText(c));
  }
}

async function sliderAndKeys(t, page) {
  // The infill probe's spot is infill on its layer, not on the top one.
  const inf = probe('infill'), top = probe('top solid');
  await t.setLayer(inf.layer);
  const before = await t.pixel(inf);
  await t.setLayer(top.layer);
  const after = await t.pixel(inf), label = await page.$eval('#layer-label', (el) => el.textContent);
  check(near(before, hex(inf.colour)) && !near(after, hex(inf.colour)), 'moving the slider redraws another layer', rgbText(before) + ' then ' + rgbText(after));
  check(label.startsWith('layer ' + top.layer + ' '), 'the layer label follows the slider', label);
  const layer = () => t.api(() => tranchePreview.layer());
  await page.focus('#view');
  await page.keyboard.press('ArrowDown');
  check((await layer()) === top.layer - 1, 'ArrowDown shows the layer below');
  await page.keyboard.press('Home');
  check((await layer()) === 0, 'Home shows the first layer');
  await page.keyboard.press('End');
  check((await layer()) === fixture.layers - 1, 'End shows the top layer');
}

async function provenance(t) {
  for (const name of ['outer wall, slow', 'outer wall, top', 'outer wall, default', 'overhang piece', 'infill', 'top solid']) {
    const p = probe(name);
    await t.setLayer(p.layer);
    const text = await t.clickAt(p);
    check(text.includes("'" + p.rule + "'") && text.includes(p.where), name + ': the panel names ' + p.rule + ' at ' + p.where, text.slice(0, 300));
    const decider = await t.api(() => (document.querySelector('#info ol.chain li.decider') || {}).innerText || '');
    check(decider.includes(p.rule), name + ': the speed chain ends at the deciding rule', decider);
  }
  const inf = probe('infill');
  await t.setLayer(inf.layer);
  let text = await t.clickAt(inf);
  check(/fill_angle\n45\.0° — schema default\n135\.0° — built-in default 'alternate fill angle'/.test(text), 'the fill angle chain is shown in degrees', text);
  const slow = probe('outer wall, slow'), top = probe('top solid');
  await t.setLayer(slow.layer);
  text = await t.clickAt(slow);
  check(/25\.00 mm\/s[^\n]*outer perimeter speed[\s\S]*12\.50 mm\/s[^\n]*slow walls/.test(text), 'the chain shows 25 mm/s from the default, then 12.5 from slow walls', text);
  check(text.includes('speed = speed * 50%'), 'the chain shows the assignment as written');
  check(/100\.0 % — schema default\n.*95\.0 % — --set flow=0\.95/.test(text), 'the flow chain shows the --set override, in percent', text);
  text = await t.clickAt({ x: slow.x, y: slow.y + 0.45 });  // the inner perimeter, just inside
  check(text.includes("'pressure advance'") && text.includes('M900 K0.045') && text.includes('before path'), 'an executor shows its rule and G-code', text.slice(0, 400));
  await t.setLayer(top.layer);
  text = await t.clickAt(top);
  check(/generated by replacer 'ironing pass' fixture\.rules:14/.test(text), 'a replaced path names its replacer', text.slice(-200));
  text = await t.clickAt({ x: 123, y: 100 });  // outside the vase, inside the view
  check(text.includes('Click a path'), 'clicking beside every path clears the panel');
}

async function colouring(t, page) {
  // By deciding rule: the pixel has the legend's colour for that rule.
  const slow = probe('outer wall, slow');
  await t.api(() => tranchePreview.setColour('rule', 'speed'));
  await t.setLayer(slow.layer);
  const swatch = await page.$$eval('#legend li', (lis) => {
    const li = lis.find((l) => l.textContent.includes("'slow walls' (fixture.rules:4)"));
    return li ? getComputedStyle(li.querySelector('.swatch')).backgroundColor : null;
  });
  const ruleC = await t.pixel(slow);
  check(swatch && swatch === rgbText(ruleC), "colour by rule: the slow wall has the legend's colour for 'slow walls'", swatch + ' vs ' + rgbText(ruleC));
  // By speed: the slowest (the overhang, 10 mm/s) at the bottom of the scale, the fastest (infill, 80) at the top.
  await t.api(() => tranchePreview.setColour('speed'));
  const ranges = await t.api(() => JSON.parse(document.getElementById('tranche-data').textContent).ranges);
  const ov = probe('overhang piece'), inf = probe('infill');
  await t.setLayer(ov.layer);
  const slowest = await t.pixel(ov);
  await t.setLayer(inf.layer);
  const fastest = await t.pixel(inf);
  check(near(slowest, hex(ranges[0])), "colour by speed: 10 mm/s is the scale's first colour", rgbText(slowest));
  check(near(fastest, hex(ranges[ranges.length - 1])), "colour by speed: 80 mm/s is the scale's last colour", rgbText(fastest));
  const legend = await page.$eval('#legend', (el) => el.innerText);
  check(legend.includes('80.0 mm/s') && legend.includes('10.0 mm/s'), 'the speed legend spans 10 to 80 mm/s', legend);
  await t.api(() => tranchePreview.setColour('kind'));
}

async function retractionsAndZoom(t, page) {
  const shot = async () => decodePng(Buffer.from(await page.screenshot({ type: 'png' })));
  const without = await shot();
  await page.click('#travels');
  const withTravels = await shot();
  await page.click('#travels');
  let changed = 0;
  for (let y = 0; y < without.height; y += 2) for (let x = 0; x < without.width; x += 2) changed += !near(without.at(x, y), withTravels.at(x, y), 4);
  check(changed > 20, 'travels are drawn on request', changed + ' sampled pixels changed');
  const retract = { x: 105, y: 90 };  // where the fixture's layer change starts, retracted
  const noDot = await t.pixel(retract);
  await page.click('#retractions');
  const dot = await t.pixel(retract);
  check(!near(noDot, [0xcd, 0x22, 0xd6]) && near(dot, [0xcd, 0x22, 0xd6]), 'retractions are marked on request', rgbText(noDot) + ' then ' + rgbText(dot));
  await page.click('#retractions');
  // The wheel zooms about the pointer: the point under it stays, and is still drawn in its colour.
  const inf = probe('infill');
  await t.setLayer(inf.layer);
  const pos = await t.pagePos(inf), mmBefore = (await t.pagePos({ x: inf.x + 1, y: inf.y })).x - pos.x;
  await page.mouse.move(pos.x, pos.y);
  await page.mouse.wheel({ deltaY: -400 });
  const after = await t.pagePos(inf), mmAfter = (await t.pagePos({ x: inf.x + 1, y: inf.y })).x - after.x;
  check(Math.abs(after.x - pos.x) < 1 && Math.abs(after.y - pos.y) < 1, 'the wheel zooms about the pointer');
  check(mmAfter > 1.5 * mmBefore, 'the wheel zooms in', mmBefore.toFixed(1) + ' then ' + mmAfter.toFixed(1) + ' px/mm');
  check(near(await t.pixel(inf), hex(inf.colour)), 'after zooming the infill is still drawn in its colour');
}

async function emptyPrint(browser) {
  const empty = await browser.newPage();
  const errors = [];
  empty.on('pageerror', (e) => errors.push(String(e)));
  empty.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  await empty.goto('file://' + path.join(path.dirname(path.resolve(pagePath)), 'empty.html'), { waitUntil: 'load' });
  await empty.waitForFunction('window.tranchePreview && (window.tranchePreview.ready || window.tranchePreview.error)', { timeout: 30000 });
  const e = await empty.evaluate(() => ({ error: tranchePreview.error, layers: tranchePreview.layerCount, label: document.getElementById('layer-label').textContent }));
  check(!e.error && e.layers === 0 && e.label === 'no layers' && errors.length === 0, 'a print with no layers opens without an error', JSON.stringify(e) + errors.join(' | '));
  await empty.close();
}

// The README's picture: the stacked view, an outer wall's provenance open.
async function readmePicture(t, page) {
  await page.setViewport({ width: 960, height: 560, deviceScaleFactor: 1 });
  await t.api(() => { tranchePreview.setColour('kind'); tranchePreview.setStack(true); });
  const wall = probe('outer wall, top');
  await t.setLayer(wall.layer);
  await t.clickAt(wall);
  await page.$eval('#side', (side) => { side.scrollTop = side.querySelector('#info table').offsetTop + 80; });  // the chain in view
  const shot = decodePng(Buffer.from(await page.screenshot({ type: 'png' })));
  fs.writeFileSync(screenshotOut, encodePng(shot));
  const back = decodePng(fs.readFileSync(screenshotOut));
  check(back.width === shot.width && near(back.at(500, 300), shot.at(500, 300), 6), 'the saved screenshot reads back');
  console.log('screenshot: ' + screenshotOut);
}

main()
  .catch((e) => { failed++; console.log('FAIL: ' + (e.stack || e)); })
  .finally(() => {
    console.log(passed + ' passed, ' + failed + ' failed');
    process.exit(failed ? 1 : 0);
  });
