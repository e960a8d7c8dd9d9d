#!/usr/bin/env node
// Tokenizes every stdlib and example .rules file and the rules blocks of docs/guide.md and
// docs/language.md with editors/tranche-rules.tmLanguage.json, through vscode-textmate and
// vscode-oniguruma as VS Code does, and checks:
// - nothing that is not white space is left with the root scope only (every token matched);
// - reserved words are keywords, comments are comments, strings are strings;
// - every number with a unit: the number is constant.numeric, the unit keyword.other.unit;
// - every `{...}` of a gcode/comment template is an interpolation, whose fields are scoped;
// - the grammar's property, enum value and level names are the schema's (runtime/schema/*.def).
// Usage: node test-grammar.js [NODE_MODULES_DIR]   (default: ./node_modules beside this file)
'use strict';
const fs = require('fs');
const path = require('path');

const modules = path.resolve(process.argv[2] || path.join(__dirname, 'node_modules'));
const vsctm = require(path.join(modules, 'vscode-textmate'));
const oniguruma = require(path.join(modules, 'vscode-oniguruma'));

const root = path.resolve(__dirname, '..', '..');
const grammarPath = path.join(root, 'editors', 'tranche-rules.tmLanguage.json');
const S = '.tranche-rules';

let passed = 0;
let failed = 0;
const failures = [];
function check(ok, what) {
  if (ok) {
    passed++;
  } else {
    failed++;
    if (failures.length < 60) failures.push(what);
  }
}

function walk(dir, out) {
  for (const e of fs.readdirSync(dir, { withFileTypes: true })) {
    const p = path.join(dir, e.name);
    if (e.isDirectory()) walk(p, out);
    else if (e.name.endsWith('.rules')) out.push(p);
  }
  return out;
}

// Sources to tokenize: [name, text].
function sources() {
  const out = [];
  for (const dir of ['stdlib', 'examples'])
    for (const f of walk(path.join(root, dir), []).sort()) out.push([path.relative(root, f), fs.readFileSync(f, 'utf8')]);
  for (const doc of ['guide.md', 'language.md']) {
    const lines = fs.readFileSync(path.join(root, 'docs', doc), 'utf8').split('\n');
    let block = null;
    let start = 0;
    lines.forEach((line, i) => {
      if (block === null && line === '```rules') {
        block = [];
        start = i + 2;
      } else if (block !== null && line === '```') {
        out.push([`docs/${doc}:${start}`, block.join('\n') + '\n']);
        block = null;
      } else if (block !== null) {
        block.push(line);
      }
    });
  }
  return out;
}

const RESERVED = ('use param rule when on append before after replace gcode comment let if then else for in move to ' +
  'travel extrude with default offset reverse retract and or not mod true false').split(' ');

// Character ranges of strings and comments, found without the grammar (for the independent checks).
function lexRanges(text) {
  const strings = []; // [start, end, isTemplate]
  const comments = [];
  let i = 0;
  while (i < text.length) {
    const c = text[i];
    if (c === '#') {
      let j = text.indexOf('\n', i);
      if (j < 0) j = text.length;
      comments.push([i, j]);
      i = j;
    } else if (c === '"') {
      const before = text.slice(0, i).match(/\b(gcode|comment)\s*$/);
      const triple = text.startsWith('"""', i);
      let j = i + (triple ? 3 : 1);
      while (j < text.length) {
        if (text[j] === '\\') { j += 2; continue; }
        if (triple ? text.startsWith('"""', j) : text[j] === '"' || text[j] === '\n') break;
        j++;
      }
      j += triple ? 3 : 1;
      strings.push([i, j, !!before]);
      i = j;
    } else {
      i++;
    }
  }
  return { strings, comments };
}

function inRanges(ranges, pos) {
  return ranges.some(([a, b]) => pos >= a && pos < b);
}

