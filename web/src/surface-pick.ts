// Picking on the surface view: the point and triangle in front under the pointer, the frame
// (patch) of a triangle (GET /api/patch-ids, fetched once per mesh layout), and whether a
// point is hidden behind the surface (what is hidden is never picked).
import * as THREE from 'three';
import { api } from './api';
import type { Vec3 } from './api';
import type { Studio } from './studio';

/** A point nearer the camera than the surface in front of it by less than this fraction of
 * the model's size is on the surface, seen (the mesh's chords stand off the true surface by
 * far less at the studio's resolutions; a vertex hidden by a fold is farther). */
export const HIDDEN_TOLERANCE = 0.01;

export class SurfacePicker {
  private ids: { key: string; ids: Uint32Array } | null = null;

  constructor(private readonly studio: Studio) {}

  /** The surface's first hit under a client point: the point and its triangle. */
  hit(clientX: number, clientY: number): { point: THREE.Vector3; triangle: number } | null {
    const view = this.studio.surfaceView;
    const raycaster = new THREE.Raycaster();
    raycaster.ray.copy(view.ray(clientX, clientY));
    this.refresh();
    const first = raycaster.intersectObject(view.mesh, false)[0];
    return first && first.faceIndex != null ? { point: first.point, triangle: first.faceIndex } : null;
  }

  /** Call before seen(): a mesh delta moves vertices without updating the bounds raycasting
   * reads. */
  refresh(): void {
    this.studio.surfaceView.mesh.geometry.computeBoundingSphere();
  }

  /** The frame of triangle `t` of the mesh shown (null when there is none). */
  async frameOf(t: number): Promise<number | null> {
    const { mesh, model } = this.studio.store.state;
    if (!mesh || !model) return null;
    // The layout depends on the frames and the resolution alone.
    const key = `${mesh.resolution}/${mesh.triangleCount}/${model.frames.map((f) => f.vertices.join(',')).join(';')}`;
    if (this.ids?.key !== key) this.ids = { key, ids: (await api.patchIds(mesh.resolution)).ids };
    return t >= 0 && t < this.ids.ids.length ? this.ids.ids[t] : null;
  }

  /** The vertex of `vertices` seen nearest a client point, within `pixels` of it, or null
   * (a vertex hidden behind the surface is never picked, however near on screen). */
  vertexAt(vertices: readonly Vec3[], clientX: number, clientY: number, pixels: number, size: number): number | null {
    const view = this.studio.surfaceView;
    const near: { i: number; d: number }[] = [];
    vertices.forEach((v, i) => {
      const s = view.toClient(new THREE.Vector3(...v));
      const d = Math.hypot(s.x - clientX, s.y - clientY);
      if (s.visible && d <= pixels) near.push({ i, d });
    });
    near.sort((a, b) => a.d - b.d);
    this.refresh();
    return near.find(({ i }) => this.seen(vertices[i], size))?.i ?? null;
  }

  /** Whether `p` is seen in the surface view: in front of the camera and not behind the
   * surface (the first hit along the ray toward it is at it, within HIDDEN_TOLERANCE × `size`). */
  seen(p: Vec3, size: number): boolean {
    const view = this.studio.surfaceView;
    const target = new THREE.Vector3(...p);
    if (!view.toClient(target).visible) return false;
    const from = view.camera.position.clone();
    const distance = target.distanceTo(from);
    const raycaster = new THREE.Raycaster(from, target.clone().sub(from).normalize(), 0, distance);
    const first = raycaster.intersectObject(view.mesh, false)[0];
    return !first || first.distance >= distance - HIDDEN_TOLERANCE * size;
  }
}
