// What the page's address says: http://HOST:PORT/?doc=ID#token=TOKEN. The
// token travels in the fragment, which browsers never send to a server or
// put in a Referer, never in the query. `name` (query) is the name others
// see in presence. The WebSocket is on the same host, path /ws, wss when the
// page came over https.
export function readPageParams(location) {
  const query = new URLSearchParams(location.search);
  const fragment = new URLSearchParams(location.hash.replace(/^#/, ''));
  const doc = query.get('doc');
  return {
    documentId: doc !== null && /^\d+$/.test(doc) && BigInt(doc) > 0n ? BigInt(doc) : null,
    token: fragment.get('token') ?? '',
    name: (query.get('name') ?? 'web viewer').slice(0, 128),
    lod: query.get('lod'),
    // ?views=1: a view-dependent subscription (docs/WEB_VIEWER.md "Views"),
    // ?tolerance=PX its screen-space error (0.25..256, default 1).
    views: query.get('views') === '1',
    tolerance: Math.min(256, Math.max(0.25, Number(query.get('tolerance') ?? 1) || 1)),
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
