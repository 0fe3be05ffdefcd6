// The frame view: a vertex-frame model's frame polylines and vertex handles, picked in screen
// space, and redrawn only in the moved handles' region during a drag (damage.ts).
import * as THREE from 'three';
import type { Model, Vec3 } from './api';
import { EMPTY_RECT, addPoint, pointsIn, segmentsIn } from './damage';
import type { Rect, ScreenPoints } from './damage';
import { AxisGizmo, Viewport, modelBox, pointsBox } from './viewport';

/** The edges of a frame: its 8 vertices in a loop. */
const FRAME_EDGES = 8;

export const FRAME_COLOR = new THREE.Color(0x3d5a80);
export const FRAME_SELECTED = new THREE.Color(0xee6c4d);
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
}

