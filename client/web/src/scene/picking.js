// Which control vertex a pointer names: a ray from the camera meets the
// region meshes, and of the control vertices of the chosen level the one
// nearest to that hit point is picked (at the finest level, the nearest
// corner of the hit triangle). It must also lie within a few pixels of the
// pointer on screen, so that a press elsewhere on the surface orbits.
// Also: screen positions of vertices, for the test hook and the HUD, and a
// visibility test (front-facing and not hidden behind another part).
import * as THREE from 'three';

const PICK_RADIUS_PX = 18;

export class Picker {
  constructor(sceneView, vertices) {
    this.view = sceneView;
    this.vertices = vertices;
    this.raycaster = new THREE.Raycaster();
  }

  canvasRect() {
    return this.view.renderer.domElement.getBoundingClientRect();
  }

  // Client (CSS) pixels to normalized device coordinates.
  ndc(clientX, clientY) {
    const rect = this.canvasRect();
    return new THREE.Vector2(((clientX - rect.left) / rect.width) * 2 - 1, -((clientY - rect.top) / rect.height) * 2 + 1);
  }

  // The first surface point under the pointer, or null.
  hit(clientX, clientY) {
    this.raycaster.setFromCamera(this.ndc(clientX, clientY), this.view.camera);
    const hits = this.raycaster.intersectObjects(this.view.regionMeshes(), false);
    return hits.length > 0 ? hits[0] : null;
  }

  // Client pixels of a world point, or null behind the camera.
  toScreen(position) {
    const p = new THREE.Vector3(...position).project(this.view.camera);
    if (p.z > 1 || p.z < -1) return null;
    const rect = this.canvasRect();
    return { x: rect.left + ((p.x + 1) / 2) * rect.width, y: rect.top + ((1 - p.y) / 2) * rect.height };
  }

  // Whether a vertex faces the camera and nothing else lies in front of it.
  visible(vertex) {
    const eye = this.view.camera.position;
    const p = new THREE.Vector3(...vertex.position);
    const toEye = eye.clone().sub(p);
    if (toEye.dot(new THREE.Vector3(...vertex.normal)) <= 0) return false;
    const screen = this.toScreen(vertex.position);
    if (!screen) return false;
    const hit = this.hit(screen.x, screen.y);
    const distance = toEye.length();
    return hit !== null && hit.distance >= distance - 1e-3 * Math.max(distance, 1);
  }

  // The control vertex of `level` under the pointer, or null. At the
  // profile's finest level every displayed vertex is one, and this is the
  // hit triangle's nearest corner.
  pick(clientX, clientY, level) {
    const hit = this.hit(clientX, clientY);
    if (!hit) return null;
    let best = null, bestDistance = Infinity;
    const point = new THREE.Vector3();
    for (const v of this.vertices.atLevel(level)) {
      const d = hit.point.distanceToSquared(point.set(v.position[0], v.position[1], v.position[2]));
      if (d < bestDistance) { bestDistance = d; best = v; }
    }
    if (!best) return null;
    const screen = this.toScreen(best.position);
    if (!screen || Math.hypot(screen.x - clientX, screen.y - clientY) > PICK_RADIUS_PX) return null;
    return best;
  }

  // Where the pointer drags a vertex: the ray meets the plane through the
  // vertex's starting point that faces the camera (tessera-view's
  // dragTarget).
  dragTarget(clientX, clientY, anchor) {
    this.raycaster.setFromCamera(this.ndc(clientX, clientY), this.view.camera);
    const normal = this.view.camera.getWorldDirection(new THREE.Vector3());
    const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(normal, new THREE.Vector3(...anchor));
    const target = this.raycaster.ray.intersectPlane(plane, new THREE.Vector3());
    return target ? [target.x, target.y, target.z] : anchor;
  }

  // The visible control vertex of `level` nearest to the canvas centre.
  nearCentre(level) {
    const rect = this.canvasRect();
    const cx = rect.left + rect.width / 2, cy = rect.top + rect.height / 2;
    const candidates = [];
    for (const v of this.vertices.atLevel(level)) {
      const s = this.toScreen(v.position);
      if (s) candidates.push({ v, s, d: Math.hypot(s.x - cx, s.y - cy) });
    }
    candidates.sort((a, b) => a.d - b.d);
    for (const c of candidates.slice(0, 64)) if (this.visible(c.v)) return { vertex: c.v, screen: c.s };
    return null;
  }
}
