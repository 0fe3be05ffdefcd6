// The two three.js views: the vertex-frame model (handles and frame polylines) and the
// shaded surface. Picking is done in screen space (pixels), so thin lines and small
// handles are as easy to hit at every zoom.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import type { MeshData, Model, Vec3 } from './api';
import { curvatureColors, symmetricRange, vertexCurvatures } from './curvature';
import { EMPTY_RECT, addPoint, pointsIn, segmentsIn } from './damage';
import type { Rect, ScreenPoints } from './damage';
import { PREVIEW_PIXEL_SCALE } from './preview';

const FRAME_EDGES = 8;
/** Above this many changed runs a delta uploads the whole buffer instead. */
const MAX_UPLOAD_RANGES = 256;

/** Whether WebGL runs on the CPU (SwiftShader, llvmpipe): there multisampling triples the
 * cost of a frame, so the views draw without it. */
function softwareWebGL(): boolean {
  const gl = document.createElement('canvas').getContext('webgl2');
  if (!gl) return false;
  const info = gl.getExtension('WEBGL_debug_renderer_info');
  const name = String(gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER));
  gl.getExtension('WEBGL_lose_context')?.loseContext();
  return /swiftshader|llvmpipe|softpipe|software/i.test(name);
}

/** Antialiasing: off on software WebGL unless the page is opened with ?aa=1 (?aa=0 turns
 * it off everywhere). */
const ANTIALIAS = (() => {
  const aa = new URLSearchParams(location.search).get('aa');
  return aa === null ? !softwareWebGL() : aa !== '0';
})();

/** Size of the axis gizmo, CSS pixels. */
const GIZMO_PIXELS = 84;

/** A text label that always faces the camera. */
function labelSprite(text: string, color: string): THREE.Sprite {
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = 64;
  const g = canvas.getContext('2d')!;
  g.font = 'bold 44px system-ui, sans-serif';
  g.fillStyle = color;
  g.textAlign = 'center';
  g.textBaseline = 'middle';
  g.fillText(text, 32, 34);
  const sprite = new THREE.Sprite(new THREE.SpriteMaterial({ map: new THREE.CanvasTexture(canvas), depthTest: false }));
  sprite.scale.setScalar(0.55);
  return sprite;
}

/** The x (red), y (green) and z (blue) axes as the camera sees them, in a corner. */
class AxisGizmo {
  private readonly scene = new THREE.Scene();
  private readonly camera = new THREE.OrthographicCamera(-1.5, 1.5, 1.5, -1.5, 0.1, 10);

  constructor() {
    const axes: [THREE.Vector3, string, string][] = [
      [new THREE.Vector3(1, 0, 0), '#d62828', 'x'],
      [new THREE.Vector3(0, 1, 0), '#2a9d3f', 'y'],
      [new THREE.Vector3(0, 0, 1), '#1d4ed8', 'z'],
    ];
    for (const [dir, color, name] of axes) {
      const line = new THREE.Line(
        new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(), dir]),
        new THREE.LineBasicMaterial({ color, linewidth: 2 }),
      );
      const label = labelSprite(name, color);
      label.position.copy(dir).multiplyScalar(1.25);
      this.scene.add(line, label);
    }
  }

  /** Where the gizmo is drawn (CSS pixels from the bottom left), null when the view is
   * too small for it. */
  static area(renderer: THREE.WebGLRenderer): THREE.Box2 | null {
    const size = renderer.getSize(new THREE.Vector2());
    if (size.x < 3 * GIZMO_PIXELS || size.y < 3 * GIZMO_PIXELS) return null;
    const min = new THREE.Vector2(size.x - GIZMO_PIXELS - 6, 6);
    return new THREE.Box2(min, min.clone().addScalar(GIZMO_PIXELS));
  }

  /** Draws the gizmo; `scale`: into that share of the drawing buffer each way, from its
   * bottom left (a preview: SurfaceView.draw). */
  render(renderer: THREE.WebGLRenderer, main: THREE.Camera, scale = 1): void {
    const area = AxisGizmo.area(renderer);
    if (!area) return;
    const size = renderer.getSize(new THREE.Vector2());
    this.camera.quaternion.copy(main.quaternion);
    this.camera.position.set(0, 0, 3).applyQuaternion(main.quaternion);
    const [x, y, side] = [area.min.x * scale, area.min.y * scale, GIZMO_PIXELS * scale];
    const autoClear = renderer.autoClear;
    renderer.autoClear = false;
    renderer.setScissorTest(true);
    renderer.setScissor(x, y, side, side);
    renderer.setViewport(x, y, side, side);
    renderer.clearDepth();
    renderer.render(this.scene, this.camera);
    renderer.setScissorTest(false);
    renderer.setViewport(0, 0, size.x, size.y);
    renderer.autoClear = autoClear;
  }
}

/** A canvas with its renderer, scene, camera and orbit controls, rendered when it changes. */
export class Viewport {
  readonly renderer: THREE.WebGLRenderer;
  readonly scene = new THREE.Scene();
  readonly camera = new THREE.PerspectiveCamera(40, 1, 0.001, 1000);
  controls!: OrbitControls;
  private readonly gizmo = new AxisGizmo();

  /** `preserve`: the drawing buffer keeps its pixels between frames (a view that redraws
   * only a region: FrameView). */
  constructor(
    readonly container: HTMLElement,
    preserve = false,
  ) {
    this.renderer = new THREE.WebGLRenderer({ antialias: ANTIALIAS, preserveDrawingBuffer: preserve });
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
    this.controls.addEventListener('change', () => this.invalidate());
  }

