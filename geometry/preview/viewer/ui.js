// The page: reads the data, wires the controls (layer slider and keys, colouring, travels,
// stack, zoom and pan), shows the legend and, for a clicked path, its provenance. Exposes
// window.tranchePreview for tests and benchmarks (tests/geometry/preview/browser).
'use strict';

(function () {
  const $ = (id) => document.getElementById(id);
  const api = (window.tranchePreview = { ready: false, error: null });
  const started = performance.now();
  const esc = (s) => String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]);
  const fmt = (v, digits) => (Number.isFinite(v) ? v.toFixed(digits) : '–');

  function fail(e) {
    api.error = String((e && e.message) || e);
    $('status').textContent = 'cannot show the preview: ' + api.error;
    $('status').className = 'error';
  }

  async function boot() {
    const meta = JSON.parse($('tranche-data').textContent);
    const raw = await TP.inflate(meta.blob);
    if (raw.length !== meta.blobBytes) throw new Error('the preview data is ' + raw.length + ' bytes, not ' + meta.blobBytes);
    const decoded = TP.decode(meta, raw);
    const decodedAt = performance.now();
    const view = new TP.View($('view'), decoded);
    setup(view, meta);
    view.fit();
    render(view);
    api.timings = { decodeMs: decodedAt - started, firstDrawMs: performance.now() - started };
    api.readyAt = performance.now();  // since navigation start
    api.ready = true;
    $('status').textContent = decoded.layerCount + ' layers, ' + decoded.pathN.length + ' paths';
  }

  function render(view) {
    const d = view.d, li = view.layer;
    $('layer').value = String(li);
    $('layer-label').textContent = d.layerCount
      ? 'layer ' + d.layerIndex[li] + ' · z ' + fmt(d.layerZ[li], 2) + ' mm · ' + fmt(d.layerH[li], 2) + ' mm high'
      : 'no layers';
    view.draw();
    api.drawCount = (api.drawCount || 0) + 1;
  }

  function slotNames(meta) {
    // Properties that appear in some chain, speed first.
    const used = new Set();
    for (const p of meta.provenance) for (const [prop] of p.s) used.add(prop);
    const speed = meta.props.findIndex((p) => p[0] === 'speed');
    return [...used].sort((a, b) => (a === speed ? -1 : b === speed ? 1 : a - b));
  }

  function setup(view, meta) {
    $('title').textContent = meta.title || 'Tranche preview';
    const slider = $('layer');
    slider.max = String(Math.max(0, view.d.layerCount - 1));
    const setLayer = (i) => {
      view.layer = Math.max(0, Math.min(view.d.layerCount - 1, i));
      render(view);
    };
    slider.addEventListener('input', () => setLayer(Number(slider.value)));
    $('up').addEventListener('click', () => setLayer(view.layer + 1));
    $('down').addEventListener('click', () => setLayer(view.layer - 1));

    const slots = slotNames(meta);
    const slotSel = $('slot');
    for (const s of slots) slotSel.add(new Option(meta.props[s][0], String(s)));
    if (!slots.length) slotSel.add(new Option('(nothing recorded)', '-1'));
    view.slot = slots.length ? slots[0] : -1;
    const colourSel = $('colour');
    const applyColour = () => {
      view.mode = colourSel.value;
      view.slot = slotSel.value === '' ? -1 : Number(slotSel.value);  // '' : a slot nothing recorded
      $('slot-box').style.display = view.mode === 'rule' ? '' : 'none';
      view.invalidate();
      legend(view);
      render(view);
    };
    colourSel.addEventListener('change', applyColour);
    slotSel.addEventListener('change', applyColour);
    const toggle = (id, key, refit) => $(id).addEventListener('change', () => {
      view[key] = $(id).checked;
      if (refit) view.fit();
      render(view);
    });
    toggle('travels', 'showTravels');
    toggle('retractions', 'showRetractions');
    toggle('stack', 'stack', true);
    view.stack = $('stack').checked;
    $('fit').addEventListener('click', () => { view.fit(); render(view); });
    applyColour();

    interaction(view, setLayer);
    window.addEventListener('resize', () => render(view));

    Object.assign(api, {
      layerCount: view.d.layerCount,
      layer: () => view.layer,
      setLayer,
      setColour: (mode, slotName) => {
        colourSel.value = mode;
        if (slotName) slotSel.value = String(meta.props.findIndex((p) => p[0] === slotName));
        applyColour();
      },
      setStack: (on) => { $('stack').checked = on; view.stack = on; view.fit(); render(view); },
      // Page (CSS px) position of bed point (x, y) mm on the current layer.
      toPage: (x, y) => {
        const r = view.canvas.getBoundingClientRect(), s = view.toScreen(x, y);
        return { x: r.left + s.x, y: r.top + s.y };
      },
      picked: () => view.picked,
    });
  }

  function interaction(view, setLayer) {
    const canvas = view.canvas;
    let drag = null;
    canvas.addEventListener('pointerdown', (e) => {
      drag = { x: e.clientX, y: e.clientY, ox: view.ox, oy: view.oy, moved: false };
      canvas.setPointerCapture(e.pointerId);
    });
    canvas.addEventListener('pointermove', (e) => {
      if (!drag) return;
      const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
      if (Math.abs(dx) + Math.abs(dy) > 3) drag.moved = true;
      if (!drag.moved) return;
      canvas.classList.add('dragging');
      view.ox = drag.ox + dx;
      view.oy = drag.oy + dy;
      render(view);
    });
    canvas.addEventListener('pointerup', (e) => {
      const d = drag;
      drag = null;
      canvas.classList.remove('dragging');
      if (!d || d.moved) return;
      const r = canvas.getBoundingClientRect();
      view.picked = view.pick(e.clientX - r.left, e.clientY - r.top);
      info(view);
      render(view);
    });
    canvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      const r = canvas.getBoundingClientRect(), sx = e.clientX - r.left, sy = e.clientY - r.top;
      const f = Math.exp(-e.deltaY * (e.deltaMode === 1 ? 0.05 : 0.0015));
      view.ox = sx - (sx - view.ox) * f;
      view.oy = sy - (sy - view.oy) * f;
      view.scale *= f;
      render(view);
    }, { passive: false });
    window.addEventListener('keydown', (e) => {
      if (e.target instanceof HTMLSelectElement || e.target instanceof HTMLInputElement) return;  // the slider steps itself
      const step = e.shiftKey ? 10 : 1;
      const keys = {
        ArrowUp: () => setLayer(view.layer + step), ArrowRight: () => setLayer(view.layer + step),
        PageUp: () => setLayer(view.layer + 10), ArrowDown: () => setLayer(view.layer - step),
        ArrowLeft: () => setLayer(view.layer - step), PageDown: () => setLayer(view.layer - 10),
        Home: () => setLayer(0), End: () => setLayer(view.d.layerCount - 1),
        f: () => { view.fit(); render(view); },
        '+': () => zoom(view, 1.25), '=': () => zoom(view, 1.25), '-': () => zoom(view, 0.8),
      };
      if (keys[e.key]) { e.preventDefault(); keys[e.key](); }
    });
  }

  function zoom(view, f) {
    const r = view.canvas.getBoundingClientRect(), cx = r.width / 2, cy = r.height / 2;
    view.ox = cx - (cx - view.ox) * f;
    view.oy = cy - (cy - view.oy) * f;
    view.scale *= f;
    render(view);
  }

  function legend(view) {
    const meta = view.d.meta, box = $('legend');
    const item = (colour, label, count) => '<li><span class="swatch" style="background:' + colour + '"></span>' +
      esc(label) + (count !== undefined ? '<span class="count">' + count + '</span>' : '') + '</li>';
    if (view.mode === 'kind') {
      const count = new Array(meta.kinds.length).fill(0);
      for (const k of view.d.pathKind) count[k]++;
      box.innerHTML = '<h3>Path kind</h3><ul>' + meta.kinds.map((k, i) => (count[i] ? item(k[2], k[1], count[i] + (count[i] === 1 ? ' path' : ' paths')) : '')).join('') + '</ul>';
    } else if (view.mode === 'rule') {
      const c = view.ruleCategories(), name = view.slot >= 0 ? meta.props[view.slot][0] : '–';
      box.innerHTML = '<h3>Who decided ' + esc(name) + '</h3><ul>' + c.keys.map((k, i) =>
        item(i === c.none ? '#6b7280' : meta.categories[i % meta.categories.length], k, c.counts.get(k) + ' pieces')).join('') + '</ul>';
    } else {
      const m = TP.MEASURES[view.mode], { lo, hi } = view.range(view.mode), n = meta.ranges.length, s = m.scale || 1;
      const rows = [];
      for (let i = n - 1; i >= 0; i--) rows.push(item(meta.ranges[i], fmt((lo + ((hi - lo) * i) / (n - 1)) * s, m.digits) + ' ' + m.unit));
      box.innerHTML = '<h3>' + esc(m.label) + ' (' + esc(m.unit) + ')</h3><ul>' + (hi > lo ? rows.join('') : item(meta.ranges[0], fmt(lo * s, m.digits) + ' ' + m.unit)) + '</ul>';
    }
  }

  function chainHtml(meta, prop, steps) {
    const [, unit, names] = meta.props[prop], S = meta.strings;
    // Ratios are stored as fractions and read as percentages (50% is 0.5), as in the rules;
    // enums and bools by their names.
    const show = (v) => (names && names[v] !== undefined ? names[v] : unit === '%' ? fmt(v * 100, 1) + ' %' : unit === 'deg' ? fmt(v, 1) + '°' : fmt(v, unit ? 2 : 3) + (unit ? ' ' + unit : ''));
    const items = steps.map((s, i) => {
      const [value, , rule, file, line, text] = s;
      const where = S[file] ? ' <span class="where">' + esc(S[file] + (line ? ':' + line : '')) + '</span>' : '';
      const who = esc(meta.sources[s[1]]) + (S[rule] ? " '" + esc(S[rule]) + "'" : '');
      return '<li' + (i === steps.length - 1 ? ' class="decider"' : '') + '>' + esc(show(value)) + ' — ' + who + where +
        (S[text] ? ' <code>' + esc(S[text]) + '</code>' : '') + '</li>';
    });
    return '<h4>' + esc(meta.props[prop][0]) + '</h4><ol class="chain">' + items.join('') + '</ol>';
  }

  function info(view) {
    const box = $('info'), d = view.d, meta = d.meta, sel = view.picked;
    if (!sel) { box.innerHTML = '<p class="hint">Click a path to see which rules decided it.</p>'; return; }
    const path = sel.path, pt = d.pathPt0[path] + sel.piece, li = d.pathLayer[path];
    const kind = meta.kinds[d.pathKind[path]];
    const rows = [
      ['layer', d.layerIndex[li] + ' (z ' + fmt(d.layerZ[li], 2) + ' mm)'],
      ['island', d.pathIsland[path] >= 0 ? d.pathIsland[path] : '–'],
      ['cell', d.pathCell[path] >= 0 ? d.pathCell[path] : '–'],
      ['perimeter', d.pathPerimeter[path] >= 0 ? d.pathPerimeter[path] : '–'],
      ['piece', (sel.piece + 1) + ' of ' + (d.pathN[path] - 1)],
      ['speed', fmt(d.pieceS[pt], 1) + ' mm/s'], ['flow', fmt(d.pieceF[pt] * 100, 1) + ' %'],
      ['width', fmt(d.pieceW[pt], 3) + ' mm'], ['fan', fmt(d.pathFan[path] * 100, 0) + ' %'],
      ['nozzle', fmt(d.pathTemp[path], 0) + ' °C'], ['volumetric', fmt(d.pieceV[pt], 2) + ' mm³/s'],
    ];
    let html = '<h3><span class="swatch" style="background:' + kind[2] + '"></span> ' + esc(kind[1]) + ' <code>' + esc(kind[0]) + '</code></h3>' +
      '<table>' + rows.map(([k, v]) => '<tr><td>' + k + '</td><td>' + esc(v) + '</td></tr>').join('') + '</table>';
    const id = d.pieceProv[pt] >= 0 ? d.pieceProv[pt] : d.pathProv[path];
    if (id < 0) {
      html += '<p class="hint">No provenance was recorded for this path.</p>';
    } else {
      const p = meta.provenance[id], S = meta.strings;
      for (const [prop, steps] of p.s) html += chainHtml(meta, prop, steps);
      if (p.e.length) {
        html += '<h4>G-code added by executors</h4>';
        for (const [after, level, rule, file, line, text] of p.e)
          html += '<div>' + (after ? 'after ' : 'before ') + esc(meta.levels[level]) + ": rule '" + esc(S[rule]) + "' " +
            '<span class="where">' + esc(S[file] + (line ? ':' + line : '')) + '</span><pre>' + esc(S[text]) + '</pre></div>';
      }
      html += '<h4>G-code</h4>';
      if (p.r) {
        const [rule, file, line, dflt] = p.r;
        html += "<div class=\"replacer\">generated by replacer '" + esc(S[rule]) + "' <span class=\"where\">" +
          esc(S[file] + (line ? ':' + line : '')) + '</span>' + (dflt ? ' (its output includes the default G-code)' : '') + '</div>';
      } else {
        html += '<div>the default G-code (no replacer)</div>';
      }
    }
    box.innerHTML = html;
  }

  boot().catch(fail);
})();
