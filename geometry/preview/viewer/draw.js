// Draws the decoded preview on a canvas 2D: the current layer's paths batched by colour and
// width into Path2D objects in mm (so zoom and pan only change the transform), the layers below
// as a dimmed stack in an oblique view, travels and retractions on request, the picked path.
'use strict';

TP.MEASURES = {
  speed: { label: 'speed', unit: 'mm/s', digits: 1 },
  flow: { label: 'flow', unit: '%', digits: 1, scale: 100 },
  width: { label: 'width', unit: 'mm', digits: 3 },
  fan: { label: 'fan', unit: '%', digits: 0, scale: 100 },
  temp: { label: 'temperature', unit: '°C', digits: 0 },
  vol: { label: 'volumetric rate', unit: 'mm³/s', digits: 2 },
};
const TILT = 0.5;  // the oblique view's y foreshortening (z is drawn 1:1 upwards)

TP.View = class {
  constructor(canvas, data) {
    this.canvas = canvas;
    this.ctx = canvas.getContext('2d');
    this.d = data;
    this.layer = Math.max(0, data.layerCount - 1);
    this.mode = 'kind';
    this.slot = 0;
    this.stack = true;
    this.showTravels = false;
    this.showRetractions = false;
    this.picked = null;  // {path, piece}
    this.cache = new Map();  // layer -> batches, for the current colouring
    this.shells = new Map();  // layer -> Path2D of its outline (the stack)
    this.scale = 1; this.ox = 0; this.oy = 0;
    this.ranges = {};
    this.categories = null;
  }

  // Per-piece value of a measure (pt: the piece's first point; path: its path).
  value(measure, pt, path) {
    const d = this.d;
    switch (measure) {
      case 'speed': return d.pieceS[pt];
      case 'flow': return d.pieceF[pt];
      case 'width': return d.pieceW[pt];
      case 'vol': return d.pieceV[pt];
      case 'fan': return d.pathFan[path];
      case 'temp': return d.pathTemp[path];
    }
    return 0;
  }

  range(measure) {
    if (this.ranges[measure]) return this.ranges[measure];
    const d = this.d;
    let lo = Infinity, hi = -Infinity;
    for (let path = 0; path < d.pathN.length; path++) {
      const p0 = d.pathPt0[path], n = d.pathN[path];
      for (let pt = p0; pt < p0 + n - 1; pt++) {
        const v = this.value(measure, pt, path);
        if (v < lo) lo = v;
        if (v > hi) hi = v;
      }
    }
    if (!(lo <= hi)) { lo = 0; hi = 0; }
    return (this.ranges[measure] = { lo, hi });
  }

  // Deciders of the rule colouring's slot, most frequent first: {keys, colourOfProv}.
  ruleCategories() {
    if (this.categories && this.categories.slot === this.slot) return this.categories;
    const d = this.d, meta = d.meta;
    const keyOfProv = meta.provenance.map((_, id) => {
      const chain = TP.chainOf(meta, id, this.slot);
      return chain && chain.length ? TP.deciderOf(meta, chain[chain.length - 1]) : 'not recorded';
    });
    const counts = new Map();
    const add = (key, n) => counts.set(key, (counts.get(key) || 0) + n);
    for (let path = 0; path < d.pathN.length; path++) {
      const p0 = d.pathPt0[path], pieces = d.pathN[path] - 1;
      for (let pt = p0; pt < p0 + pieces; pt++) {
        const id = d.pieceProv[pt] >= 0 ? d.pieceProv[pt] : d.pathProv[path];
        add(id >= 0 ? keyOfProv[id] : 'not recorded', 1);
      }
    }
    const keys = [...counts.keys()].sort((a, b) => counts.get(b) - counts.get(a));
    const index = new Map(keys.map((k, i) => [k, i]));
    const colourOfProv = Int32Array.from(keyOfProv, (k) => index.get(k) ?? 0);
    const none = index.has('not recorded') ? index.get('not recorded') : -1;
    this.categories = { slot: this.slot, keys, counts, colourOfProv, none };
    return this.categories;
  }

  // Colour (CSS string) of each piece under the current mode, as a function (pt, path) -> string.
  colourer() {
    const d = this.d, meta = d.meta;
    if (this.mode === 'kind') {
      const colours = meta.kinds.map((k) => k[2]);
      return (pt, path) => colours[d.pathKind[path]];
    }
    if (this.mode === 'rule') {
      const c = this.ruleCategories();
      const cols = meta.categories;
      return (pt, path) => {
        const id = d.pieceProv[pt] >= 0 ? d.pieceProv[pt] : d.pathProv[path];
        const k = id >= 0 ? c.colourOfProv[id] : c.none;
        return k === c.none ? '#6b7280' : cols[k % cols.length];
      };
    }
    const { lo, hi } = this.range(this.mode);
    const steps = meta.ranges, n = steps.length;
    return (pt, path) => {
      const t = hi > lo ? (this.value(this.mode, pt, path) - lo) / (hi - lo) : 0;
      return steps[Math.min(n - 1, Math.max(0, Math.round(t * (n - 1))))];
    };
  }

  invalidate() { this.cache.clear(); this.categories = null; }

  // The layer's paths as Path2D batches keyed by colour and width (1/40 mm steps).
  batches(li) {
    let b = this.cache.get(li);
    if (b) return b;
    const d = this.d, colour = this.colourer();
    const map = new Map();
    for (let path = d.layerPath0[li]; path < d.layerPath0[li + 1]; path++) {
      const p0 = d.pathPt0[path], n = d.pathN[path];
      let current = null;
      for (let pt = p0; pt < p0 + n - 1; pt++) {
        const c = colour(pt, path), wq = Math.max(1, Math.round(d.pieceW[pt] * 40));
        const key = c + '/' + wq;
        let batch = map.get(key);
        if (!batch) map.set(key, (batch = { colour: c, width: wq / 40, path: new Path2D() }));
        if (batch !== current) { batch.path.moveTo(d.pts[2 * pt], d.pts[2 * pt + 1]); current = batch; }
        batch.path.lineTo(d.pts[2 * pt + 2], d.pts[2 * pt + 3]);
      }
    }
    b = [...map.values()];
    if (this.cache.size > 64) this.cache.clear();
    this.cache.set(li, b);
    return b;
  }

  // A layer's outline for the stack: its outer perimeters, or every path when it has none.
  shell(li) {
    let s = this.shells.get(li);
    if (s) return s;
    const d = this.d;
    s = new Path2D();
    let any = false;
    for (let pass = 0; pass < 2 && !any; pass++) {
      for (let path = d.layerPath0[li]; path < d.layerPath0[li + 1]; path++) {
        if (pass === 0 && d.pathKind[path] !== 0) continue;
        const p0 = d.pathPt0[path], n = d.pathN[path];
        s.moveTo(d.pts[2 * p0], d.pts[2 * p0 + 1]);
        for (let pt = p0 + 1; pt < p0 + n; pt++) s.lineTo(d.pts[2 * pt], d.pts[2 * pt + 1]);
        any = true;
      }
    }
    this.shells.set(li, s);
    return s;
  }

  fit() {
    const r = this.canvas.getBoundingClientRect();
    const [x0, y0, x1, y1] = this.d.box;
    const zTop = this.stack ? this.d.layerZ[this.d.layerCount - 1] || 0 : 0;
    const k = this.stack ? TILT : 1;
    const w = Math.max(x1 - x0, 1), h = Math.max((y1 - y0) * k + zTop, 1);
    this.scale = 0.9 * Math.min(r.width / w, r.height / h);
    this.ox = r.width / 2 - ((x0 + x1) / 2) * this.scale;
    // Screen y of model (x, y) on layer z: oy - (y*k + z)*scale; centre the whole extent.
    this.oy = r.height / 2 + (((y0 + y1) / 2) * k + zTop / 2) * this.scale;
  }

  // Canvas-pixel transform of layer li (mm -> CSS px -> device px).
  transform(li, dpr) {
    const k = this.stack ? TILT : 1, z = this.stack ? this.d.layerZ[li] : 0;
    return [dpr * this.scale, 0, 0, -dpr * this.scale * k, dpr * this.ox, dpr * (this.oy - z * this.scale)];
  }

  // CSS pixel position (relative to the canvas) of bed point (x, y) on the current layer.
  toScreen(x, y) {
    const k = this.stack ? TILT : 1, z = this.stack ? this.d.layerZ[this.layer] : 0;
    return { x: this.ox + x * this.scale, y: this.oy - (y * k + z) * this.scale };
  }
  toBed(sx, sy) {
    const k = this.stack ? TILT : 1, z = this.stack ? this.d.layerZ[this.layer] : 0;
    return { x: (sx - this.ox) / this.scale, y: ((this.oy - sy) / this.scale - z) / k };
  }

  resize() {
    const dpr = window.devicePixelRatio || 1, r = this.canvas.getBoundingClientRect();
    const w = Math.max(1, Math.round(r.width * dpr)), h = Math.max(1, Math.round(r.height * dpr));
    if (this.canvas.width !== w || this.canvas.height !== h) { this.canvas.width = w; this.canvas.height = h; }
  }

  draw() {
    this.resize();
    const ctx = this.ctx, d = this.d, dpr = window.devicePixelRatio || 1, li = this.layer;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, this.canvas.width, this.canvas.height);
    if (!d.layerCount) return;
    ctx.lineCap = 'round';
    ctx.lineJoin = 'round';
    if (this.stack) {
      const top = Math.max(1, d.layerZ[li]);
      for (let i = 0; i < li; i++) {
        ctx.setTransform(...this.transform(i, dpr));
        const l = Math.round(28 + 30 * (d.layerZ[i] / top));  // lower layers darker: depth
        ctx.strokeStyle = 'hsl(24, 12%, ' + l + '%)';
        ctx.lineWidth = Math.max(d.layerH[i] * 2, 1.2 / this.scale);
        ctx.stroke(this.shell(i));
      }
    } else if (li > 0) {
      ctx.setTransform(...this.transform(li - 1, dpr));
      ctx.globalAlpha = 0.22;
      for (const b of this.batches(li - 1)) { ctx.strokeStyle = '#8a9099'; ctx.lineWidth = b.width; ctx.stroke(b.path); }
      ctx.globalAlpha = 1;
    }
    ctx.setTransform(...this.transform(li, dpr));
    for (const b of this.batches(li)) { ctx.strokeStyle = b.colour; ctx.lineWidth = b.width; ctx.stroke(b.path); }
    if (this.showTravels) this.drawTravels(li);
    if (this.showRetractions) this.drawRetractions(li);
    if (this.picked && d.pathLayer[this.picked.path] === li) this.drawPicked();
  }

  drawTravels(li) {
    const ctx = this.ctx, d = this.d, p = new Path2D();
    for (let t = d.layerTravel0[li]; t < d.layerTravel0[li + 1]; t++) {
      const p0 = d.trPt0[t];
      p.moveTo(d.trPts[2 * p0], d.trPts[2 * p0 + 1]);
      for (let i = p0 + 1; i < p0 + d.trN[t]; i++) p.lineTo(d.trPts[2 * i], d.trPts[2 * i + 1]);
    }
    ctx.strokeStyle = 'rgba(90, 140, 255, 0.85)';
    ctx.lineWidth = 1 / this.scale;
    ctx.stroke(p);
  }

  drawRetractions(li) {
    const ctx = this.ctx, d = this.d, p = new Path2D(), r = 3.5 / this.scale;
    for (let t = d.layerTravel0[li]; t < d.layerTravel0[li + 1]; t++) {
      if (!d.trRetract[t]) continue;
      const x = d.trPts[2 * d.trPt0[t]], y = d.trPts[2 * d.trPt0[t] + 1];
      p.moveTo(x + r, y);
      p.arc(x, y, r, 0, 2 * Math.PI);
    }
    ctx.fillStyle = '#cd22d6';  // PrusaSlicer's retraction colour
    ctx.fill(p);
  }

  drawPicked() {
    const ctx = this.ctx, d = this.d, path = this.picked.path;
    const p0 = d.pathPt0[path], n = d.pathN[path], p = new Path2D();
    p.moveTo(d.pts[2 * p0], d.pts[2 * p0 + 1]);
    for (let pt = p0 + 1; pt < p0 + n; pt++) p.lineTo(d.pts[2 * pt], d.pts[2 * pt + 1]);
    ctx.strokeStyle = '#ffffff';
    ctx.lineWidth = d.pieceW[p0] + 4 / this.scale;
    ctx.globalAlpha = 0.9;
    ctx.stroke(p);
    ctx.globalAlpha = 1;
    ctx.strokeStyle = '#111111';
    ctx.lineWidth = Math.max(d.pieceW[p0] * 0.5, 1 / this.scale);
    ctx.stroke(p);
  }

  // The piece nearest to CSS point (sx, sy) on the current layer, within its half width or 6 px.
  pick(sx, sy) {
    const d = this.d, li = this.layer, { x, y } = this.toBed(sx, sy);
    let best = null, bestD = Infinity;
    for (let path = d.layerPath0[li]; path < d.layerPath0[li + 1]; path++) {
      const p0 = d.pathPt0[path], n = d.pathN[path];
      for (let pt = p0; pt < p0 + n - 1; pt++) {
        const ax = d.pts[2 * pt], ay = d.pts[2 * pt + 1], bx = d.pts[2 * pt + 2], by = d.pts[2 * pt + 3];
        const dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
        const t = len2 > 0 ? Math.max(0, Math.min(1, ((x - ax) * dx + (y - ay) * dy) / len2)) : 0;
        const ex = ax + t * dx - x, ey = ay + t * dy - y, dist = Math.sqrt(ex * ex + ey * ey);
        const reach = Math.max(d.pieceW[pt] / 2, 6 / this.scale);
        if (dist <= reach && dist < bestD) { bestD = dist; best = { path, piece: pt - p0 }; }
      }
    }
    return best;
  }
};