  resize(): void {
    const w = Math.max(1, this.container.clientWidth);
    const h = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(w, h, false);
    this.renderer.domElement.style.width = '100%';
    this.renderer.domElement.style.height = '100%';
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.invalidate();
  }

  /** Looks at a box along `direction` (from the box toward the camera; default: the
   * current direction, or front-right above for a new view), near enough that its corners
   * just fit the view. */
  fit(box: THREE.Box3, direction?: THREE.Vector3): void {
    if (box.isEmpty()) return;
    const center = box.getCenter(new THREE.Vector3());
    const size = Math.max(box.getSize(new THREE.Vector3()).length(), 1e-3);
    const toCamera = (direction ?? this.viewDirection()).clone().normalize();
    const right = new THREE.Vector3().crossVectors(this.camera.up, toCamera);
    if (right.lengthSq() < 1e-20) right.set(1, 0, 0); // looking straight along up (top, bottom)
    right.normalize();
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
    this.fitted = true;
    this.invalidate();
  }

  private fitted = false;

  /** From the camera's target toward the camera (front-right above until a first fit). */
  viewDirection(): THREE.Vector3 {
    if (!this.fitted) return ISO_VIEW.clone();
    return this.camera.position.clone().sub(this.controls.target).normalize();
  }

  /** Looks along a named direction at a box (a view preset). */
  setView(view: ViewName, box: THREE.Box3): void {
    this.fit(box, VIEW_DIRECTIONS[view]);
  }

  /** Takes another view's camera (linked cameras): same place, target and zoom. */
  follow(other: Viewport): void {
    this.camera.position.copy(other.camera.position);
    this.camera.quaternion.copy(other.camera.quaternion);
    this.camera.near = other.camera.near;
    this.camera.far = other.camera.far;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(other.controls.target);
    this.invalidate();
  }

  protected dirty = true;

  /** Asks for a render in the next animation frame (the views draw only on change). */
  invalidate(): void {
    this.dirty = true;
  }

  /** Renders if anything changed since the last render (the camera moved, or the scene
   * was invalidated); returns whether it rendered. */
  renderIfNeeded(): boolean {
    if (this.controls.update()) this.invalidate(); // damping still moving the camera
    if (!this.dirty) return false;
    this.dirty = false;
    this.draw();
    ++this.draws;
    return true;
  }

  /** Draws since the page loaded, whole or of a region (tests, benchmarks). */
  draws = 0;

  /** The scene, then the axis gizmo in the bottom-right corner. */
  protected draw(): void {
    this.renderer.render(this.scene, this.camera);
    this.drawGizmo();
  }

  protected drawGizmo(scale = 1): void {
    this.gizmo.render(this.renderer, this.camera, scale);
  }

  /** How much the canvas is enlarged on screen (a CSS transform from its bottom left). */
  protected cssScale(): number {
    return 1;
  }

  /** The canvas' box in client pixels as laid out (without the enlargement of cssScale). */
  canvasRect(): { left: number; top: number; width: number; height: number } {
    const r = this.renderer.domElement.getBoundingClientRect();
    const k = this.cssScale();
    return { left: r.left, top: r.bottom - r.height / k, width: r.width / k, height: r.height / k };
  }

  /** Renders now and waits for the GPU to finish; the milliseconds it took (benchmarks). */
  renderTimed(): number {
    const t0 = performance.now();
    this.draw();
    // Reading a pixel waits for the (GPU process') draw to end; gl.finish() does not.
    const gl = this.renderer.getContext();
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
    return performance.now() - t0;
  }

  /** A world point in client (page) pixels, and whether it lies in front of the camera. */
  toClient(p: THREE.Vector3): { x: number; y: number; z: number; visible: boolean } {
    const rect = this.canvasRect();
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
    const rect = this.canvasRect();
    const ndc = new THREE.Vector2(
      ((clientX - rect.left) / rect.width) * 2 - 1,
      -((clientY - rect.top) / rect.height) * 2 + 1,
    );
    const raycaster = new THREE.Raycaster();
    raycaster.setFromCamera(ndc, this.camera);
    return raycaster.ray;
  }
}

/** The view presets: the direction from the model toward the camera (z is up). Top and
 * bottom lean a hair toward -y so that "up" on screen stays +y. */
export const VIEW_DIRECTIONS = {
  front: new THREE.Vector3(0, -1, 0),
  back: new THREE.Vector3(0, 1, 0),
  right: new THREE.Vector3(1, 0, 0),
  left: new THREE.Vector3(-1, 0, 0),
  top: new THREE.Vector3(0, -1e-4, 1),
  bottom: new THREE.Vector3(0, -1e-4, -1),
  iso: new THREE.Vector3(0.55, -1.2, 0.9),
} as const;
export type ViewName = keyof typeof VIEW_DIRECTIONS;
const ISO_VIEW = VIEW_DIRECTIONS.iso;

export function modelBox(model: Model): THREE.Box3 {
  return pointsBox([model.vertices]);
}

