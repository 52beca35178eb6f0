// Fit to view (tessera-view's OrbitCamera::fit, client/view/camera.cc): from
// the current viewing direction, the camera moves to the distance and
// lateral offset at which the projection of every surface point is centred
// and fills FILL of the frame in its tighter dimension (a little less than
// tessera-view's 86%: the page's panel is wider than its HUD). Solved per axis
// under perspective: fitting a bounding sphere or centring the box leaves
// long models small or off-centre. The orbit then turns about the box's
// centre, and the clipping planes follow the model's size. `reservedTop`,
// a fraction of the frame's height that a panel covers at the top, is left
// free: the model is fitted into the rows below it and centred there.
import * as THREE from 'three';

const FILL = 0.8;

// Per screen axis, with x across and z towards the eye from the centre: a
// point is inside the frame when x - e lies within +-k (d - z). Over all
// points that bounds e to [max(x + k z) - k d, min(x - k z) + k d], which is
// not empty from d = (max(x + k z) - min(x - k z)) / 2k on.
class Extent {
  constructor(k) {
    this.k = k;
    this.hi = -Infinity;
    this.lo = Infinity;
    this.zHi = 0;
    this.zLo = 0;
  }

  add(x, z) {
    if (x + this.k * z > this.hi) { this.hi = x + this.k * z; this.zHi = z; }
    if (x - this.k * z < this.lo) { this.lo = x - this.k * z; this.zLo = z; }
  }

  distance() {
    return (this.hi - this.lo) / (2 * this.k);
  }

  // The offset that leaves the two extreme points equally far from the
  // frame's edges once projected, the slack shared by their depths.
  offset(d) {
    const low = this.hi - this.k * d, high = this.lo + this.k * d;
    const nearHi = d - this.zHi, nearLo = d - this.zLo;
    return low + ((high - low) * nearHi) / Math.max(nearHi + nearLo, 1e-9);
  }
}

// points: a flat array (or several) of x, y, z; box: their THREE.Box3.
export function fitCamera(camera, controls, box, pointArrays, reservedTop = 0) {
  const centre = box.getCenter(new THREE.Vector3());
  const radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 1e-6);
  const back = camera.position.clone().sub(controls.target);
  if (back.lengthSq() === 0) back.set(1, 0.8, 1.3);
  back.normalize();
  const right = new THREE.Vector3().crossVectors(camera.up, back).normalize();
  const up = new THREE.Vector3().crossVectors(back, right);
  const top = Math.min(Math.max(reservedTop, 0), 0.5);
  const halfY = Math.tan(THREE.MathUtils.degToRad(camera.fov / 2));
  const tanY = halfY * FILL;
  // The free rows span normalized heights -1 .. 1 - 2 top: half of them is
  // (1 - top) of the frame's, centred at -top.
  const across = new Extent(tanY * camera.aspect), upward = new Extent(tanY * (1 - top));
  const q = new THREE.Vector3();
  for (const points of pointArrays) {
    for (let i = 0; i < points.length; i += 3) {
      q.set(points[i] - centre.x, points[i + 1] - centre.y, points[i + 2] - centre.z);
      const z = q.dot(back);
      across.add(q.dot(right), z);
      upward.add(q.dot(up), z);
    }
  }
  const d = Math.max(across.distance(), upward.distance(), radius * 0.05);
  // Looking at a point top x the frame's half height above the model's centre
  // puts that centre at height -top on the screen.
  const target = centre.clone().addScaledVector(right, across.offset(d))
    .addScaledVector(up, upward.offset(d) + top * halfY * d);
  controls.target.copy(target);
  camera.position.copy(target).addScaledVector(back, d);
  camera.near = radius / 100;
  camera.far = d + radius * 100;
  camera.updateProjectionMatrix();
  controls.minDistance = radius * 0.05;
  controls.maxDistance = radius * 40;
  controls.update();
}
