// Point-sprite textures drawn once into a small canvas: the control-vertex
// dots (control_points.js) and collaborators' picks (presence_layer.js).
import * as THREE from 'three';

const SIZE = 64;

export function canvasSprite(draw) {
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = SIZE;
  draw(canvas.getContext('2d'), SIZE);
  const texture = new THREE.CanvasTexture(canvas);
  texture.colorSpace = THREE.SRGBColorSpace;
  return texture;
}

// A filled disc inside a darker rim; the insets are pixels from the
// canvas's edge to the rim's and to the disc's outer circles.
export function rimmedDisc({ rim, fill, rimInset, discInset }) {
  return canvasSprite((g, s) => {
    g.beginPath();
    g.arc(s / 2, s / 2, s / 2 - rimInset, 0, 2 * Math.PI);
    g.fillStyle = rim;
    g.fill();
    g.beginPath();
    g.arc(s / 2, s / 2, s / 2 - discInset, 0, 2 * Math.PI);
    g.fillStyle = fill;
    g.fill();
  });
}