export function pointsBox(lines: Vec3[][]): THREE.Box3 {
  const box = new THREE.Box3();
  for (const line of lines) for (const v of line) box.expandByPoint(new THREE.Vector3(...v));
  return box;
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
  // The line vertices ("slots") of each model vertex, CSR: slots[first[i] .. first[i+1]).
  private first = new Uint32Array(0);
  private slots = new Uint32Array(0);
  /** The model vertex of each line vertex (segment m joins line vertices 2m and 2m + 1). */
  lineVertex = new Uint32Array(0);

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
    this.indexSlots(model);
    const g = this.object.geometry;
    g.getAttribute('position').needsUpdate = true;
    g.getAttribute('color').needsUpdate = true;
    g.computeBoundingSphere();
  }

  private indexSlots(model: Model): void {
    const first = new Uint32Array(model.vertices.length + 1);
    for (const frame of model.frames) for (const v of frame.vertices) first[v + 1] += 2;
    for (let i = 0; i < model.vertices.length; ++i) first[i + 1] += first[i];
    const fill = first.slice(0, -1);
    const slots = new Uint32Array(first[model.vertices.length]);
    const lineVertex = new Uint32Array(slots.length);
    let k = 0;
    for (const frame of model.frames)
      for (let e = 0; e < FRAME_EDGES; ++e)
        for (const v of [frame.vertices[e], frame.vertices[(e + 1) % FRAME_EDGES]]) {
          slots[fill[v]++] = k;
          lineVertex[k++] = v;
        }
    this.first = first;
    this.slots = slots;
    this.lineVertex = lineVertex;
  }

  /** Calls `fn` with the other end of every segment at model vertex `vertex`. */
  neighbours(vertex: number, fn: (other: number) => void): void {
    for (let s = this.first[vertex]; s < this.first[vertex + 1]; ++s) fn(this.lineVertex[this.slots[s] ^ 1]);
  }

  /** Moves one vertex of the model last given to update(): only its line ends change. */
  moveVertex(vertex: number, p: Vec3): void {
    const attribute = this.object.geometry.getAttribute('position') as THREE.BufferAttribute;
    for (let s = this.first[vertex]; s < this.first[vertex + 1]; ++s) {
      const k = this.slots[s];
      this.positions.set(p, 3 * k);
      attribute.addUpdateRange(3 * k, 3);
    }
    attribute.needsUpdate = true;
  }
}

/** The true boundary curves of the patches (from the server), drawn over the surface; a
 * selected frame's in the selection colour. */
export class BoundaryLines {
  readonly object: THREE.LineSegments;
  private patches = 0;
  private perPatch = 0; // line vertices per patch

  constructor(opacity: number) {
    const material = new THREE.LineBasicMaterial({ vertexColors: true, transparent: true, opacity, depthTest: false });
    this.object = new THREE.LineSegments(new THREE.BufferGeometry(), material);
    this.object.renderOrder = 2;
    this.object.frustumCulled = false;
  }

  /** Curves as /api/boundaries sends them: [patch][4 sides][samples][xyz]. */
  set(xyz: Float32Array, samples: number, selected: ReadonlySet<number>): void {
    const patches = xyz.length / (12 * samples);
    const perPatch = 4 * (samples - 1) * 2;
    const positions = new Float32Array(3 * perPatch * patches);
    let k = 0;
    for (let p = 0; p < patches; ++p)
      for (let side = 0; side < 4; ++side) {
        const base = 3 * ((p * 4 + side) * samples);
        for (let i = 0; i + 1 < samples; ++i) {
          positions.set(xyz.subarray(base + 3 * i, base + 3 * i + 6), k);
          k += 6;
        }
      }
    const g = this.object.geometry;
    g.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    if (this.patches !== patches || this.perPatch !== perPatch)
      g.setAttribute('color', new THREE.BufferAttribute(new Float32Array(3 * perPatch * patches), 3));
    this.patches = patches;
    this.perPatch = perPatch;
    this.colour(selected);
  }

  colour(selected: ReadonlySet<number>): void {
    const color = this.object.geometry.getAttribute('color') as THREE.BufferAttribute | undefined;
    if (!color) return;
    const a = color.array as Float32Array;
    for (let p = 0; p < this.patches; ++p) {
      const c = selected.has(p) ? FRAME_SELECTED : FRAME_COLOR;
      for (let i = p * this.perPatch; i < (p + 1) * this.perPatch; ++i) a.set([c.r, c.g, c.b], 3 * i);
    }
    color.needsUpdate = true;
  }

  clear(): void {
    this.object.geometry.deleteAttribute('position');
    this.object.geometry.deleteAttribute('color');
    this.patches = this.perPatch = 0;
  }
}

const HANDLE_VERTEX = /* glsl */ `
attribute float handleSize;
attribute vec3 handleColor;
varying vec3 vColor;
void main() {
  vColor = handleColor;
  gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
  gl_PointSize = handleSize;
}`;

// A lit ball drawn in a point sprite: as cheap as a point, read as a handle.
const HANDLE_FRAGMENT = /* glsl */ `
varying vec3 vColor;
void main() {
  vec2 d = gl_PointCoord * 2.0 - 1.0;
  float r2 = dot(d, d);
  if (r2 > 1.0) discard;
  vec3 n = vec3(d.x, -d.y, sqrt(1.0 - r2));
  float light = 0.55 + 0.45 * max(dot(n, normalize(vec3(-0.4, 0.5, 0.8))), 0.0);
  gl_FragColor = vec4(vColor * light + vec3(0.35) * pow(n.z, 12.0), 1.0);
}`;

/** Handle diameters in CSS pixels. */
const HANDLE_PIXELS = 9;
const HANDLE_SELECTED_PIXELS = 14;

/** Vertex handles: one point sprite per model vertex, a constant size on screen (a 3,000
 * vertex model costs 3,000 points, not 3,000 spheres). */
