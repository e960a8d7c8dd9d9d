#!/usr/bin/env node
// Drives `rulec lsp` as an editor does: spawns it, talks JSON-RPC over its standard input and
// output through vscode-jsonrpc (the transport of VS Code's language client), and checks the
// answers: initialize, diagnostics as a document is opened and edited (related locations, the
// Unnecessary tag), hover, completion (fields, enum values, units), go to definition (params,
// `use`s, the rules a W201 names), document symbols, formatting, quick fixes, shutdown and exit.
// Usage: node test-lsp.js NODE_MODULES_DIR RULEC
'use strict';
const path = require('path');
const { spawn } = require('child_process');

const modules = path.resolve(process.argv[2] || path.join(__dirname, 'node_modules'));
const rulec = path.resolve(process.argv[3] || path.join(__dirname, '..', '..', 'build', 'apps', 'rulec'));
const rpc = require(path.join(modules, 'vscode-jsonrpc', 'node'));
const root = path.resolve(__dirname, '..', '..');

let passed = 0;
const failures = [];
function check(ok, what, got) {
  if (ok) passed++;
  else failures.push(what + (got === undefined ? '' : ': got ' + JSON.stringify(got).slice(0, 400)));
}

const server = spawn(rulec, ['lsp', '--stdlib', path.join(root, 'stdlib')], { stdio: ['pipe', 'pipe', 'inherit'] });
const conn = rpc.createMessageConnection(new rpc.StreamMessageReader(server.stdout), new rpc.StreamMessageWriter(server.stdin));
const waiting = new Map();  // version -> resolve
conn.onNotification('textDocument/publishDiagnostics', (p) => {
  const resolve = waiting.get(p.version);
  if (resolve) { waiting.delete(p.version); resolve(p); }
});
conn.listen();
function diagnosticsOf(version) { return new Promise((resolve) => waiting.set(version, resolve)); }

const uri = 'file://' + path.join(root, 'build', 'lsp-test.rules');
const doc = { uri };
const pos = (line, character) => ({ line, character });
const text = [
  'use "features/bridges"',
  'param pause_height = 5 mm',
  'rule "slow" when layer.indx < 2 { speed = 20 }',
  'rule "pause" when layer.z > pause_height { fan = 100% }',
  '',
].join('\n');

// The VS Code extension starts this server: its manifest and entry point must hold together.
function checkExtension() {
  const fs = require('fs');
  const vm = require('vm');
  const manifest = JSON.parse(fs.readFileSync(path.join(root, 'editors', 'package.json'), 'utf8'));
  check(manifest.main === './extension.js', 'the extension has an entry point', manifest.main);
  check((manifest.activationEvents || []).includes('onLanguage:tranche-rules'), 'it starts on .rules files', manifest.activationEvents);
  check(manifest.dependencies && manifest.dependencies['vscode-languageclient'], 'it uses vscode-languageclient', manifest.dependencies);
  const source = fs.readFileSync(path.join(root, 'editors', 'extension.js'), 'utf8');
  let compiles = true;
  try { new vm.Script(source, { filename: 'extension.js' }); } catch (e) { compiles = false; }
  check(compiles, 'extension.js compiles');
  check(/args = \['lsp'\]/.test(source), 'extension.js runs `rulec lsp`');
}

