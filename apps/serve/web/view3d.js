// view3d.js — the three.js view: the swatch's yarns as tubes (one mesh per yarn, so the canvas's
// data-yarns is what is drawn), or the garment's GLB; orbit controls, front or back light.
import * as THREE from 'three';
import {OrbitControls} from 'three/addons/controls/OrbitControls.js';
import {GLTFLoader} from 'three/addons/loaders/GLTFLoader.js';

const YARN = new THREE.Color(0xe9dcc3);  // undyed wool, for charts without colours

// A tube around a polyline (points flat xyz, times pointUnit), rings along parallel-transported
// frames; per-vertex colours from `colours` (flat linear rgb, times colourUnit) when given.
function tubeGeometry(points, closed, colours, radius, pointUnit, colourUnit, sides = 8) {
  const n = points.length / 3;
  const p = (i) => new THREE.Vector3(points[3 * i], points[3 * i + 1], points[3 * i + 2]).multiplyScalar(pointUnit);
  const rings = closed ? n + 1 : n;
  const pos = new Float32Array(rings * sides * 3), nor = new Float32Array(rings * sides * 3);
  const col = new Float32Array(rings * sides * 3);
  let normal = null;
  for (let r = 0; r < rings; r++) {
    const i = r % n;
    const prev = closed ? (i - 1 + n) % n : Math.max(i - 1, 0), next = closed ? (i + 1) % n : Math.min(i + 1, n - 1);
    const t = p(next).sub(p(prev)).normalize();
    if (!normal) {
      normal = Math.abs(t.y) < 0.9 ? new THREE.Vector3(0, 1, 0) : new THREE.Vector3(1, 0, 0);
    }
    normal.sub(t.clone().multiplyScalar(t.dot(normal))).normalize();
    const binormal = new THREE.Vector3().crossVectors(t, normal);
    const c = p(i);
    for (let s = 0; s < sides; s++) {
      const a = (2 * Math.PI * s) / sides;
      const d = normal.clone().multiplyScalar(Math.cos(a)).addScaledVector(binormal, Math.sin(a));
      const k = (r * sides + s) * 3;
      pos[k] = c.x + radius * d.x; pos[k + 1] = c.y + radius * d.y; pos[k + 2] = c.z + radius * d.z;
      nor[k] = d.x; nor[k + 1] = d.y; nor[k + 2] = d.z;
      const rgb = colours ? [colours[3 * i] * colourUnit, colours[3 * i + 1] * colourUnit, colours[3 * i + 2] * colourUnit]
                          : [YARN.r, YARN.g, YARN.b];
      col[k] = rgb[0]; col[k + 1] = rgb[1]; col[k + 2] = rgb[2];
    }
  }
  const index = [];
  for (let r = 0; r + 1 < rings; r++) {
    for (let s = 0; s < sides; s++) {
      const a = r * sides + s, b = r * sides + (s + 1) % sides, c = a + sides, d = b + sides;
      index.push(a, b, c, b, d, c);
    }
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(pos, 3));
  g.setAttribute('normal', new THREE.BufferAttribute(nor, 3));
  g.setAttribute('color', new THREE.BufferAttribute(col, 3));
  g.setIndex(index);
  return g;
}

// Is WebGL drawn in software (no GPU: SwiftShader, llvmpipe)? Then the view draws without
// multisampling: on this project's 2-core machine a swatch edit reached the screen in about half
// the time without it (docs/serve.md).
function softwareWebGL() {
  try {
    const gl = document.createElement('canvas').getContext('webgl2');
    if (!gl) return false;
    const info = gl.getExtension('WEBGL_debug_renderer_info');
    const name = String(gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER));
    gl.getExtension('WEBGL_lose_context')?.loseContext();
    return /swiftshader|llvmpipe|softpipe|software/i.test(name);
  } catch {
    return false;
  }
}