class Handles {
  readonly object: THREE.Points;
  /** Where each handle is drawn (xyz per model vertex). */
  positions = new Float32Array(0);
  private sizes = new Float32Array(0);
  private colors = new Float32Array(0);

  constructor(private readonly pixelRatio: number) {
    const material = new THREE.ShaderMaterial({ vertexShader: HANDLE_VERTEX, fragmentShader: HANDLE_FRAGMENT });
    this.object = new THREE.Points(new THREE.BufferGeometry(), material);
    this.object.frustumCulled = false;
    this.object.renderOrder = 3;
  }

  update(model: Model, selected: number | null, also: readonly number[] = []): void {
    const n = model.vertices.length;
    const g = this.object.geometry;
    if (this.sizes.length !== n) {
      this.positions = new Float32Array(3 * n);
      this.sizes = new Float32Array(n);
      this.colors = new Float32Array(3 * n);
      g.setAttribute('position', new THREE.BufferAttribute(this.positions, 3));
      g.setAttribute('handleSize', new THREE.BufferAttribute(this.sizes, 1));
      g.setAttribute('handleColor', new THREE.BufferAttribute(this.colors, 3));
    }
    model.vertices.forEach((p, i) => this.positions.set(p, 3 * i));
    const picked = new Set(also);
    for (let i = 0; i < n; ++i) this.style(i, i === selected || picked.has(i));
    for (const name of ['position', 'handleSize', 'handleColor']) g.getAttribute(name).needsUpdate = true;
  }

  private style(i: number, selected: boolean): void {
    this.sizes[i] = (selected ? HANDLE_SELECTED_PIXELS : HANDLE_PIXELS) * this.pixelRatio;
    const c = selected ? HANDLE_SELECTED : HANDLE_COLOR;
    this.colors.set([c.r, c.g, c.b], 3 * i);
  }

  moveVertex(vertex: number, p: Vec3): void {
    const attribute = this.object.geometry.getAttribute('position') as THREE.BufferAttribute;
    this.positions.set(p, 3 * vertex);
    attribute.addUpdateRange(3 * vertex, 3);
    attribute.needsUpdate = true;
  }
}

/** Some of the primitives of a LineSegments' or Points' object, drawn with its attributes
 * and material (a region's redraw): an index buffer with room for every vertex, of which
 * the first `count` are drawn. */
class Subset {
  readonly object: THREE.LineSegments | THREE.Points;
  private indices = new Uint32Array(0);

  constructor(private readonly source: THREE.LineSegments | THREE.Points) {
    const geometry = new THREE.BufferGeometry();
    this.object =
      source instanceof THREE.Points
        ? new THREE.Points(geometry, source.material)
        : new THREE.LineSegments(geometry, source.material);
    this.object.renderOrder = source.renderOrder;
    this.object.frustumCulled = false;
    this.object.visible = false;
  }

  /** Where to write the indices drawn (room for every vertex of the source). */
  buffer(): Uint32Array {
    const count = this.source.geometry.getAttribute('position')?.count ?? 0;
    if (this.indices.length !== count) {
      // A new index buffer; the old geometry's shared attributes are the source's: only its
      // own index is freed.
      const old = this.object.geometry;
      for (const name of Object.keys(old.attributes)) old.deleteAttribute(name);
      old.dispose();
      this.indices = new Uint32Array(count);
      this.object.geometry = new THREE.BufferGeometry().setIndex(new THREE.BufferAttribute(this.indices, 1));
    }
    return this.indices;
  }

  /** Draws the first `count` indices of buffer() with the source's attributes as they are. */
  use(count: number): void {
    const g = this.object.geometry;
    for (const [name, attribute] of Object.entries(this.source.geometry.attributes))
      if (g.getAttribute(name) !== attribute) g.setAttribute(name, attribute);
    const index = g.getIndex()!;
    index.clearUpdateRanges();
    if (count > 0) index.addUpdateRange(0, count);
    index.needsUpdate = true;
    g.setDrawRange(0, count);
  }
}

/** Pixels (CSS) around a moved handle's segments in which they may colour pixels (1 px
 * lines, rounding to pixels). */
const LINE_PAD_PIXELS = 2;
/** Half the side of the square a handle may colour (CSS pixels): a selected handle's whole
 * diameter, a margin for rounding and the pixel ratio. */
const HANDLE_REACH_PIXELS = HANDLE_SELECTED_PIXELS;
/** A drag's region redraw is done whole above this share of the view's pixels (its
 * primitives are then most of the view's anyway). */
const REGION_MAX_SHARE = 0.25;

/** The left view: vertex handles and frame polylines, with screen-space picking. During a
 * drag only the region of the moved handles is redrawn (damage.ts: a whole draw of a large
 * model holds the page's main thread while the edit's answer waits). */
export class FrameView extends Viewport {
  readonly lines = new FrameLines();
  private readonly handles: Handles;
  private readonly lineSubset: Subset;
  private readonly handleSubset: Subset;
  /** The whole view is to be drawn (something else than handles moved changed). */
  private whole = true;
  /** The moved handles' region to draw again (CSS pixels from the bottom left), if any. */
  private damage: Rect | null = null;
  /** Each handle on screen as last drawn; null until asked for after a whole draw (the
   * camera may have changed). */
  private screen: ScreenPoints | null = null;
  /** Region draws since the page loaded (tests). */
  regionDraws = 0;
  private model: Model | null = null;
  /** A view-only model's curves and spines (hidden while a vertex-frame model is shown). */
  private readonly curves = new THREE.LineSegments(
    new THREE.BufferGeometry(),
    new THREE.LineBasicMaterial({ color: FRAME_COLOR }),
  );
  private readonly spines = new THREE.LineSegments(
    new THREE.BufferGeometry(),
    new THREE.LineBasicMaterial({ color: FRAME_SELECTED }),
  );

