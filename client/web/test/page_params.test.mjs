// The page's address: the token from the fragment only, the document from
// the query, the WebSocket URL from the page's own scheme and host, and a
// view unless a profile is asked for.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readPageParams, webSocketUrl, addressWithDocument } from '../src/ui/page_params.js';

const at = (href) => new URL(href);

test('doc from the query, token from the fragment', () => {
  const p = readPageParams(at('http://127.0.0.1:8080/?doc=42#token=abc%2Bdef'));
  assert.equal(p.documentId, 42n);
  assert.equal(p.token, 'abc+def');
});

test('a token in the query is not taken; a missing or bad doc is null', () => {
  const p = readPageParams(at('http://h/?doc=x&token=leaked'));
  assert.equal(p.token, '');
  assert.equal(p.documentId, null);
  assert.equal(readPageParams(at('http://h/?doc=0')).documentId, null);
});

test('ws beside http, wss beside https, path /ws', () => {
  assert.equal(webSocketUrl(at('http://127.0.0.1:9000/?doc=1')), 'ws://127.0.0.1:9000/ws');
  assert.equal(webSocketUrl(at('https://example.test/index.html')), 'wss://example.test/ws');
});

test('choosing a document keeps the fragment', () => {
  assert.equal(addressWithDocument(at('http://h:1/?name=al#token=t'), 7n), '/?name=al&doc=7#token=t');
});

test('a view by default; ?views=0 or a ?lod preset asks for a profile; ?views=1 still means a view', () => {
  const views = (query) => readPageParams(at(`http://h/?doc=1${query}#token=t`)).views;
  assert.equal(views(''), true);
  assert.equal(views('&views=0'), false);
  assert.equal(views('&lod=fine'), false);
  assert.equal(views('&lod=coarse&tolerance=4'), false);
  assert.equal(views('&views=1'), true);
  assert.equal(views('&views=1&lod=fine'), true, '?views=1 wins over ?lod');
  assert.equal(readPageParams(at('http://h/?views=0&lod=fine')).lod, 'fine');
});

test('?level=N starts at that control level and ?cage=1 with the cage; anything else is the default', () => {
  const params = (query) => readPageParams(at(`http://h/?doc=1${query}#token=t`));
  assert.deepEqual([params('').level, params('').cage], [null, false]);
  assert.deepEqual([params('&level=0&cage=1').level, params('&level=0&cage=1').cage], [0, true]);
  assert.equal(params('&level=12').level, 12);
  for (const bad of ['&level=', '&level=-1', '&level=1.5', '&level=x', '&level=123']) assert.equal(params(bad).level, null, bad);
  for (const off of ['&cage=0', '&cage=yes', '&cage=']) assert.equal(params(off).cage, false, off);
});

test('?codec=meshopt asks for meshopt regions and, without ?views=1, a profile; without ?codec= a profile is meshopt, a view Draco', () => {
  const p = (query) => readPageParams(at(`http://h/?doc=1${query}#token=t`));
  assert.equal(p('').codec, 'draco');
  assert.equal(p('&views=1').codec, 'draco');
  assert.equal(p('&lod=fine').codec, 'meshopt');
  assert.equal(p('&views=0').codec, 'meshopt');
  assert.equal(p('&lod=fine&codec=draco').codec, 'draco');
  assert.equal(p('&lod=fine&views=1').codec, 'draco');
  assert.equal(p('&codec=draco').codec, 'draco');
  assert.equal(p('&codec=zstd').codec, 'draco');
  assert.equal(p('&lod=fine&codec=zstd').codec, 'meshopt');
  assert.equal(p('&codec=meshopt').codec, 'meshopt');
  assert.equal(p('&codec=meshopt').views, false);
  assert.equal(p('&codec=meshopt&views=1').views, true);
});
