// The 3D view (three.js): the regions as meshes (region_batches.js packs
// them into a few large ones and rebuilds those a snapshot or delta
// touches); smooth shading with the limit normals the regions carry; lights
// that follow the camera so that whatever side is shown is lit; a wireframe
// overlay and region colours as toggles; orbit, pan and zoom by
// OrbitControls. Frames are drawn when something changed (the camera, the
// regions, a marker, a toggle, the size), not at every display refresh: a
// still model costs nothing, and a software renderer (headless tests) keeps
// up with the deltas.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { RoomEnvironment } from 'three/examples/jsm/environments/RoomEnvironment.js';
import { fitCamera } from './camera_fit.js';
import { RegionBatches, regionColour, levelColour } from './region_batches.js';
import { closeCracks, shownTiles } from './tile_assembly.js';

const SURFACE_COLOUR = 0xa7b0bd;
const WIRE_COLOUR = 0x161c24;

// Whether WebGL runs on the CPU (SwiftShader, llvmpipe): no GPU to spend.
function softwareRenderer(renderer) {
  const gl = renderer.getContext();
  const info = gl.getExtension('WEBGL_debug_renderer_info');
  const name = info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
  return /swiftshader|llvmpipe|software/i.test(String(name));
}

export class SceneView {
  // tiles: a view-dependent subscription's tiles, shown with their cracks
  // closed and coloured by level with the region-colour toggle.
  constructor(container, tiles = false) {
    this.container = container;
    this.tiles = tiles;
    this.shownPositions = new Map(); // tiles: region id -> the positions shown
    // Pixels at the top of the frame a panel covers: fit-to-view leaves them free.
    this.reservedTop = () => 0;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, alpha: true, powerPreference: 'high-performance' });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    this.renderer.outputColorSpace = THREE.SRGBColorSpace;
    this.renderer.toneMapping = THREE.ACESFilmicToneMapping;
    this.renderer.toneMappingExposure = 1.0;
    this.renderer.setClearColor(0x000000, 0); // the page's gradient shows through
    container.appendChild(this.renderer.domElement);

    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(30, 1, 0.01, 1000);
    this.camera.position.set(2.6, 2.1, 3.4);
    this.scene.add(this.camera);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.enableDamping = true;
    // The page's frame request; set by main.js. User input on the controls
    // asks for frames too; while damping, each drawn frame asks for the next.
    this.onInvalidate = () => {};
    this.controls.addEventListener('change', () => this.invalidate());
    // Called before each frame is drawn, the camera placed: for what depends
    // on the camera (main.js lays out the control cage's lines).
    this.beforeRender = () => {};
    this.controls.dampingFactor = 0.12;
    this.controls.screenSpacePanning = true;
    this.addLights();

    this.root = new THREE.Group(); // region meshes
    this.scene.add(this.root);
    this.material = new THREE.MeshStandardMaterial({
      color: SURFACE_COLOUR, roughness: 0.48, metalness: 0.04,
      // Pushed back a little so the wireframe overlay wins the depth test.
      polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
    });
    this.colouredMaterial = this.material.clone();
    this.colouredMaterial.color.set(0xffffff);
    this.colouredMaterial.vertexColors = true;
    this.batches = new RegionBatches((batch) => this.addBatch(batch), (batch) => this.dropBatch(batch),
      tiles ? levelColour : regionColour);
    this.wireMaterial = new THREE.MeshBasicMaterial({ color: WIRE_COLOUR, wireframe: true, transparent: true, opacity: 0.35 });
    this.wireframe = false;
    this.regionColours = false;
    this.frames = 0;
    this.dirty = true;
    this.fitted = false;
    this.resize();
    new ResizeObserver(() => this.resize()).observe(container);
  }

  // A hemisphere fixed to the world (sky above, warm ground below), a warm
  // key light from the upper left, a cool fill from the right at a third of
  // its strength and a rim light from behind, all three fixed to the
  // camera; a soft studio environment for the highlights.
  addLights() {
    this.scene.add(new THREE.HemisphereLight(0xdfe8ff, 0x3b332b, 0.55));
    const cameraLight = (colour, intensity, x, y, z) => {
      const light = new THREE.DirectionalLight(colour, intensity);
      light.position.set(x, y, z);
      light.target.position.set(0, 0, -1);
      this.camera.add(light);
      this.camera.add(light.target);
    };
    cameraLight(0xfff1de, 2.0, -0.7, 1.6, 0.7); // key
    cameraLight(0xcfe0ff, 0.55, 1.5, -0.1, 0.5); // fill
    cameraLight(0xffffff, 1.6, 0.3, 0.9, -1.7); // rim
    // The soft environment light is prefiltered once (PMREM): milliseconds
    // on a GPU, but 5.3 s of main-thread time under a software renderer
    // (SwiftShader, measured in headless Chromium), which would hold the
    // first picture back that long. Without a GPU the four lights above
    // carry the shading alone.
    if (!softwareRenderer(this.renderer)) {
      const pmrem = new THREE.PMREMGenerator(this.renderer);
      this.scene.environment = pmrem.fromScene(new RoomEnvironment(), 0.04).texture;
      this.scene.environmentIntensity = 0.25;
      pmrem.dispose();
    }
  }

  resize() {
    const width = this.container.clientWidth || 1, height = this.container.clientHeight || 1;
    this.renderer.setSize(width, height, false);
    this.renderer.domElement.style.width = '100%';
    this.renderer.domElement.style.height = '100%';
    this.camera.aspect = width / height;
    this.camera.updateProjectionMatrix();
    this.invalidate();
  }

  // Something on screen changed: draw at the next animation frame (the
  // page asks for one through onInvalidate).
  invalidate() {
    this.dirty = true;
    this.onInvalidate();
  }

  get triangles() {
    return this.batches.triangles;
  }

  addBatch(batch) {
    batch.mesh = new THREE.Mesh(batch.geometry, this.regionColours ? this.colouredMaterial : this.material);
    batch.wire = new THREE.Mesh(batch.geometry, this.wireMaterial);
    batch.wire.visible = this.wireframe;
    batch.wire.raycast = () => {}; // picking sees the surface only
    this.root.add(batch.mesh, batch.wire);
  }

  dropBatch(batch) {
    this.root.remove(batch.mesh, batch.wire);
  }

  // Tiles or regions from now on: set before the subscription's first
  // picture (a morph document falls back to a profile, main.js).
  useTiles(on) {
    this.tiles = on;
    this.batches.colourOf = on ? levelColour : regionColour;
    this.shownPositions.clear();
  }

  // A change of session/document_view.js: the whole set, or the regions a delta
  // changed and removed. Geometry is rebuilt before the next frame.
  apply(change, regions) {
    this.batches.expectRegions(regions.size);
    if (this.tiles && (change.kind === 'snapshot' || change.kind === 'delta')) {
      this.applyTiles(regions);
    } else if (change.kind === 'snapshot') {
      for (const id of this.batches.ids()) if (!regions.has(id)) this.batches.remove(id);
      for (const [id, region] of regions) this.batches.set(id, region);
    } else if (change.kind === 'delta') {
      for (const id of change.removed) this.batches.remove(id);
      for (const id of change.changed) if (regions.has(id)) this.batches.set(id, regions.get(id));
    }
    this.batches.flush();
    this.invalidate();
    if (!this.fitted && this.batches.batches.length > 0) this.fit();
  }

  // Every tile held, its cracks towards coarser neighbours closed over the
  // whole set (tile_assembly.js): a tile whose closed positions did not
  // change keeps its buffer. While the surface's preview is held, it alone
  // (docs/WEB_VIEWER.md "Views").
  applyTiles(held) {
    const regions = shownTiles(held);
    for (const id of this.batches.ids()) {
      if (!regions.has(id)) this.batches.remove(id), this.shownPositions.delete(id);
    }
    const { positions } = closeCracks(regions);
    const same = (a, b) => a === b || (a && b && a.length === b.length && a.every((x, i) => x === b[i]));
    for (const [id, region] of regions) {
      const p = positions.get(id);
      const shown = this.shownPositions.get(id);
      if (shown && shown.region === region && same(shown.positions, p)) continue;
      this.batches.set(id, p === region.positions ? region : { ...region, positions: p });
      this.shownPositions.set(id, { region, positions: p });
    }
  }

  // The ids of the regions drawn (with a view, the preview alone while held).
  shownIds() {
    return this.batches.ids();
  }

  bounds() {
    const box = new THREE.Box3();
    for (const { geometry } of this.batches.batches) if (geometry) box.union(geometry.boundingBox);
    return box;
  }

  fit() {
    const box = this.bounds();
    if (box.isEmpty()) return;
    const points = this.batches.batches.filter((b) => b.geometry).map((b) => b.geometry.getAttribute('position').array);
    const height = this.renderer.domElement.clientHeight || 1;
    fitCamera(this.camera, this.controls, box, points, this.reservedTop() / height);
    this.fitted = true;
    this.invalidate();
  }

  setWireframe(on) {
    this.wireframe = on;
    for (const { wire } of this.batches.batches) if (wire) wire.visible = on;
    this.invalidate();
  }

  setRegionColours(on) {
    this.regionColours = on;
    for (const { mesh } of this.batches.batches) if (mesh) mesh.material = on ? this.colouredMaterial : this.material;
    this.invalidate();
  }

  // Draws a frame if the camera moved (damping goes on after the pointer
  // stops) or something was invalidated; true when it drew.
  renderIfNeeded() {
    const moved = this.controls.update();
    if (!moved && !this.dirty) return false;
    this.dirty = false;
    this.beforeRender();
    this.renderer.render(this.scene, this.camera);
    ++this.frames;
    return true;
  }

  regionMeshes() {
    return this.batches.batches.filter((b) => b.mesh).map((b) => b.mesh);
  }
}