  constructor(container: HTMLElement) {
    super(container, true); // the pixels outside a drag's region are kept
    this.handles = new Handles(this.renderer.getPixelRatio());
    this.lineSubset = new Subset(this.lines.object);
    this.handleSubset = new Subset(this.handles.object);
    this.scene.add(this.lines.object, this.lineSubset.object);
    this.scene.add(this.handles.object, this.handleSubset.object);
    this.scene.add(this.curves, this.spines);
    const grid = new THREE.GridHelper(1, 10, 0xc9ced6, 0xdfe3e8);
    grid.rotation.x = Math.PI / 2;
    grid.name = 'grid';
    this.scene.add(grid);
  }

  setModel(
    model: Model,
    selectedVertex: number | null,
    selectedFrames: ReadonlySet<number>,
    selectedVertices: readonly number[] = [],
  ): void {
    const resized = !this.model || this.model.vertices.length !== model.vertices.length;
    this.model = model;
    this.showEditable(true);
    if (resized) this.placeGrid(modelBox(model));
    this.handles.update(model, selectedVertex, selectedVertices);
    this.lines.update(model, selectedFrames);
    this.invalidate();
  }

  /** A view-only model: its closed curves and open spines as polylines, nothing to pick. */
  showCurves(curves: Vec3[][], spines: Vec3[][]): void {
    this.model = null;
    this.showEditable(false);
    const segments = (lines: Vec3[][], closed: boolean) => {
      const out: number[] = [];
      for (const line of lines)
        for (let i = 0; i + (closed ? 0 : 1) < line.length; ++i)
          out.push(...line[i], ...line[(i + 1) % line.length]);
      return new THREE.Float32BufferAttribute(out, 3);
    };
    this.curves.geometry.setAttribute('position', segments(curves, true));
    this.spines.geometry.setAttribute('position', segments(spines, false));
    this.curves.geometry.computeBoundingSphere();
    this.spines.geometry.computeBoundingSphere();
    this.placeGrid(pointsBox([...curves, ...spines]));
    this.invalidate();
  }

  private showEditable(on: boolean): void {
    this.handles.object.visible = this.lines.object.visible = on;
    this.curves.visible = this.spines.visible = !on;
  }

  /** The ground grid under a box. */
  private placeGrid(box: THREE.Box3): void {
    const grid = this.scene.getObjectByName('grid');
    if (!grid || box.isEmpty()) return;
    const size = box.getSize(new THREE.Vector3());
    grid.scale.setScalar(Math.max(size.x, size.y, 1e-3) * 1.6);
    grid.position.set(...box.getCenter(new THREE.Vector3()).toArray().slice(0, 2) as [number, number], box.min.z);
  }

  /** Moves one vertex of the model shown (a drag): its handle and its line ends, and the
   * region they covered and cover now is drawn again in the next frame. */
  moveVertex(vertex: number, p: Vec3): void {
    const damage = this.whole ? null : (this.damage ?? { ...EMPTY_RECT });
    if (damage) this.addDamage(damage, vertex);
    this.handles.moveVertex(vertex, p);
    this.lines.moveVertex(vertex, p);
    if (damage) {
      this.project(this.screenPoints(), vertex);
      this.addDamage(damage, vertex);
      this.damage = damage;
    }
    this.dirty = true;
  }

  override invalidate(): void {
    super.invalidate();
    this.whole = true;
  }

  /** Grows `rect` by what vertex `vertex`'s handle and segments cover on screen now. */
  private addDamage(rect: Rect, vertex: number): void {
    const screen = this.screenPoints();
    addPoint(rect, screen, vertex, HANDLE_REACH_PIXELS);
    this.lines.neighbours(vertex, (other) => addPoint(rect, screen, other, LINE_PAD_PIXELS));
  }

  /** The handles on screen (computed after a whole draw, then kept up by moveVertex). */
  private screenPoints(): ScreenPoints {
    if (this.screen && this.screen.wild.length === this.handles.positions.length / 3) return this.screen;
    const n = this.handles.positions.length / 3;
    this.screen = { xy: new Float32Array(2 * n), wild: new Uint8Array(n) };
    for (let i = 0; i < n; ++i) this.project(this.screen, i);
    return this.screen;
  }

  private readonly projected = new THREE.Vector3();

  /** Handle i on screen, as the camera of the last draw sees it. */
  private project(screen: ScreenPoints, i: number): void {
    const q = this.projected.fromArray(this.handles.positions, 3 * i).project(this.camera);
    const size = this.renderer.getSize(new THREE.Vector2());
    screen.xy[2 * i] = ((q.x + 1) / 2) * size.x;
    screen.xy[2 * i + 1] = ((q.y + 1) / 2) * size.y;
    // outside the depth range (behind the camera, say) its lines' pixels are not bounded
    screen.wild[i] = q.z >= -1 && q.z <= 1 && Number.isFinite(q.x + q.y) ? 0 : 1;
  }

