// The two three.js views: the vertex-frame model (handles and frame polylines) and the
// shaded surface. Picking is done in screen space (pixels), so thin lines and small
// handles are as easy to hit at every zoom.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import type { MeshData, Model, Vec3 } from './api';

const FRAME_EDGES = 8;

/** A canvas with its renderer, scene, camera and orbit controls, rendered every frame. */
export class Viewport {
  readonly renderer: THREE.WebGLRenderer;
  readonly scene = new THREE.Scene();
  readonly camera = new THREE.PerspectiveCamera(40, 1, 0.001, 1000);
  controls!: OrbitControls;

  constructor(readonly container: HTMLElement) {
    this.renderer = new THREE.WebGLRenderer({ antialias: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    this.renderer.setClearColor(0xf4f5f7);
    this.container.appendChild(this.renderer.domElement);
    this.camera.up.set(0, 0, 1);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8f99, 1.6));
    const key = new THREE.DirectionalLight(0xffffff, 1.8);
    key.position.set(2, -3, 4);
    this.camera.add(key);
    this.scene.add(this.camera);
    new ResizeObserver(() => this.resize()).observe(this.container);
    this.resize();
  }

  /** Creates the orbit controls; call after adding pointer listeners that must run first. */
  attachControls(): void {
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.enableDamping = true;
    this.controls.dampingFactor = 0.15;
  }

  resize(): void {
    const w = Math.max(1, this.container.clientWidth);
    const h = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(w, h, false);
    this.renderer.domElement.style.width = '100%';
    this.renderer.domElement.style.height = '100%';
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
  }

  /** Looks at a box from the front-right, above (z is up), near enough that its corners
   * just fit the view. */
  fit(box: THREE.Box3): void {
    if (box.isEmpty()) return;
    const center = box.getCenter(new THREE.Vector3());
    const size = Math.max(box.getSize(new THREE.Vector3()).length(), 1e-3);
    const toCamera = new THREE.Vector3(0.55, -1.2, 0.9).normalize();
    const right = new THREE.Vector3().crossVectors(this.camera.up, toCamera).normalize();
    const up = new THREE.Vector3().crossVectors(toCamera, right);
    const tanV = Math.tan(THREE.MathUtils.degToRad(this.camera.fov) / 2);
    const tanH = tanV * this.camera.aspect;
    let distance = 0;
    for (let i = 0; i < 8; ++i) {
      const corner = new THREE.Vector3(
        i & 1 ? box.max.x : box.min.x,
        i & 2 ? box.max.y : box.min.y,
        i & 4 ? box.max.z : box.min.z,
      ).sub(center);
      const toward = corner.dot(toCamera);
      distance = Math.max(
        distance,
        toward + Math.abs(corner.dot(right)) / tanH,
        toward + Math.abs(corner.dot(up)) / tanV,
      );
    }
    distance = Math.max(distance * 1.12, size * 0.1);
    this.camera.position.copy(center).addScaledVector(toCamera, distance);
    this.camera.near = distance / 100;
    this.camera.far = distance * 100;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(center);
    this.controls.update();
  }

  render(): void {
    this.controls.update();
    this.renderer.render(this.scene, this.camera);
  }

  /** A world point in client (page) pixels, and whether it lies in front of the camera. */
  toClient(p: THREE.Vector3): { x: number; y: number; z: number; visible: boolean } {
    const rect = this.renderer.domElement.getBoundingClientRect();
    const q = p.clone().project(this.camera);
    return {
      x: rect.left + ((q.x + 1) / 2) * rect.width,
      y: rect.top + ((1 - q.y) / 2) * rect.height,
      z: q.z,
      visible: q.z > -1 && q.z < 1,
    };
  }

  /** The ray through a client point. */
  ray(clientX: number, clientY: number): THREE.Ray {
    const rect = this.renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(
      ((clientX - rect.left) / rect.width) * 2 - 1,
      -((clientY - rect.top) / rect.height) * 2 + 1,
    );
    const raycaster = new THREE.Raycaster();
    raycaster.setFromCamera(ndc, this.camera);
    return raycaster.ray;
  }
}

