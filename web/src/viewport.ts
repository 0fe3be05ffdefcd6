// The views' shared base: a three.js renderer, camera and orbit controls in a canvas, the
// axis gizmo in its corner, view presets and fitting boxes. Picking is done in screen space
// (pixels), so thin lines and small handles are as easy to hit at every zoom.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import type { Model, Vec3 } from './api';



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
export class AxisGizmo {
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
    this.stopMotion();
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

  /** Ends what is left of an orbit's, pan's or zoom's damping (OrbitControls keeps turning
   * the camera for a while after the pointer is released): a fit or a view preset right
   * after an orbit must land where it was asked to, not be turned on by the rest of it. */
  stopMotion(): void {
    const damping = this.controls.enableDamping;
    this.controls.enableDamping = false;
    this.controls.update(); // without damping, update() applies and clears what is left
    this.controls.enableDamping = damping;
  }

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

  /** The point of the line through `vertex` along the unit vector `axis` (a global or a local
   * axis, orientation.ts) nearest the ray through a client point: a drag locked to it. */
  axisTarget(vertex: Vec3, axis: Vec3, x: number, y: number): Vec3 {
    const start = new THREE.Vector3(...vertex);
    const along = new THREE.Vector3(...axis);
    const reach = 1e6 * (1 + start.length());
    const onAxis = new THREE.Vector3();
    this.ray(x, y).distanceSqToSegment(
      start.clone().addScaledVector(along, -reach),
      start.clone().addScaledVector(along, reach),
      undefined,
      onAxis,
    );
    return onAxis.toArray() as Vec3;
  }

  /** Where a drag of `vertex` to a client point lands: on the plane through the vertex
   * that faces the camera. */
  dragTarget(vertex: Vec3, x: number, y: number): Vec3 | null {
    const normal = this.camera.getWorldDirection(new THREE.Vector3());
    const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(normal, new THREE.Vector3(...vertex));
    const hit = this.ray(x, y).intersectPlane(plane, new THREE.Vector3());
    return hit ? (hit.toArray() as Vec3) : null;
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