  /** The damaged region to draw, in whole pixels inside the view (with the axis gizmo
   * when it meets it), or null to draw the whole view. */
  private region(): Rect | null {
    const d = this.damage;
    if (!d) return null;
    const size = this.renderer.getSize(new THREE.Vector2());
    const r = {
      x0: Math.max(0, Math.floor(d.x0)),
      y0: Math.max(0, Math.floor(d.y0)),
      x1: Math.min(size.x, Math.ceil(d.x1)),
      y1: Math.min(size.y, Math.ceil(d.y1)),
    };
    if (r.x1 <= r.x0 || r.y1 <= r.y0) return null;
    const gizmo = AxisGizmo.area(this.renderer);
    if (gizmo && gizmo.min.x <= r.x1 && gizmo.max.x >= r.x0 && gizmo.min.y <= r.y1 && gizmo.max.y >= r.y0) {
      r.x0 = Math.min(r.x0, gizmo.min.x);
      r.y0 = Math.min(r.y0, gizmo.min.y);
      r.x1 = Math.max(r.x1, gizmo.max.x);
      r.y1 = Math.max(r.y1, gizmo.max.y);
    }
    return (r.x1 - r.x0) * (r.y1 - r.y0) <= REGION_MAX_SHARE * size.x * size.y ? r : null;
  }

  protected override draw(): void {
    const region = this.whole ? null : this.region();
    this.whole = false;
    this.damage = null;
    if (!region) {
      this.screen = null;
      super.draw();
      return;
    }
    // Only the segments and handles that may colour a pixel of the region, in their order,
    // over the region cleared: the pixels a whole draw would give there.
    const screen = this.screenPoints();
    const lines = this.lineSubset.buffer();
    this.lineSubset.use(segmentsIn(screen, this.lines.lineVertex, region, LINE_PAD_PIXELS, lines));
    const handles = this.handleSubset.buffer();
    this.handleSubset.use(pointsIn(screen, screen.wild.length, region, HANDLE_REACH_PIXELS, handles));
    const pairs = [
      [this.lines.object, this.lineSubset.object],
      [this.handles.object, this.handleSubset.object],
    ] as const;
    for (const [whole, some] of pairs) [some.visible, whole.visible] = [whole.visible, false];
    this.renderer.setScissor(region.x0, region.y0, region.x1 - region.x0, region.y1 - region.y0);
    this.renderer.setScissorTest(true);
    this.renderer.render(this.scene, this.camera);
    this.renderer.setScissorTest(false);
    for (const [whole, some] of pairs) [whole.visible, some.visible] = [some.visible, false];
    const gizmo = AxisGizmo.area(this.renderer);
    if (gizmo && gizmo.min.x >= region.x0 && gizmo.max.x <= region.x1 && gizmo.min.y >= region.y0 && gizmo.max.y <= region.y1)
      this.drawGizmo();
    ++this.regionDraws;
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

  /** The vertices whose handles lie inside a client rectangle (a box selection). */
  verticesInBox(x0: number, y0: number, x1: number, y1: number): number[] {
    if (!this.model) return [];
    const [left, right] = [Math.min(x0, x1), Math.max(x0, x1)];
    const [top, bottom] = [Math.min(y0, y1), Math.max(y0, y1)];
    const out: number[] = [];
    this.model.vertices.forEach((v, i) => {
      const s = this.toClient(new THREE.Vector3(...v));
      if (s.visible && s.x >= left && s.x <= right && s.y >= top && s.y <= bottom) out.push(i);
    });
    return out;
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
// elevation above the plane normal to `axis` picks black or white, antialiased with fwidth.
const ZEBRA_FRAGMENT = /* glsl */ `
uniform float stripes;
uniform vec3 axis;
varying vec3 vNormal;
varying vec3 vWorld;
void main() {
  vec3 n = normalize(vNormal);
  vec3 view = normalize(vWorld - cameraPosition);
  if (!gl_FrontFacing) n = -n;
  vec3 r = reflect(view, n);
  float s = sin(asin(clamp(dot(r, axis), -1.0, 1.0)) * stripes);
  float w = max(fwidth(s), 1e-4);
  float band = clamp(s / (2.0 * w) + 0.5, 0.0, 1.0);
  float shade = 0.75 + 0.25 * abs(dot(n, -view));
  gl_FragColor = vec4(vec3(mix(0.08, 0.97, band) * shade), 1.0);
}`;

/** Stripes over the half-circle of reflected elevations, by default. */
export const ZEBRA_DEFAULT_STRIPES = 16;

export type CurvatureMode = 'off' | 'mean' | 'gaussian';

/** The right view: the shaded surface, zebra stripes or curvature colours on demand,
 * frames overlaid. */
export class SurfaceView extends Viewport {
  readonly overlay = new BoundaryLines(0.7);
  readonly mesh: THREE.Mesh;
  private readonly shaded: THREE.Material;
  private readonly zebra: THREE.ShaderMaterial;
  private readonly coloured: THREE.Material;
  /** The zebra material (tests read its uniforms). */
  get zebraMaterial(): THREE.ShaderMaterial {
    return this.zebra;
  }
  /** The shaded surface during a preview: Lambert lighting, a third cheaper per pixel than
   * the standard material's on software WebGL (docs/performance.md, "Studio: adaptive preview"). */
  private readonly previewShaded: THREE.Material;
  private zebraOn = false;
  private overlayOn = true;
  /** Whether a gesture's preview is shown (setPreview). */
  private preview = false;
  /** The boundary curves are of an older surface (a preview showed another; new ones not yet here). */
  private curvesStale = false;
  private curvature: CurvatureMode = 'off';
  /** The colour scale's half-range of the curvature shown (legend), 0 when off. */
  curvatureRange = 0;
  /** Called after curvature colours are recomputed (the legend). */
  onCurvature: (mode: CurvatureMode, range: number) => void = () => {};

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
      uniforms: { stripes: { value: ZEBRA_DEFAULT_STRIPES }, axis: { value: new THREE.Vector3(0, 0, 1) } },
      vertexShader: ZEBRA_VERTEX,
      fragmentShader: ZEBRA_FRAGMENT,
      side: THREE.DoubleSide,
    });
    this.coloured = new THREE.MeshStandardMaterial({
      vertexColors: true,
      roughness: 0.6,
      metalness: 0,
      side: THREE.DoubleSide,
      polygonOffset: true,
      polygonOffsetFactor: 1,
      polygonOffsetUnits: 1,
    });
    this.previewShaded = new THREE.MeshLambertMaterial({
      color: 0x98c1d9,
      side: THREE.DoubleSide,
      polygonOffset: true,
      polygonOffsetFactor: 1,
      polygonOffsetUnits: 1,
    });
    this.mesh = new THREE.Mesh(new THREE.BufferGeometry(), this.shaded);
    this.mesh.frustumCulled = false;
    this.scene.add(this.mesh);
    this.scene.add(this.overlay.object);
  }

