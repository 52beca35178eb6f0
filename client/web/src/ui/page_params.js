// What the page's address says: http://HOST:PORT/?doc=ID#token=TOKEN. The
// token travels in the fragment, which browsers never send to a server or
// put in a Referer, never in the query. `name` (query) is the name others
// see in presence; `level` and `cage` what the page starts showing. The
// WebSocket is on the same host, path /ws, wss when the page came over
// https.
export function readPageParams(location) {
  const query = new URLSearchParams(location.search);
  const fragment = new URLSearchParams(location.hash.replace(/^#/, ''));
  const doc = query.get('doc');
  // ?codec=meshopt or draco: the regions' codec (docs/REGION_ENCODING.md
  // "meshopt regions"). The server serves meshopt to LOD profiles only, so
  // ?codec=meshopt also means a profile unless ?views=1 (whose tiles stay
  // Draco). Without ?codec=, a profile is asked for in meshopt and a view
  // in Draco: in the page, meshopt decoded fandisk's snapshot about three
  // times faster for 1.3 times its bytes (docs/PERFORMANCE.md "Region
  // codecs: the page's default").
  const asked = ['meshopt', 'draco'].includes(query.get('codec')) ? query.get('codec') : null;
  const views = query.has('views') ? query.get('views') !== '0' : !query.has('lod') && asked !== 'meshopt';
  return {
    codec: asked ?? (views ? 'draco' : 'meshopt'),
    documentId: doc !== null && /^\d+$/.test(doc) && BigInt(doc) > 0n ? BigInt(doc) : null,
    token: fragment.get('token') ?? '',
    name: (query.get('name') ?? 'web viewer').slice(0, 128),
    lod: query.get('lod'),
    // A view-dependent subscription unless the address asks for a profile
    // with ?views=0 or ?lod=PRESET (docs/WEB_VIEWER.md "Views"); ?views=1
    // wins over ?lod. ?tolerance=PX is its screen-space error (0.25..256,
    // default 1).
    views,
    tolerance: Math.min(256, Math.max(0.25, Number(query.get('tolerance') ?? 1) || 1)),
    // ?level=N starts the dots (and the cage) at control level N instead of
    // 1; the page keeps it within its profile's levels. ?cage=1 starts with
    // the control cage drawn (docs/WEB_VIEWER.md "The control cage").
    level: /^\d{1,2}$/.test(query.get('level') ?? '') ? Number(query.get('level')) : null,
    cage: query.get('cage') === '1',
  };
}

export function webSocketUrl(location) {
  return `${location.protocol === 'https:' ? 'wss:' : 'ws:'}//${location.host}/ws`;
}

// The address with ?doc=ID, keeping the fragment (the token).
export function addressWithDocument(location, documentId) {
  const query = new URLSearchParams(location.search);
  query.set('doc', String(documentId));
  return `${location.pathname}?${query}${location.hash}`;
}