export function modelBox(model: Model): THREE.Box3 {
  const box = new THREE.Box3();
  for (const v of model.vertices) box.expandByPoint(new THREE.Vector3(...v));
  return box;
}

/** The median length of the frames' polyline edges. */
function medianEdge(model: Model): number {
  const lengths: number[] = [];
  for (const frame of model.frames)
    for (let e = 0; e < FRAME_EDGES; ++e) {
      const a = model.vertices[frame.vertices[e]], b = model.vertices[frame.vertices[(e + 1) % FRAME_EDGES]];
      lengths.push(Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
    }
  lengths.sort((x, y) => x - y);
  return lengths.length ? Math.max(lengths[lengths.length >> 1], 1e-6) : 1;
}

const FRAME_COLOR = new THREE.Color(0x3d5a80);
const FRAME_SELECTED = new THREE.Color(0xee6c4d);
const HANDLE_COLOR = new THREE.Color(0x293241);
const HANDLE_SELECTED = new THREE.Color(0xee6c4d);

/** Frame polylines (closed, through P1..P8) as one LineSegments with per-vertex colours. */
export class FrameLines {
  readonly object: THREE.LineSegments;
  private positions = new Float32Array(0);
  private colors = new Float32Array(0);

  constructor(opacity = 1) {
    const material = new THREE.LineBasicMaterial({
      vertexColors: true,
      transparent: opacity < 1,
      opacity,
      depthTest: opacity >= 1,
    });
    this.object = new THREE.LineSegments(new THREE.BufferGeometry(), material);
    this.object.renderOrder = 2;
    this.object.frustumCulled = false;
  }

  update(model: Model, selected: ReadonlySet<number>): void {
    const n = model.frames.length * FRAME_EDGES * 2;
    if (this.positions.length !== 3 * n) {
      this.positions = new Float32Array(3 * n);
      this.colors = new Float32Array(3 * n);
      const g = this.object.geometry;
      g.setAttribute('position', new THREE.BufferAttribute(this.positions, 3));
      g.setAttribute('color', new THREE.BufferAttribute(this.colors, 3));
    }
    let k = 0;
    model.frames.forEach((frame, f) => {
      const color = selected.has(f) ? FRAME_SELECTED : FRAME_COLOR;
      for (let e = 0; e < FRAME_EDGES; ++e) {
        for (const idx of [frame.vertices[e], frame.vertices[(e + 1) % FRAME_EDGES]]) {
          const p = model.vertices[idx];
          this.positions.set(p, 3 * k);
          this.colors.set([color.r, color.g, color.b], 3 * k);
          ++k;
        }
      }
    });
    const g = this.object.geometry;
    g.getAttribute('position').needsUpdate = true;
    g.getAttribute('color').needsUpdate = true;
    g.computeBoundingSphere();
  }
}

/** The left view: vertex handles and frame polylines, with screen-space picking. */
export class FrameView extends Viewport {
  readonly lines = new FrameLines();
  private handles: THREE.InstancedMesh | null = null;
  private handleRadius = 0.01;
  private model: Model | null = null;

  constructor(container: HTMLElement) {
    super(container);
    this.scene.add(this.lines.object);
    const grid = new THREE.GridHelper(1, 10, 0xc9ced6, 0xdfe3e8);
    grid.rotation.x = Math.PI / 2;
    grid.name = 'grid';
    this.scene.add(grid);
  }

  setModel(model: Model, selectedVertex: number | null, selectedFrames: ReadonlySet<number>): void {
    this.model = model;
    const count = model.vertices.length;
    if (!this.handles || this.handles.count !== count) {
      if (this.handles) {
        this.scene.remove(this.handles);
        this.handles.geometry.dispose();
      }
      const box = modelBox(model);
      this.handleRadius = Math.min(
        Math.max(box.getSize(new THREE.Vector3()).length(), 1e-3) * 0.009,
        0.12 * medianEdge(model),
      );
      this.handles = new THREE.InstancedMesh(
        new THREE.SphereGeometry(1, 16, 12),
        new THREE.MeshStandardMaterial({ roughness: 0.5, metalness: 0.1 }),
        count,
      );
      this.handles.frustumCulled = false;
      this.scene.add(this.handles);
      const grid = this.scene.getObjectByName('grid');
      if (grid) {
        const size = box.getSize(new THREE.Vector3());
        const s = Math.max(size.x, size.y, 1e-3) * 1.6;
        grid.scale.setScalar(s);
        grid.position.set(...box.getCenter(new THREE.Vector3()).toArray().slice(0, 2) as [number, number], box.min.z);
      }
    }
    const m = new THREE.Matrix4();
    for (let i = 0; i < count; ++i) {
      const r = i === selectedVertex ? this.handleRadius * 1.6 : this.handleRadius;
      m.makeScale(r, r, r).setPosition(...model.vertices[i]);
      this.handles.setMatrixAt(i, m);
      this.handles.setColorAt(i, i === selectedVertex ? HANDLE_SELECTED : HANDLE_COLOR);
    }
    this.handles.instanceMatrix.needsUpdate = true;
    if (this.handles.instanceColor) this.handles.instanceColor.needsUpdate = true;
    this.lines.update(model, selectedFrames);
  }

  /** The vertex whose handle is nearest a client point (within `pixels`), front-most first. */
  vertexAt(x: number, y: number, pixels = 12): number | null {
    if (!this.model) return null;
    let best: number | null = null;
    let bestScore = Infinity;
    this.model.vertices.forEach((v, i) => {
      const s = this.toClient(new THREE.Vector3(...v));
      if (!s.visible) return;
      const d = Math.hypot(s.x - x, s.y - y);
      if (d > pixels) return;
      const score = d + s.z * 1e-3;
      if (score < bestScore) (bestScore = score), (best = i);
    });
    return best;
  }

  /** The frame whose polyline passes nearest a client point (within `pixels`). On an edge
   * that two frames share, the frame on the side of the point (nearer centre) wins. */
  frameAt(x: number, y: number, pixels = 7): number | null {
    if (!this.model) return null;
    const model = this.model;
    const screen = model.vertices.map((v) => this.toClient(new THREE.Vector3(...v)));
    let best: number | null = null;
    let bestD = Infinity;
    let bestC = Infinity;
    model.frames.forEach((frame, f) => {
      let d = Infinity;
      for (let e = 0; e < FRAME_EDGES; ++e) {
        const a = screen[frame.vertices[e]];
        const b = screen[frame.vertices[(e + 1) % FRAME_EDGES]];
        if (!a.visible || !b.visible) continue;
        const dx = b.x - a.x, dy = b.y - a.y;
        const len2 = dx * dx + dy * dy;
        const t = len2 > 0 ? Math.min(1, Math.max(0, ((x - a.x) * dx + (y - a.y) * dy) / len2)) : 0;
        d = Math.min(d, Math.hypot(a.x + t * dx - x, a.y + t * dy - y));
      }
      if (d > pixels) return;
      const c = this.frameCentre(frame.vertices, screen);
      const dc = Math.hypot(c.x - x, c.y - y);
      if (d < bestD - 0.75 || (Math.abs(d - bestD) <= 0.75 && dc < bestC)) {
        bestD = d;
        bestC = dc;
        best = f;
      }
    });
    return best;
  }

  private frameCentre(vertices: number[], screen: { x: number; y: number }[]): { x: number; y: number } {
    let x = 0, y = 0;
    for (const i of vertices) (x += screen[i].x), (y += screen[i].y);
    return { x: x / vertices.length, y: y / vertices.length };
  }

  /** The client point of a vertex handle (tests). */
  vertexScreen(i: number): { x: number; y: number } {
    const s = this.toClient(new THREE.Vector3(...this.model!.vertices[i]));
    return { x: s.x, y: s.y };
  }

  /** A client point that selects frame `f`: the middle of its first edge, 3 px inwards. */
  frameScreen(f: number): { x: number; y: number } {
    const model = this.model!;
    const frame = model.frames[f];
    const screen = model.vertices.map((v) => this.toClient(new THREE.Vector3(...v)));
    const a = screen[frame.vertices[0]], b = screen[frame.vertices[1]];
    const centre = this.frameCentre(frame.vertices, screen);
    const mid = { x: (a.x + b.x) / 2, y: (a.y + b.y) / 2 };
    const len = Math.hypot(centre.x - mid.x, centre.y - mid.y) || 1;
    return { x: mid.x + (3 * (centre.x - mid.x)) / len, y: mid.y + (3 * (centre.y - mid.y)) / len };
  }

  /** Where a drag of `vertex` to a client point lands: on the plane through the vertex
   * that faces the camera. */
  dragTarget(vertex: Vec3, x: number, y: number): Vec3 | null {
    const normal = this.camera.getWorldDirection(new THREE.Vector3());
    const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(normal, new THREE.Vector3(...vertex));
    const hit = this.ray(x, y).intersectPlane(plane, new THREE.Vector3());
    return hit ? (hit.toArray() as Vec3) : null;
  }
}

const ZEBRA_VERTEX = /* glsl */ `
varying vec3 vNormal;
varying vec3 vWorld;
void main() {
  vec4 world = modelMatrix * vec4(position, 1.0);
  vWorld = world.xyz;
  vNormal = normalize(mat3(modelMatrix) * normal);
  gl_Position = projectionMatrix * viewMatrix * world;
}`;

// Stripes of a striped environment seen in the surface: the reflected view direction's
// elevation picks black or white, antialiased with fwidth.
const ZEBRA_FRAGMENT = /* glsl */ `
uniform float stripes;
varying vec3 vNormal;
varying vec3 vWorld;
void main() {
  vec3 n = normalize(vNormal);
  vec3 view = normalize(vWorld - cameraPosition);
  if (!gl_FrontFacing) n = -n;
  vec3 r = reflect(view, n);
  float s = sin(asin(clamp(r.z, -1.0, 1.0)) * stripes);
  float w = max(fwidth(s), 1e-4);
  float band = clamp(s / (2.0 * w) + 0.5, 0.0, 1.0);
  float shade = 0.75 + 0.25 * abs(dot(n, -view));
  gl_FragColor = vec4(vec3(mix(0.08, 0.97, band) * shade), 1.0);
}`;

/** The right view: the shaded surface, zebra stripes on demand, frames overlaid. */
export class SurfaceView extends Viewport {
  readonly overlay = new FrameLines(0.55);
  readonly mesh: THREE.Mesh;
  private readonly shaded: THREE.Material;
  private readonly zebra: THREE.ShaderMaterial;

  constructor(container: HTMLElement) {
    super(container);
    this.shaded = new THREE.MeshStandardMaterial({
      color: 0x98c1d9,
      roughness: 0.45,
      metalness: 0.05,
      side: THREE.DoubleSide,
      polygonOffset: true,
      polygonOffsetFactor: 1,
      polygonOffsetUnits: 1,
    });
    this.zebra = new THREE.ShaderMaterial({
      uniforms: { stripes: { value: 10 } },
      vertexShader: ZEBRA_VERTEX,
      fragmentShader: ZEBRA_FRAGMENT,
      side: THREE.DoubleSide,
    });
    this.mesh = new THREE.Mesh(new THREE.BufferGeometry(), this.shaded);
    this.mesh.frustumCulled = false;
    this.scene.add(this.mesh);
    this.scene.add(this.overlay.object);
  }

  setMesh(data: MeshData): void {
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(data.positions, 3));
    g.setAttribute('normal', new THREE.BufferAttribute(data.normals, 3));
    g.setIndex(new THREE.BufferAttribute(data.indices, 1));
    g.computeBoundingSphere();
    this.mesh.geometry.dispose();
    this.mesh.geometry = g;
  }

  setZebra(on: boolean): void {
    this.mesh.material = on ? this.zebra : this.shaded;
  }

  setOverlay(on: boolean): void {
    this.overlay.object.visible = on;
  }
}
