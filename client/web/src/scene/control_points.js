// The control vertices of the level being edited, drawn as small dots at
// their limit positions, and a ring around the one under the pointer, so
// that the user sees what a press will pick. Beyond MAX_DOTS the dots are
// left out (they would hide the surface); the hover ring still shows.
import * as THREE from 'three';
import { canvasSprite, rimmedDisc } from './sprites.js';

const MAX_DOTS = 4000;

const dot = () => rimmedDisc({ rim: '#1b2027', fill: '#f4f1e8', rimInset: 4, discInset: 16 });

const ring = () => canvasSprite((g, s) => {
  g.beginPath();
  g.arc(s / 2, s / 2, s / 2 - 8, 0, 2 * Math.PI);
  g.lineWidth = 7;
  g.strokeStyle = '#ffd34d';
  g.stroke();
});

export class ControlPointsLayer {
  // onChange: the view must draw again.
  constructor(scene, onChange) {
    this.onChange = onChange;
    this.dots = new THREE.Points(new THREE.BufferGeometry(), new THREE.PointsMaterial({
      size: 7, sizeAttenuation: false, map: dot(), alphaTest: 0.5, transparent: true, depthWrite: false,
    }));
    this.dots.frustumCulled = false;
    // A dot lies on the surface it marks; pulled towards the eye by 0.3% of
    // its distance (in view space, so at any zoom) it wins the depth test
    // there and is still hidden by the parts in front of it.
    this.dots.material.onBeforeCompile = (shader) => {
      shader.vertexShader = shader.vertexShader.replace('#include <project_vertex>',
        '#include <project_vertex>\n  gl_Position = projectionMatrix * vec4(mvPosition.xyz * 0.997, 1.0);');
    };
    this.dots.renderOrder = 5;
    this.hover = new THREE.Points(new THREE.BufferGeometry(), new THREE.PointsMaterial({
      size: 22, sizeAttenuation: false, map: ring(), alphaTest: 0.3, transparent: true, depthTest: false,
    }));
    this.hover.frustumCulled = false;
    this.hover.renderOrder = 11;
    this.visible = true;
    scene.add(this.dots, this.hover);
  }

  // vertices: the control vertices of the level ({position}).
  setVertices(vertices) {
    const shown = this.visible && vertices.length <= MAX_DOTS ? vertices : [];
    this.dots.geometry.setAttribute('position', new THREE.Float32BufferAttribute(shown.flatMap((v) => v.position), 3));
    this.count = vertices.length;
    this.drawn = shown.length > 0;
    this.onChange();
  }

  setHover(vertex) {
    this.hover.geometry.setAttribute('position', new THREE.Float32BufferAttribute(vertex ? vertex.position : [], 3));
    this.onChange();
  }
}
