// The folders of src/ and the one direction their imports run (README.md
// "Layout of src/"): ui -> scene, session -> codec. codec imports no other
// folder, scene and session import neither each other nor ui, and only the
// page (src/*.js) may import the page's own files.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readdirSync, readFileSync, statSync } from 'node:fs';
import { dirname, join, relative, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const SRC = resolve(dirname(fileURLToPath(import.meta.url)), '../src');
const FOLDERS = ['codec', 'session', 'scene', 'ui'];
// What each folder may import besides itself; '' is the page (src/*.js).
const MAY_IMPORT = {
  codec: [],
  session: ['codec'],
  scene: ['codec'],
  ui: ['session', 'scene', 'codec'],
  '': ['ui', 'session', 'scene', 'codec'],
};

function sources(dir) {
  return readdirSync(dir).flatMap((name) => {
    const path = join(dir, name);
    return statSync(path).isDirectory() ? sources(path) : path.endsWith('.js') ? [path] : [];
  });
}

const folderOf = (path) => relative(SRC, dirname(path)).split('/')[0];

// Relative specifiers of static and dynamic imports and re-exports.
function relativeImports(text) {
  const found = [];
  for (const m of text.matchAll(/(?:\bfrom\s*|\bimport\s*\(?\s*)(['"])(\.{1,2}\/[^'"]+)\1/g)) found.push(m[2]);
  return found;
}

test('src/ holds only the page and its four folders', () => {
  for (const name of readdirSync(SRC)) {
    const path = join(SRC, name);
    if (statSync(path).isDirectory()) assert.ok(FOLDERS.includes(name), `unexpected folder src/${name}`);
    else assert.match(name, /\.js$/, `unexpected file src/${name}`);
  }
});

test('imports run one way: ui -> scene, session -> codec', () => {
  const wrong = [];
  for (const file of sources(SRC)) {
    const from = folderOf(file);
    for (const spec of relativeImports(readFileSync(file, 'utf8'))) {
      const target = resolve(dirname(file), spec);
      if (!target.startsWith(SRC + '/')) continue; // the schema's text (codec/proto_text.js)
      const to = folderOf(target);
      if (to === from) continue;
      if (!MAY_IMPORT[from].includes(to)) wrong.push(`${relative(SRC, file)} imports ${relative(SRC, target)}`);
    }
  }
  assert.deepEqual(wrong, []);
});