async function main() {
  checkExtension();
  const init = await conn.sendRequest('initialize', { processId: process.pid, rootUri: null, capabilities: {} });
  const caps = init.capabilities;
  check(caps.textDocumentSync.change === 2, 'incremental sync', caps.textDocumentSync);
  for (const c of ['hoverProvider', 'definitionProvider', 'documentSymbolProvider', 'documentFormattingProvider', 'codeActionProvider', 'completionProvider'])
    check(!!caps[c], 'capability ' + c, caps);
  conn.sendNotification('initialized', {});

  let ready = diagnosticsOf(1);
  conn.sendNotification('textDocument/didOpen', { textDocument: { uri, languageId: 'tranche-rules', version: 1, text } });
  let d = (await ready).diagnostics;
  check(d.length === 2, 'two errors on open', d);
  check(d[0].code === 'E0102' && d[0].range.start.line === 2 && d[0].range.start.character === 17, 'E0102 where rulec check puts it', d[0]);
  check(/did you mean `layer.index`\?/.test(d[0].message), 'the help in the message', d[0].message);
  check(d[1].code === 'E0202' && d[1].relatedInformation && d[1].relatedInformation[0].message === 'set here', 'E0202 with a related location', d[1]);

  const actions = await conn.sendRequest('textDocument/codeAction', { textDocument: doc, range: { start: pos(2, 0), end: pos(2, 60) }, context: { diagnostics: d } });
  const fixes = actions.map((a) => a.edit.changes[uri][0].newText);
  check(fixes.includes('layer.index') && fixes.includes('20 mm/s'), 'quick fixes for both errors', actions);
  check(actions.every((a) => a.kind === 'quickfix' && a.diagnostics && a.diagnostics.length === 1), 'quick fixes name their diagnostic', actions);

  // Apply the two fixes as edits of the document, the later one first.
  ready = diagnosticsOf(2);
  conn.sendNotification('textDocument/didChange', { textDocument: { uri, version: 2 }, contentChanges: [
    { range: { start: pos(2, 42), end: pos(2, 44) }, text: '20 mm/s' },
    { range: { start: pos(2, 17), end: pos(2, 27) }, text: 'layer.index' }] });
  d = (await ready).diagnostics;
  check(d.length === 0, 'no diagnostics once fixed', d);

  const hover = await conn.sendRequest('textDocument/hover', { textDocument: doc, position: pos(3, 30) });
  check(hover && /param = `5 mm`/.test(hover.contents.value), 'hover on a param gives its value', hover);
  const hoverField = await conn.sendRequest('textDocument/hover', { textDocument: doc, position: pos(2, 20) });
  check(hoverField && /`layer.index`/.test(hoverField.contents.value), 'hover on a field', hoverField);
  const hoverUse = await conn.sendRequest('textDocument/hover', { textDocument: doc, position: pos(0, 10) });
  check(hoverUse && /stdlib\/features\/bridges.rules/.test(hoverUse.contents.value), 'hover on a use gives its path', hoverUse);

  const def = await conn.sendRequest('textDocument/definition', { textDocument: doc, position: pos(3, 30) });
  check(Array.isArray(def) && def[0].range.start.line === 1, 'definition of a param', def);
  const defUse = await conn.sendRequest('textDocument/definition', { textDocument: doc, position: pos(0, 10) });
  check(Array.isArray(defUse) && /bridges.rules$/.test(defUse[0].uri), 'definition of a use', defUse);

  // Completion after `path.kind == ` on a new line.
  ready = diagnosticsOf(3);
  conn.sendNotification('textDocument/didChange', { textDocument: { uri, version: 3 }, contentChanges: [
    { range: { start: pos(4, 0), end: pos(4, 0) }, text: 'rule when path.kind == ' }] });
  await ready;
  const comp = await conn.sendRequest('textDocument/completion', { textDocument: doc, position: pos(4, 23) });
  const labels = comp.items.map((i) => i.label);
  check(labels.includes('outer_perimeter') && !labels.includes('speed'), 'enum values after ==', labels);
  const compField = await conn.sendRequest('textDocument/completion', { textDocument: doc, position: pos(2, 23) });
  check(compField.items.some((i) => i.label === 'z_bottom'), 'fields after layer.', compField.items.map((i) => i.label));

  // A rule that never takes effect: W201, faded (tag Unnecessary = 1), and from its header the
  // definition goes to the rule that overrides it.
  ready = diagnosticsOf(4);
  conn.sendNotification('textDocument/didChange', { textDocument: { uri, version: 4 }, contentChanges: [{ text:
    'rule "early" { speed = 30 mm/s }\nrule "late" { speed = 40 mm/s }\n' }] });
  d = (await ready).diagnostics;
  const w201 = d.find((x) => x.code === 'W201');
  check(w201 && w201.range.start.line === 0, 'W201 on the rule that never takes effect', d);
  check(w201 && Array.isArray(w201.tags) && w201.tags.length === 1 && w201.tags[0] === 1, 'W201 tagged unnecessary', w201);
  const defRule = await conn.sendRequest('textDocument/definition', { textDocument: doc, position: pos(0, 8) });
  check(Array.isArray(defRule) && defRule.length === 1 && defRule[0].range.start.line === 1 && defRule[0].uri === uri,
        'definition from a W201 rule goes to the rule that overrides it', defRule);

  // Units after a number: the unit of the property being set first.
  ready = diagnosticsOf(5);
  conn.sendNotification('textDocument/didChange', { textDocument: { uri, version: 5 }, contentChanges: [
    { range: { start: pos(2, 0), end: pos(2, 0) }, text: 'rule "u" { speed = 20 ' }] });
  await ready;
  const compUnit = await conn.sendRequest('textDocument/completion', { textDocument: doc, position: pos(2, 22) });
  const units = (compUnit && compUnit.items || []).slice().sort((a, b) =>
    (a.sortText || a.label).localeCompare(b.sortText || b.label));
  check(units.length > 0 && units[0].label === 'mm/s' && units.every((i) => i.kind === units[0].kind) &&
        units.some((i) => i.label === 'mm') && !units.some((i) => i.label === 'speed'),
        'units after a number, the property\'s first', units.map((i) => i.label));

  ready = diagnosticsOf(6);
  conn.sendNotification('textDocument/didChange', { textDocument: { uri, version: 6 }, contentChanges: [{ text: 'rule "x"when layer.index<2{speed=20 mm/s}\n' }] });
  await ready;
  const edits = await conn.sendRequest('textDocument/formatting', { textDocument: doc, options: { tabSize: 2, insertSpaces: true } });
  check(edits.length === 1 && edits[0].newText === 'rule "x" when layer.index < 2 { speed = 20 mm/s }\n', 'formatting', edits);
  const symbols = await conn.sendRequest('textDocument/documentSymbol', { textDocument: doc });
  check(symbols.length === 1 && symbols[0].name === 'x' && symbols[0].children[0].name === 'speed', 'document symbols', symbols);

  await conn.sendRequest('shutdown');
  const exited = new Promise((resolve) => server.on('exit', resolve));
  conn.sendNotification('exit');
  const code = await exited;
  check(code === 0, 'exit status 0 after shutdown', code);
}

const timer = setTimeout(() => { failures.push('timed out'); finish(); }, 60000);
function finish() {
  clearTimeout(timer);
  console.log(`drove ${rulec} lsp over JSON-RPC (vscode-jsonrpc): ${passed} passed, ${failures.length} failed`);
  for (const f of failures) console.log('  FAILED: ' + f);
  server.kill();
  process.exit(failures.length ? 1 : 0);
}
main().then(finish, (e) => { failures.push('error: ' + (e && e.stack || e)); finish(); });
