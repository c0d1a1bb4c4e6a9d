// viewer.js: the three.js view: one BufferGeometry of the points (typed
// arrays, no per-point objects, so a million points is fine), drawn as
// round points, or as a lit surface when the input had faces; sink markers
// on top; orbit controls; rendering only when something changed; picking
// the point under a pixel.

import * as THREE from 'three';
import { OrbitControls } from './vendor/OrbitControls.js';

// A point is picked within this many CSS pixels even when drawn smaller.
const PICK_MIN_PX = 3;

// A round sprite: white disc, with a dark rim when `rim`, on black (used as
// an alpha map for plain points, so their edges keep the point's colour).
function discTexture(rim) {
  const size = 64;
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = size;
  const g = canvas.getContext('2d');
  if (!rim) {
    g.fillStyle = '#000000';
    g.fillRect(0, 0, size, size);
  }
  g.beginPath();
  g.arc(size / 2, size / 2, size / 2 - 2, 0, 2 * Math.PI);
  g.fillStyle = '#ffffff';
  g.fill();
  if (rim) {
    g.lineWidth = 10;
    g.strokeStyle = '#1b1f24';
    g.stroke();
  }
  return new THREE.CanvasTexture(canvas);
}

export class Viewer {
  constructor(container) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio);
    this.renderer.setClearColor(0xf4f5f7);
    // Colours are shown as given (sRGB bytes), so they match the legend.
    this.renderer.outputColorSpace = THREE.LinearSRGBColorSpace;
    container.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
    this.scene.add(this.camera);
    this.scene.add(new THREE.AmbientLight(0xffffff, 1.2));
    const light = new THREE.DirectionalLight(0xffffff, 1.8);
    light.position.set(1, 1, 2);
    this.camera.add(light);
    this.controls = this.makeControls();
    this.pointMaterial = new THREE.PointsMaterial({
      vertexColors: true, alphaMap: discTexture(false), alphaTest: 0.5, sizeAttenuation: true,
    });
    this.sinkMaterial = new THREE.PointsMaterial({
      vertexColors: true, map: discTexture(true), alphaTest: 0.5, sizeAttenuation: false,
      size: 16, depthTest: false,
    });
    this.surfaceMaterial = new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide });
    this.pointScale = 1;
    this.objects = [];
    this.raycaster = new THREE.Raycaster();
    this.viewProjection = new THREE.Matrix4();
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  // OrbitControls takes the camera's up vector when made.
  makeControls() {
    const controls = new OrbitControls(this.camera, this.renderer.domElement);
    controls.addEventListener('change', () => this.requestRender());
    return controls;
  }

  resize() {
    const { clientWidth: w, clientHeight: h } = this.container;
    if (!w || !h) return;
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.requestRender();
  }

  requestRender() {
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame(() => {
      this.pending = false;
      this.renderer.render(this.scene, this.camera);
    });
  }

  clear() {
    for (const o of this.objects) {
      this.scene.remove(o);
      o.geometry.dispose();
    }
    this.objects = [];
  }

  // positions: Float32Array #P*3; faces: Uint32Array #F*3 or null.
  // Returns the colour array (Uint8Array #P*3) to fill, then call colorsChanged().
  setShape(positions, faces) {
    this.clear();
    const count = positions.length / 3;
    this.colors = new Uint8Array(3 * count);
    this.positionAttr = new THREE.BufferAttribute(positions, 3);
    this.colorAttr = new THREE.BufferAttribute(this.colors, 3, true);
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', this.positionAttr);
    geometry.setAttribute('color', this.colorAttr);
    geometry.computeBoundingSphere();
    geometry.computeBoundingBox();
    this.sphere = geometry.boundingSphere;
    this.box = geometry.boundingBox;
    this.points = new THREE.Points(geometry, this.pointMaterial);
    this.surface = faces ? this.makeSurface(faces) : null;
    this.objects.push(this.points);
    this.scene.add(this.points);
    this.baseSize = (4 * this.sphere.radius) / Math.sqrt(Math.max(count, 1));
    this.setPointScale(this.pointScale);
    this.fit();
    return this.colors;
  }

  makeSurface(faces) {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', this.positionAttr);
    geometry.setAttribute('color', this.colorAttr);
    geometry.setIndex(new THREE.BufferAttribute(faces, 1));
    geometry.computeVertexNormals();
    const mesh = new THREE.Mesh(geometry, this.surfaceMaterial);
    this.objects.push(mesh);
    this.scene.add(mesh);
    this.points.visible = false;
    return mesh;
  }

  hasSurface() {
    return Boolean(this.surface);
  }

  // Surface or points, when the input had faces.
  showSurface(on) {
    if (!this.surface) return;
    this.surface.visible = on;
    this.points.visible = !on;
    this.requestRender();
  }

  colorsChanged() {
    this.colorAttr.needsUpdate = true;
    this.requestRender();
  }

  setPointScale(scale) {
    this.pointScale = scale;
    this.pointMaterial.size = (this.baseSize || 1) * scale;
    this.requestRender();
  }

  // sinks: point indices; rgb: Uint8Array #sinks*3.
  setSinks(sinks, rgb, visible) {
    if (this.sinks) {
      this.scene.remove(this.sinks);
      this.sinks.geometry.dispose();
      this.objects = this.objects.filter((o) => o !== this.sinks);
    }
    const pos = new Float32Array(3 * sinks.length);
    sinks.forEach((p, i) => pos.set(this.positionAttr.array.subarray(3 * p, 3 * p + 3), 3 * i));
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    geometry.setAttribute('color', new THREE.BufferAttribute(rgb, 3, true));
    this.sinks = new THREE.Points(geometry, this.sinkMaterial);
    this.sinks.renderOrder = 1;
    this.sinks.visible = visible;
    this.objects.push(this.sinks);
    this.scene.add(this.sinks);
    this.requestRender();
  }

  showSinks(on) {
    if (this.sinks) this.sinks.visible = on;
    this.requestRender();
  }

  // Centres the shape and backs the camera off until it fills the view,
  // looking slightly obliquely at its broadest side (along the axis of
  // least extent), the axis of middle extent up.
  fit() {
    if (!this.sphere) return;
    const { center, radius } = this.sphere;
    const r = radius || 1;
    const half = THREE.MathUtils.degToRad(this.camera.fov / 2);
    const distance = (1.1 * r) / Math.sin(Math.min(half, Math.atan(Math.tan(half) * this.camera.aspect)));
    const size = this.box.getSize(new THREE.Vector3()).toArray();
    const order = [0, 1, 2].sort((a, b) => size[a] - size[b]);
    const axis = (i) => new THREE.Vector3().setComponent(order[i], 1);
    const [az, el] = [THREE.MathUtils.degToRad(25), THREE.MathUtils.degToRad(15)];
    const view = axis(0).multiplyScalar(Math.cos(az)).addScaledVector(axis(2), Math.sin(az))
      .multiplyScalar(Math.cos(el)).addScaledVector(axis(1), Math.sin(el));
    if (!this.camera.up.equals(axis(1))) {
      this.camera.up.copy(axis(1));
      this.controls.dispose();
      this.controls = this.makeControls();
    }
    this.camera.position.copy(center).addScaledVector(view, distance);
    this.camera.near = distance / 100;
    this.camera.far = distance * 10;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(center);
    this.controls.update();
    this.requestRender();
  }

  // The point drawn at (x, y), CSS pixels from the canvas's top left, or
  // -1: on the surface the nearest corner of the triangle hit, as points
  // the nearest to the camera of those whose disc covers (x, y).
  pick(x, y) {
    const { clientWidth: w, clientHeight: h } = this.renderer.domElement;
    if (!this.points || !w || !h) return -1;
    this.camera.updateMatrixWorld();
    const ndcX = (2 * x) / w - 1, ndcY = 1 - (2 * y) / h;
    if (this.surface && this.surface.visible) return this.pickSurface(ndcX, ndcY);
    return this.pickPoints(ndcX, ndcY, w, h);
  }

  // One pass over the points in clip space, no allocation.  A point at
  // depth d is drawn as a disc of radius size * h / (4 d) CSS pixels
  // (three's size attenuation), so with offsets scaled by d the radius is
  // the constant size * h / 4.
  pickPoints(ndcX, ndcY, w, h) {
    const e = this.viewProjection.multiplyMatrices(this.camera.projectionMatrix, this.camera.matrixWorldInverse).elements;
    const pos = this.positionAttr.array;
    const disc = (this.pointMaterial.size * h) / 4;
    let best = -1, bestDepth = Infinity;
    for (let i = 0; i < pos.length; i += 3) {
      const x = pos[i], y = pos[i + 1], z = pos[i + 2];
      const depth = e[3] * x + e[7] * y + e[11] * z + e[15];
      if (depth <= 0 || depth >= bestDepth) continue;
      const dx = (e[0] * x + e[4] * y + e[8] * z + e[12] - ndcX * depth) * (w / 2);
      const dy = (e[1] * x + e[5] * y + e[9] * z + e[13] - ndcY * depth) * (h / 2);
      const r = Math.max(disc, PICK_MIN_PX * depth);
      if (dx * dx + dy * dy <= r * r) {
        best = i / 3;
        bestDepth = depth;
      }
    }
    return best;
  }

  pickSurface(ndcX, ndcY) {
    this.raycaster.setFromCamera(new THREE.Vector2(ndcX, ndcY), this.camera);
    const hit = this.raycaster.intersectObject(this.surface, false)[0];
    if (!hit) return -1;
    const corner = new THREE.Vector3();
    const away = (v) => corner.fromBufferAttribute(this.positionAttr, v).distanceToSquared(hit.point);
    return [hit.face.a, hit.face.b, hit.face.c].reduce((a, b) => (away(b) < away(a) ? b : a));
  }

  // Where point i is drawn: {x, y} CSS pixels from the canvas's top left.
  screenPosition(i) {
    this.camera.updateMatrixWorld();
    const p = new THREE.Vector3().fromBufferAttribute(this.positionAttr, i).project(this.camera);
    const { clientWidth: w, clientHeight: h } = this.renderer.domElement;
    return { x: ((p.x + 1) / 2) * w, y: ((1 - p.y) / 2) * h };
  }

  snapshot() {
    this.renderer.render(this.scene, this.camera);
    return this.renderer.domElement.toDataURL('image/png');
  }
}
