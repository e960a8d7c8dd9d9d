// Reads the page's data (format "tranche-preview" v1, written by geometry/preview/preview_data.cpp)
// into flat typed arrays: every point of every path, values per piece (stored at the index of
// the piece's first point), per path and per layer. docs/preview.md describes the layout.
'use strict';
const TP = (window.TP = window.TP || {});

TP.inflate = async function (base64) {
  const bin = atob(base64);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  if (typeof DecompressionStream === 'undefined')
    throw new Error('this browser cannot decompress the preview (no DecompressionStream): use Chromium 80+ or Firefox 113+');
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate'));
  return new Uint8Array(await new Response(stream).arrayBuffer());
};

TP.decode = function (meta, buf) {
  if (meta.format !== 'tranche-preview' || meta.version !== 1)
    throw new Error('not a Tranche preview of format version 1 (found ' + meta.format + ' ' + meta.version + ')');
  const q = meta.quantum;
  const C = meta.counts;
  const L = meta.layers.length;
  const d = {
    meta,
    layerCount: L,
    layerIndex: new Int32Array(L), layerZ: new Float32Array(L), layerH: new Float32Array(L),
    layerPath0: new Uint32Array(L + 1), layerTravel0: new Uint32Array(L + 1),
    pts: new Float32Array(2 * C.points),
    pieceW: new Float32Array(C.points), pieceS: new Float32Array(C.points), pieceF: new Float32Array(C.points),
    pieceV: new Float32Array(C.points), pieceProv: new Int32Array(C.points),
    pathPt0: new Uint32Array(C.paths), pathN: new Uint32Array(C.paths), pathKind: new Uint8Array(C.paths),
    pathProv: new Int32Array(C.paths), pathFan: new Float32Array(C.paths), pathTemp: new Float32Array(C.paths),
    pathIsland: new Int32Array(C.paths), pathCell: new Int32Array(C.paths), pathPerimeter: new Int32Array(C.paths),
    pathLayer: new Uint32Array(C.paths),
    trPt0: new Uint32Array(C.travels), trN: new Uint32Array(C.travels), trRetract: new Uint8Array(C.travels),
    trPts: new Float32Array(2 * C.travelPoints),
    box: [Infinity, Infinity, -Infinity, -Infinity],
  };
  let p = 0;
  const rd = () => {
    let v = 0, s = 1, b;
    do {
      if (p >= buf.length) throw new Error('the preview data ends early (byte ' + p + ')');
      b = buf[p++];
      v += (b & 127) * s;
      s *= 128;
    } while (b & 128);
    return v;
  };
  const rs = () => { const v = rd(); return v % 2 === 1 ? -(v + 1) / 2 : v / 2; };
  let path = 0, pt = 0, tr = 0, tpt = 0;
  const box = d.box;
  for (let li = 0; li < L; li++) {
    const [index, z, h, npaths, ntravels] = meta.layers[li];
    d.layerIndex[li] = index; d.layerZ[li] = z; d.layerH[li] = h;
    d.layerPath0[li] = path; d.layerTravel0[li] = tr;
    let qx = 0, qy = 0;
    for (let k = 0; k < npaths; k++, path++) {
      d.pathKind[path] = rd();
      const n = rd(), flags = rd();
      d.pathProv[path] = rd() - 1;
      d.pathIsland[path] = rs(); d.pathCell[path] = rs(); d.pathPerimeter[path] = rs();
      d.pathFan[path] = rs() * q.fan; d.pathTemp[path] = rs() * q.temp;
      d.pathPt0[path] = pt; d.pathN[path] = n; d.pathLayer[path] = li;
      const pieces = n - 1;
      const fill = (arr, perPiece, quantum) => {
        if (perPiece) for (let i = 0; i < pieces; i++) arr[pt + i] = rs() * quantum;
        else arr.fill(rs() * quantum, pt, pt + pieces);
      };
      fill(d.pieceW, flags & 1, q.width);
      fill(d.pieceS, flags & 2, q.speed);
      fill(d.pieceF, flags & 4, q.flow);
      if (flags & 8) for (let i = 0; i < pieces; i++) d.pieceProv[pt + i] = rd() - 1;
      else d.pieceProv.fill(-1, pt, pt + pieces);
      d.pieceProv[pt + pieces] = -1;
      for (let i = 0; i < n; i++, pt++) {
        qx += rs(); qy += rs();
        const x = qx * q.xy, y = qy * q.xy;
        d.pts[2 * pt] = x; d.pts[2 * pt + 1] = y;
        if (x < box[0]) box[0] = x;
        if (y < box[1]) box[1] = y;
        if (x > box[2]) box[2] = x;
        if (y > box[3]) box[3] = y;
        if (i < pieces) d.pieceV[pt] = TP.volumetricRate(d.pieceW[pt], h, d.pieceS[pt], d.pieceF[pt]);
      }
    }
    for (let k = 0; k < ntravels; k++, tr++) {
      d.trRetract[tr] = rd() & 1;
      const n = rd() + 2;
      d.trPt0[tr] = tpt; d.trN[tr] = n;
      for (let i = 0; i < n; i++, tpt++) {
        qx += rs(); qy += rs();
        d.trPts[2 * tpt] = qx * q.xy; d.trPts[2 * tpt + 1] = qy * q.xy;
      }
    }
  }
  d.layerPath0[L] = path; d.layerTravel0[L] = tr;
  if (p !== buf.length) throw new Error('the preview data has ' + (buf.length - p) + ' unread bytes');
  if (!(box[0] <= box[2])) d.box = [0, 0, meta.bed[0], meta.bed[1]];
  return d;
};

// Bead cross-section (Slic3r's rounded rectangle, as geometry/toolpath/flow.h) times speed and flow.
TP.volumetricRate = function (w, h, speed, flow) {
  const area = w <= h ? Math.PI * w * w / 4 : (w - h) * h + Math.PI * h * h / 4;
  return area * speed * flow;
};

// The chain of `prop` (an index into meta.props) in provenance record `id`, or null.
TP.chainOf = function (meta, id, prop) {
  if (id < 0) return null;
  for (const [p, steps] of meta.provenance[id].s) if (p === prop) return steps;
  return null;
};

// Who decided the value: "rule 'name' (file:line)" or the source's name ("built-in default").
TP.deciderOf = function (meta, step) {
  const [, source, rule, file, line] = step;
  const S = meta.strings;
  const where = S[file] ? ' (' + S[file] + (line ? ':' + line : '') + ')' : '';
  return S[rule] ? meta.sources[source] + " '" + S[rule] + "'" + where : meta.sources[source] + where;
};