  /** The triangle of the surface first hit under a client point (the one in front: what
   * is hidden behind the surface is never picked), or null. */
  triangleAt(clientX: number, clientY: number): number | null {
    const rect = this.canvasRect();
    const ndc = new THREE.Vector2(((clientX - rect.left) / rect.width) * 2 - 1, -((clientY - rect.top) / rect.height) * 2 + 1);
    const raycaster = new THREE.Raycaster();
    raycaster.setFromCamera(ndc, this.camera);
    this.mesh.geometry.computeBoundingSphere(); // deltas move vertices without updating it
    const hit = raycaster.intersectObject(this.mesh, false)[0];
    return hit?.faceIndex ?? null;
  }

  /** A client point on triangle `t` of the surface (its centroid; tests). */
  triangleScreen(t: number): { x: number; y: number } {
    const g = this.mesh.geometry;
    const index = g.getIndex()!;
    const position = g.getAttribute('position');
    const c = new THREE.Vector3();
    for (let k = 0; k < 3; ++k) c.add(new THREE.Vector3().fromBufferAttribute(position, index.getX(3 * t + k)));
    const s = this.toClient(c.divideScalar(3));
    return { x: s.x, y: s.y };
  }

  /** The geometry of every mesh the page holds (mesh-sync.ts): a mesh shown again keeps
   * its WebGL buffers, so only the vertices a delta changed are uploaded. */
  private readonly geometries = new Map<MeshData, THREE.BufferGeometry>();

  /** The mesh shown (showMesh). */
  private shown: MeshData | null = null;
  /** The analytic curvature of a mesh (GET /api/curvature): H, K per vertex, of `revision`. */
  private analytic: { mesh: MeshData; revision: number; values: Float32Array } | null = null;
  /** Whether the colours shown come from the analytic curvature (else the mesh estimate). */
  analyticCurvature = false;

  /** The analytic curvature of `mesh` at `revision` (used while that mesh, unchanged, is
   * shown; the estimate from the normals otherwise, as during a preview). */
  setAnalyticCurvature(mesh: MeshData, revision: number, values: Float32Array): void {
    this.analytic = { mesh, revision, values };
    this.colour();
    this.invalidate();
  }