export class KnitView {
  constructor(canvas) {
    this.canvas = canvas;
    this.software = softwareWebGL();
    this.renderer = new THREE.WebGLRenderer({canvas, antialias: !this.software, preserveDrawingBuffer: true});
    canvas.dataset.multisampled = String(!this.software);
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0x20242b);
    this.camera = new THREE.PerspectiveCamera(30, 1, 0.001, 100);
    this.camera.position.set(0, 0.12, 0.08);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.listenToKeyEvents(canvas);
    this.controls.enableDamping = false;
    this.controls.addEventListener('change', () => this.draw());
    canvas.addEventListener('keydown', (e) => {
      if (e.key === '+' || e.key === '=') this.zoom(0.9);
      if (e.key === '-') this.zoom(1 / 0.9);
    });
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x404040, 0.8));
    this.light = new THREE.DirectionalLight(0xffffff, 2.2);
    this.scene.add(this.light, this.light.target);
    this.content = new THREE.Group();
    this.scene.add(this.content);
    this.backLight = false;
    // The tubes' outsides only (their faces wind outwards): without a GPU, the frame after a
    // swatch is drawn holds Chromium's GPU thread while software WebGL rasterises it, and the
    // next animation frame (the next edit's yarns) waits for it; drawing the insides too doubled
    // that (0.4-1.7 s per frame at load 5-9, docs/serve.md).
    this.material = new THREE.MeshStandardMaterial({vertexColors: true, roughness: 0.85});
    new ResizeObserver(() => this.resize()).observe(canvas);
    this.resize();
  }

  zoom(factor) {
    const offset = this.camera.position.clone().sub(this.controls.target).multiplyScalar(factor);
    this.camera.position.copy(this.controls.target).add(offset);
    this.controls.update();
  }

  resize() {
    const w = this.canvas.clientWidth, h = this.canvas.clientHeight;
    if (!w || !h) return;
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.draw();
  }

  setBackLight(back) {
    this.backLight = back;
    this.draw();
  }

  clear() {
    for (const child of [...this.content.children]) {
      this.content.remove(child);
      child.traverse((o) => { if (o.geometry) o.geometry.dispose(); });
    }
  }

  // The swatch of /api/swatch: {yarns, radius, size, point_unit, colour_unit, curves: [{closed,
  // points, colours}]} (points and colours integers in their units).
  showSwatch(swatch, frame) {
    this.clear();
    for (const c of swatch.curves) {
      if (c.points.length < 6) continue;
      const tube = tubeGeometry(c.points, c.closed, c.colours, swatch.radius, swatch.point_unit, swatch.colour_unit);
      this.content.add(new THREE.Mesh(tube, this.material));
    }
    this.canvas.dataset.yarns = String(this.content.children.length);
    // Framed again when the swatch's size changes much (another chart), not while it relaxes.
    if (frame || !this.swatchSize || Math.abs(swatch.size - this.swatchSize) > 0.3 * this.swatchSize) {
      this.swatchSize = swatch.size;
      // The swatch lies on y = 0 (front +y): look down on it, a little from the bottom edge.
      const s = swatch.size;
      this.controls.target.set(0, 0, 0);
      this.camera.position.set(0, 2.1 * s, 1.15 * s);
      this.camera.near = s / 100;
      this.camera.far = s * 100;
      this.camera.updateProjectionMatrix();
      this.controls.update();
    }
    this.draw();
  }

  // A garment GLB (line strips of its yarns) and the count the server reported.
  async showGarment(url, yarns, camera) {
    const gltf = await new GLTFLoader().loadAsync(url);
    this.clear();
    this.content.add(gltf.scene);
    this.canvas.dataset.yarns = String(yarns);
    if (camera) {
      this.camera.position.fromArray(camera.eye);
      this.controls.target.fromArray(camera.target);
      this.camera.up.fromArray(camera.up);
      this.camera.fov = camera.fov;
      const d = this.camera.position.distanceTo(this.controls.target);
      this.camera.near = d / 100;
      this.camera.far = d * 100;
      this.camera.updateProjectionMatrix();
      this.controls.update();
    }
    this.draw();
  }

  // The camera as the server's view: {eye, target, up, fov, width, height}.
  view() {
    return {
      eye: this.camera.position.toArray(), target: this.controls.target.toArray(), up: this.camera.up.toArray(),
      fov: this.camera.fov, width: Math.max(1, this.canvas.clientWidth), height: Math.max(1, this.canvas.clientHeight),
    };
  }

  // Renders in the next animation frame, once however many changes came before it.
  draw() {
    if (this.drawPending) return;
    this.drawPending = true;
    requestAnimationFrame(() => {
      this.drawPending = false;
      this.render();
    });
  }

  render() {
    // Front light from over the viewer's shoulder; back light from behind the fabric.
    const eye = this.camera.position.clone().sub(this.controls.target);
    const up = this.camera.up.clone().multiplyScalar(eye.length() * 0.5);
    const dir = this.backLight ? eye.clone().negate() : eye.clone();
    this.light.position.copy(this.controls.target).add(dir).add(up);
    this.light.target.position.copy(this.controls.target);
    const start = performance.now();
    this.renderer.render(this.scene, this.camera);
    this.lastRender = {start, end: performance.now()};
  }
}
