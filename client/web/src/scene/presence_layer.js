// The marks that show who else selected what (session/presence.js keeps the
// list): each other participant's selected vertices as points of their own
// colour at the vertices' limit positions, and this viewer's own picks.
import * as THREE from 'three';
import { rimmedDisc } from './sprites.js';

// A colour per session, the same on every viewer: hues spread by the golden
// angle so that neighbouring session ids differ.
export function sessionColour(sessionId) {
  const hue = (Number(BigInt(sessionId) % 360n) * 137.508) % 360;
  return new THREE.Color().setHSL(hue / 360, 0.85, 0.6);
}

// Screen-sized round points drawn over the surface (no depth test: a
// selection behind the model still shows, as a collaborator's cursor would).
export class PresenceLayer {
  // onChange: the view must draw again.
  constructor(scene, onChange) {
    this.onChange = onChange;
    this.geometry = new THREE.BufferGeometry();
    this.material = new THREE.PointsMaterial({
      size: 11, sizeAttenuation: false, vertexColors: true, depthTest: false, transparent: true,
      map: rimmedDisc({ rim: '#202428', fill: '#ffffff', rimInset: 2, discInset: 10 }),
      alphaTest: 0.5,
    });
    this.points = new THREE.Points(this.geometry, this.material);
    this.points.renderOrder = 10;
    this.points.frustumCulled = false;
    scene.add(this.points);
  }

  // others: [{sessionId, selection}] of the other participants, and this
  // viewer's own picks; positionOf(id) -> [x, y, z] or null.
  update(others, own, positionOf) {
    const positions = [], colours = [];
    const add = (id, colour) => {
      const p = positionOf(id);
      if (!p) return;
      positions.push(p[0], p[1], p[2]);
      colours.push(colour.r, colour.g, colour.b);
    };
    for (const c of others) for (const id of c.selection) add(id, sessionColour(c.sessionId));
    const mine = new THREE.Color(1, 0.25, 0.2);
    for (const id of own) add(id, mine);
    this.geometry.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
    this.geometry.setAttribute('color', new THREE.Float32BufferAttribute(colours, 3));
    this.geometry.computeBoundingSphere();
    this.onChange();
  }
}