async function main() {
  const wasm = fs.readFileSync(path.join(modules, 'vscode-oniguruma', 'release', 'onig.wasm')).buffer;
  await oniguruma.loadWASM(wasm);
  const registry = new vsctm.Registry({
    onigLib: Promise.resolve({
      createOnigScanner: (patterns) => new oniguruma.OnigScanner(patterns),
      createOnigString: (s) => new oniguruma.OnigString(s),
    }),
    loadGrammar: async (scopeName) => {
      if (scopeName !== 'source.tranche-rules') return null;
      return vsctm.parseRawGrammar(fs.readFileSync(grammarPath, 'utf8'), grammarPath);
    },
  });
  const grammar = await registry.loadGrammar('source.tranche-rules');

  // Every token of a text, with absolute offsets.
  function tokenize(text) {
    const tokens = [];
    let stack = vsctm.INITIAL;
    let offset = 0;
    for (const line of text.split('\n')) {
      const r = grammar.tokenizeLine(line, stack);
      for (const t of r.tokens) {
        const end = Math.min(t.endIndex, line.length);
        tokens.push({ start: offset + t.startIndex, end: offset + end, text: line.slice(t.startIndex, end), scopes: t.scopes });
      }
      stack = r.ruleStack;
      offset += line.length + 1;
    }
    return tokens;
  }
  const has = (tok, prefix) => tok.scopes.some((s) => s.startsWith(prefix));
  const tokenAt = (tokens, pos) => tokens.find((t) => pos >= t.start && pos < t.end);
  const lineCol = (text, pos) => {
    const before = text.slice(0, pos).split('\n');
    return `${before.length}:${before[before.length - 1].length + 1}`;
  };

  // A hand-written sample with known scopes.
  {
    const sample = 'use "features/first-layer"\n' +
      'rule "first" when layer.index < 2 and island.area >= 4 mm2 { speed = 20 mm/s; fill_angle = 15° * layer.index }\n' +
      'on layer.start when below.area > 0 { gcode "M104 S{nozzle_temp:.0} ; {{literal}}" }\n' +
      'rule when path.kind == outer_perimeter { replace path { for p in path.points { move to (p.x, p.y + 0.2mm) with flow = 90% } } }\n' +
      '# a comment\n' +
      'rule "r" { before print append { gcode """\n  G28 ; home {layers[0].area}\n""" } }\n' +
      'rule "loop" when layer.index mod 4 == 1 { fill_angle = clamp(45 deg, 0 deg, 90 deg) }\n';
    const tokens = tokenize(sample);
    const expect = (needle, nth, scope) => {
      let pos = -1;
      for (let k = 0; k <= nth; k++) pos = sample.indexOf(needle, pos + 1);
      const tok = tokenAt(tokens, pos);
      check(tok && has(tok, scope), `sample: "${needle}" (#${nth}) should have ${scope}, has ${tok ? tok.scopes.join(' ') : 'no token'}`);
    };
    expect('use', 0, 'keyword.control.import');
    expect('"features/first-layer"', 0, 'string.quoted.double.path');
    expect('rule', 0, 'storage.type.rule');
    expect('"first"', 0, 'string.quoted.double.rule-name');
    expect('when', 0, 'keyword.control');
    expect('layer', 1, 'variable.language.level');
    expect('index', 0, 'variable.other.field');
    expect('2 and', 0, 'constant.numeric');
    expect('and', 0, 'keyword.operator.logical');
    expect('4 mm2', 0, 'constant.numeric');
    expect('mm2', 0, 'keyword.other.unit');
    expect('speed', 0, 'support.variable.property');
    expect('20 mm/s', 0, 'constant.numeric');
    expect('mm/s', 0, 'keyword.other.unit');
    expect('°', 0, 'keyword.other.unit');
    expect('on', 0, 'storage.type.event');
    expect('start', 0, 'support.constant.event');
    expect('below', 0, 'variable.language.level');
    expect('gcode', 0, 'keyword.other.emit');
    expect('M104 S', 0, 'string.quoted.double.template');
    expect('{nozzle', 0, 'punctuation.definition.template-expression.begin');
    expect('nozzle_temp', 0, 'meta.template.expression');
    expect('nozzle_temp', 0, 'support.variable.property');
    expect(':.0', 0, 'punctuation.separator.format');
    expect('{{', 0, 'constant.character.escape');
    expect('outer_perimeter', 0, 'support.constant.enum');
    expect('replace', 0, 'keyword.other.replacer');
    expect('for', 0, 'keyword.control');
    expect('move', 0, 'keyword.other.action');
    expect('0.2mm', 0, 'constant.numeric');
    expect('mm)', 0, 'keyword.other.unit');
    expect('90%', 0, 'constant.numeric');
    expect('%', 0, 'keyword.other.unit');
    expect('# a comment', 0, 'comment.line.number-sign');
    expect('a comment', 0, 'comment.line.number-sign');
    expect('before', 0, 'keyword.other.executor');
    expect('append', 0, 'keyword.other.action');
    expect('G28', 0, 'string.quoted.triple.template');
    expect('layers', 0, 'variable.language.layers');
    expect('area}', 0, 'meta.template.expression');
    expect('mod', 0, 'keyword.operator.arithmetic');
    expect('clamp', 0, 'support.function.builtin');
    expect('deg', 0, 'keyword.other.unit');
  }

  // Every file: no token left unscoped, and the independent checks.
  let files = 0;
  for (const [name, text] of sources()) {
    files++;
    const tokens = tokenize(text);
    const { strings, comments } = lexRanges(text);
    for (const t of tokens) {
      if (!/\S/.test(t.text)) continue;
      check(t.scopes.length >= 2, `${name}:${lineCol(text, t.start)}: "${t.text}" is not matched by any rule of the grammar`);
      check(!has(t, 'invalid'), `${name}:${lineCol(text, t.start)}: "${t.text}" is marked invalid`);
    }
    // Comments and strings.
    for (const [a] of comments) {
      const tok = tokenAt(tokens, a);
      check(tok && has(tok, 'comment.line'), `${name}:${lineCol(text, a)}: a comment is not scoped as one`);
    }
    for (const [a, b, template] of strings) {
      for (let p = a; p < b; p++) {
        if (/\s/.test(text[p])) continue;
        const tok = tokenAt(tokens, p);
        if (!tok) continue;
        check(has(tok, 'string'), `${name}:${lineCol(text, p)}: "${text[p]}" inside a string is not scoped as a string`);
        break;
      }
      if (!template) continue;
      // Each `{` of a template that is not `{{` opens an interpolation.
      for (let p = a; p < b; p++) {
        if (text[p] !== '{') continue;
        if (text[p + 1] === '{') { p++; continue; }
        const tok = tokenAt(tokens, p);
        check(tok && has(tok, 'punctuation.definition.template-expression.begin'),
          `${name}:${lineCol(text, p)}: a template interpolation is not recognised`);
        const close = text.indexOf('}', p);
        for (let q = p + 1; q < close; q++) {
          const inner = tokenAt(tokens, q);
          if (inner && /\S/.test(text[q]))
            check(has(inner, 'meta.template.expression'), `${name}:${lineCol(text, q)}: interpolation content is not scoped`);
        }
      }
    }
    // Code outside strings and comments: reserved words, numbers and units.
    const code = (pos) => !inRanges(strings, pos) && !inRanges(comments, pos);
    const word = /[\p{L}_][\p{L}\p{N}_]*/gu;
    let m;
    while ((m = word.exec(text))) {
      if (!code(m.index) || !RESERVED.includes(m[0])) continue;
      if (m.index > 0 && text[m.index - 1] === '.') continue;
      const tok = tokenAt(tokens, m.index);
      check(tok && (has(tok, 'keyword') || has(tok, 'storage.type') || has(tok, 'constant.language')),
        `${name}:${lineCol(text, m.index)}: reserved word "${m[0]}" is not a keyword (${tok ? tok.scopes.join(' ') : ''})`);
    }
    const num = /(?<![\p{L}\p{N}_.])([0-9]+(?:\.(?!\.)[0-9]*)?|\.[0-9]+)(\s*)(mm\/s2|mm\/s|mm3\/s|mm2|mm3|mm|deg|°C|°|%|s\b|C\b)?/gu;
    while ((m = num.exec(text))) {
      if (!code(m.index)) continue;
      const tok = tokenAt(tokens, m.index);
      check(tok && has(tok, 'constant.numeric'), `${name}:${lineCol(text, m.index)}: number "${m[1]}" is not constant.numeric`);
      if (m[3]) {
        const upos = m.index + m[1].length + m[2].length;
        const utok = tokenAt(tokens, upos);
        check(utok && has(utok, 'keyword.other.unit'), `${name}:${lineCol(text, upos)}: unit "${m[3]}" is not keyword.other.unit`);
      }
    }
  }
  check(files >= 30, `only ${files} files tokenized`);

  // The grammar's names are the schema's.
  const grammarText = fs.readFileSync(grammarPath, 'utf8');
  const def = (f) => fs.readFileSync(path.join(root, 'runtime', 'schema', f), 'utf8');
  const props = [...def('properties.def').matchAll(/^TRANCHE_PROP\(\w+, "(\w+)"/gm)].map((x) => x[1]);
  const levels = [...new Set([...def('fields.def').matchAll(/^TRANCHE_FIELD\(\w+, "(\w+)\./gm)].map((x) => x[1]))];
  const enumValues = [...def('enums.def').matchAll(/^TRANCHE_ENUM\(\w+, "\w+",\s*\n\s*"([^"]*)"/gm)].flatMap((x) => x[1].split(' '));
  check(props.length >= 30 && levels.length >= 6 && enumValues.length >= 15, 'could not read runtime/schema/*.def');
  const alternation = (scope) => {
    const g = JSON.parse(grammarText);
    const rule = g.repository.expression.patterns.find((p) => p.name === scope + S);
    return rule ? rule.match.replace(/^\\b\(|\)\\b$/g, '').split('|') : [];
  };
  const gProps = alternation('support.variable.property');
  const gEnums = alternation('support.constant.enum');
  const gLevels = alternation('variable.language.level');
  const same = (a, b) => a.length === b.length && [...a].sort().join() === [...b].sort().join();
  check(same(gProps, props), `grammar properties differ from runtime/schema/properties.def (run editors/update-grammar.py): grammar ${gProps.join(',')}; schema ${props.join(',')}`);
  check(same([...new Set(gEnums)], [...new Set(enumValues)]), `grammar enum values differ from runtime/schema/enums.def (run editors/update-grammar.py): ${enumValues.join(',')}`);
  check(same(gLevels, levels), `grammar levels differ from runtime/schema/fields.def: ${levels.join(',')}`);

  // The VS Code extension manifest points at this grammar.
  const manifest = JSON.parse(fs.readFileSync(path.join(root, 'editors', 'package.json'), 'utf8'));
  const contributed = manifest.contributes.grammars[0];
  check(contributed.scopeName === 'source.tranche-rules' && path.resolve(root, 'editors', contributed.path) === grammarPath,
    'editors/package.json does not contribute editors/tranche-rules.tmLanguage.json as source.tranche-rules');
  check(manifest.contributes.languages[0].extensions.includes('.rules'), 'editors/package.json does not claim .rules files');
  JSON.parse(fs.readFileSync(path.join(root, 'editors', 'language-configuration.json'), 'utf8'));

  for (const f of failures) console.log('FAIL: ' + f);
  if (failed > failures.length) console.log(`... and ${failed - failures.length} more failures`);
  console.log(`tokenized ${files} rule files and the sample with ${path.relative(root, grammarPath)}`);
  console.log(`${passed} passed, ${failed} failed`);
  process.exit(failed ? 1 : 0);
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});
