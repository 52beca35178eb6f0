// The page's camera as a view-dependent subscription's View (tessera.proto,
// docs/PROTOCOL.md section 16), and when to send it: when it moved, at most
// every SEND_INTERVAL_MS (the server applies one per --view-interval-ms
// anyway), and never while the view is frozen.
const SEND_INTERVAL_MS = 50;

// camera: a three.js PerspectiveCamera (world matrix current); width and
// height in pixels.
export function viewOfCamera(camera, width, height, tolerancePixels) {
  const e = camera.matrixWorld.elements;
  // Columns of the world matrix: x right, y up, z back.
  const up = { x: e[4], y: e[5], z: e[6] };
  const forward = { x: -e[8], y: -e[9], z: -e[10] };
  return {
    eye: { x: camera.position.x, y: camera.position.y, z: camera.position.z },
    forward,
    up,
    orthographic: false,
    fov_y_radians: (camera.fov * Math.PI) / 180,
    ortho_height: 0,
    near_distance: camera.near,
    width: Math.max(1, Math.round(width)),
    height: Math.max(1, Math.round(height)),
    tolerance_pixels: tolerancePixels,
  };
}

function sameView(a, b) {
  if (!a || !b) return false;
  const close = (p, q, eps) => Math.abs(p.x - q.x) <= eps && Math.abs(p.y - q.y) <= eps && Math.abs(p.z - q.z) <= eps;
  const scale = Math.max(1e-9, Math.hypot(a.eye.x, a.eye.y, a.eye.z), 1);
  return close(a.eye, b.eye, 1e-5 * scale) && close(a.forward, b.forward, 1e-6) && close(a.up, b.up, 1e-6) &&
    a.width === b.width && a.height === b.height && a.tolerance_pixels === b.tolerance_pixels &&
    a.fov_y_radians === b.fov_y_radians;
}

export class ViewSender {
  // send(view): the session's setView, false when it could not go now.
  constructor(send) {
    this.send = send;
    this.last = null;
    this.lastAt = -Infinity;
    this.frozen = false;
    this.pending = false; // moved since the view last sent
  }

  // The camera now: sent if it moved and the interval passed; true while
  // a moved camera waits for the interval (ask again later).
  offer(view, now = performance.now()) {
    if (this.frozen) return false;
    this.pending = !sameView(view, this.last);
    if (!this.pending) return false;
    if (now - this.lastAt < SEND_INTERVAL_MS) return true;
    if (!this.send(view)) return true;
    this.last = view;
    this.lastAt = now;
    this.pending = false;
    return false;
  }
}