  /** Shows `data`: a new mesh (uploaded whole), or one held before, whose vertex `runs`
   * (start, count) a delta has rewritten in its arrays (only those are uploaded). */
  showMesh(data: MeshData, runs?: Uint32Array): void {
    this.shown = data;
    // A surface of the preview: the boundary curves are of an older one (until new ones
    // come, after the gesture; a press that moved nothing keeps them).
    if (this.preview) this.curvesStale = true;
    let g = this.geometries.get(data);
    if (!g) {
      g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.BufferAttribute(data.positions, 3));
      g.setAttribute('normal', new THREE.BufferAttribute(data.normals, 3));
      g.setIndex(new THREE.BufferAttribute(data.indices, 1));
      g.computeBoundingSphere();
      this.geometries.set(data, g);
    } else if (runs) {
      for (const name of ['position', 'normal']) {
        const attribute = g.getAttribute(name) as THREE.BufferAttribute;
        // Many small uploads cost more than one big one.
        if (runs.length <= 2 * MAX_UPLOAD_RANGES)
          for (let r = 0; r < runs.length; r += 2) attribute.addUpdateRange(3 * runs[r], 3 * runs[r + 1]);
        else attribute.clearUpdateRanges();
        attribute.needsUpdate = true;
      }
    }
    this.mesh.geometry = g;
    this.colour(); // all of it: the colour scale may change with the new shape
    this.invalidate();
  }

  /** Frees the WebGL buffers of a mesh the page no longer holds. */
  dropMesh(data: MeshData): void {
    if (this.analytic?.mesh === data) this.analytic = null;
    this.geometries.get(data)?.dispose();
    this.geometries.delete(data);
  }

  setZebra(on: boolean): void {
    this.zebraOn = on;
    this.pickMaterial();
  }

  /** Stripe count and the axis the environment's stripes run around. */
  setZebraOptions(stripes: number, axis: THREE.Vector3): void {
    this.zebra.uniforms.stripes.value = stripes;
    this.zebra.uniforms.axis.value.copy(axis).normalize();
    this.invalidate();
  }

  /** Colours the surface by its mean or Gaussian curvature (or not). */
  setCurvature(mode: CurvatureMode): void {
    this.curvature = mode;
    this.colour();
    this.pickMaterial();
  }

  /** A gesture's preview (on) or the chosen resolution again (off): during a preview the
   * view draws at PREVIEW_PIXEL_SCALE of the pixel density (draw), shades with Lambert lighting and
   * hides the boundary curves (which follow the surface again when the gesture ends). */
  setPreview(on: boolean): void {
    if (this.preview === on) return;
    this.preview = on;
    this.showOverlay();
    this.pickMaterial();
  }

  /** The canvas' CSS scale (1 / PREVIEW_PIXEL_SCALE during a preview), as last drawn. */
  private shownScale = 1;

  /** During a preview the scene is drawn into the bottom-left PREVIEW_PIXEL_SCALE of the
   * canvas' drawing buffer each way, and the canvas is shown enlarged by its inverse from its
   * bottom-left corner (a CSS transform; the view clips the rest), so that the browser's
   * compositor scales the picture up as it did when the canvas itself was made smaller. The
   * canvas keeps its size: resizing it (setPixelRatio) reallocates WebGL's drawing buffer,
   * which held the page's main thread 40-90 ms on SwiftShader at the start and at the end
   * of every gesture, the release's full-resolution draw waiting behind it (docs/performance.md,
   * "Studio: adaptive preview"). The transform changes in the draw that needs it, so the
   * compositor never shows a picture with the other's scale. */
  protected override draw(): void {
    const scale = this.preview ? PREVIEW_PIXEL_SCALE : 1;
    if (scale === 1) super.draw();
    else {
      const size = this.renderer.getSize(new THREE.Vector2());
      this.renderer.setViewport(0, 0, size.x * scale, size.y * scale);
      // Points sized in screen pixels (the selection's dots) keep their size on screen.
      const points: THREE.PointsMaterial[] = [];
      this.scene.traverseVisible((o) => {
        const m = (o as THREE.Points).material;
        if (m instanceof THREE.PointsMaterial && !m.sizeAttenuation && !points.includes(m)) points.push(m);
      });
      for (const m of points) m.size *= scale;
      this.renderer.render(this.scene, this.camera);
      for (const m of points) m.size /= scale;
      this.drawGizmo(scale);
      this.renderer.setViewport(0, 0, size.x, size.y);
    }
    this.showScale(1 / scale);
  }

  private showScale(cssScale: number): void {
    if (this.shownScale === cssScale) return;
    this.shownScale = cssScale;
    const style = this.renderer.domElement.style;
    style.transformOrigin = '0 100%';
    style.transform = cssScale === 1 ? '' : `scale(${cssScale})`;
  }

  protected override cssScale(): number {
    return this.shownScale;
  }

  private pickMaterial(): void {
    const shaded = this.preview ? this.previewShaded : this.shaded;
    this.mesh.material = this.zebraOn ? this.zebra : this.curvature !== 'off' ? this.coloured : shaded;
    this.invalidate();
  }

  /** Recomputes the curvature colours of the whole mesh (when they are shown). */
  private colour(): void {
    const g = this.mesh.geometry;
    const position = g.getAttribute('position') as THREE.BufferAttribute | undefined;
    if (this.curvature === 'off' || !position || !g.index) {
      this.curvatureRange = 0;
      this.onCurvature(this.curvature, 0);
      return;
    }
    const a = this.analytic;
    this.analyticCurvature =
      !!a && a.mesh === this.shown && a.revision === a.mesh.revision && a.values.length === 2 * position.count;
    let values: Float32Array;
    if (this.analyticCurvature) {
      values = new Float32Array(position.count);
      const offset = this.curvature === 'mean' ? 0 : 1;
      for (let i = 0; i < values.length; ++i) values[i] = a!.values[2 * i + offset];
    } else {
      const normal = g.getAttribute('normal') as THREE.BufferAttribute;
      const k = vertexCurvatures(position.array, normal.array, g.index.array);
      values = this.curvature === 'mean' ? k.mean : k.gaussian;
    }
    this.curvatureRange = symmetricRange(values);
    let color = g.getAttribute('color') as THREE.BufferAttribute | undefined;
    if (!color || color.count !== position.count) {
      color = new THREE.BufferAttribute(new Float32Array(3 * position.count), 3);
      g.setAttribute('color', color);
    }
    curvatureColors(values, this.curvatureRange, color.array as Float32Array);
    color.needsUpdate = true;
    this.onCurvature(this.curvature, this.curvatureRange);
  }

  private showOverlay(): void {
    this.overlay.object.visible = this.overlayOn && !this.preview && !this.curvesStale;
  }

  setOverlay(on: boolean): void {
    this.overlayOn = on;
    this.showOverlay();
    this.invalidate();
  }

  /** The patches' boundary curves (/api/boundaries), or none. */
  setBoundaries(curves: { xyz: Float32Array; samples: number } | null, selectedFrames: ReadonlySet<number>): void {
    if (curves) this.overlay.set(curves.xyz, curves.samples, selectedFrames);
    else this.overlay.clear();
    this.curvesStale = false;
    this.showOverlay();
    this.invalidate();
  }

  selectOverlay(selectedFrames: ReadonlySet<number>): void {
    this.overlay.colour(selectedFrames);
    this.invalidate();
  }
}
