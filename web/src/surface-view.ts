// The surface view: the shaded surface (zebra stripes, curvature colours), its mesh kept in
// WebGL buffers that deltas update in place, and the true boundary curves of the patches.
import * as THREE from 'three';
import type { MeshData } from './api';
import { curvatureColors, symmetricRange, vertexCurvatures } from './curvature';
import { PREVIEW_PIXEL_SCALE } from './preview';
import { Viewport } from './viewport';
import { FRAME_COLOR, FRAME_SELECTED } from './frame-view';

/** Above this many changed runs a delta uploads the whole buffer instead. */
const MAX_UPLOAD_RANGES = 256;

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

