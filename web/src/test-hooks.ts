// Hooks for the browser tests and the latency benchmark (e2e/, bench/studio/latency.mjs):
// where things are on screen, edits through the page, the page's state. Loaded only when
// a test drives the page (navigator.webdriver) or with ?test=1 (main.ts).
import * as THREE from 'three';
import { api } from './api';
import { modellerTools } from './modeller';
import type { Edit } from './api';
import { positionsBox } from './transform';
import { onSurface } from './snap';
import type { Studio } from './studio';

declare global {
  interface Window {
    __studio: unknown;
  }
}

export function installTestHooks(studio: Studio): void {
  const { store, frameView, surfaceView, pump } = studio;
  window.__studio = {
    vertexScreen: (i: number) => frameView.vertexScreen(i),
    frameScreen: (f: number) => frameView.frameScreen(f),
    edit: (edit: Edit) => pump.once('test', () => edit).then(() => store.state.error),
    idle: () => pump.idle(),
    /** Resolves when no mesh request is in flight (after a solver change, say). */
    meshIdle: () => studio.meshes.idle(),
    /** Whether the page's mesh (updated by deltas) equals the whole mesh the server makes now. */
    meshMatchesServer: async () => {
      const m = store.state.mesh;
      if (!m) return false;
      const full = await api.mesh({ resolution: m.resolution, ...studio.solver });
      if (full.kind !== 'full' || full.revision !== m.revision) return false;
      const same = (a: ArrayLike<number>, b: ArrayLike<number>) =>
        a.length === b.length && Array.prototype.every.call(a, (x: number, i: number) => x === b[i]);
      return same(full.positions, m.positions) && same(full.normals, m.normals) && same(full.indices, m.indices);
    },
    /** Each view's draws so far (a region's too), and whether the surface shows its
     * boundary-curve overlay (benchmarks: what a release draws). */
    draws: () => ({ frame: frameView.draws, surface: surfaceView.draws, overlay: surfaceView.overlay.object.visible }),
    /** The surface view drawn now, its drawing buffer read back (RGBA rows from the bottom,
     * base64), and how much the canvas is shown enlarged (a preview: 2). */
    surfacePixels: () => {
      surfaceView.invalidate();
      surfaceView.renderIfNeeded();
      const gl = surfaceView.renderer.getContext();
      const pixels = new Uint8Array(4 * gl.drawingBufferWidth * gl.drawingBufferHeight);
      gl.readPixels(0, 0, gl.drawingBufferWidth, gl.drawingBufferHeight, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
      let text = '';
      for (let i = 0; i < pixels.length; i += 0x8000) text += String.fromCharCode(...pixels.subarray(i, i + 0x8000));
      const shown = surfaceView.renderer.domElement.style.transform;
      return { width: gl.drawingBufferWidth, height: gl.drawingBufferHeight, base64: btoa(text), transform: shown };
    },
    /** Puts the surface view's camera where `cameras()` said it was (position, target, and
     * its depth range). */
    setSurfaceCamera: (c: { position: number[]; target: number[]; near: number; far: number }) => {
      surfaceView.camera.position.fromArray(c.position);
      surfaceView.controls.target.fromArray(c.target);
      surfaceView.camera.near = c.near;
      surfaceView.camera.far = c.far;
      surfaceView.camera.updateProjectionMatrix();
      surfaceView.controls.update();
      surfaceView.invalidate();
    },
    /** The frame view's region draws so far (a drag's moved handles: frame-view.ts). */
    frameRegionDraws: () => frameView.regionDraws,
    /** Pixels of the frame view as drawn, then as a whole draw gives them now: how many
     * differ (its drawing buffer is preserved: region draws keep the rest). */
    frameRedrawDifference: async () => {
      const gl = frameView.renderer.getContext();
      const read = () => {
        const pixels = new Uint8Array(4 * gl.drawingBufferWidth * gl.drawingBufferHeight);
        gl.readPixels(0, 0, gl.drawingBufferWidth, gl.drawingBufferHeight, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
        return pixels;
      };
      const shown = read();
      frameView.invalidate();
      frameView.renderIfNeeded();
      const whole = read();
      let differ = 0;
      for (let i = 0; i < shown.length; i += 4)
        if (shown[i] !== whole[i] || shown[i + 1] !== whole[i + 1] || shown[i + 2] !== whole[i + 2]) ++differ;
      return { differ, pixels: shown.length / 4 };
    },
    renderTimes: (n: number) => ({
      frames: Array.from({ length: n }, () => frameView.renderTimed()),
      surface: Array.from({ length: n }, () => surfaceView.renderTimed()),
    }),
    state: () => ({
      revision: store.state.status?.revision,
      mesh: store.state.mesh?.revision,
      resolution: store.state.mesh?.resolution,
      error: store.state.error,
      meshDeltas: store.state.meshDeltas,
    }),
    /** The bounding box of the page's surface mesh. */
    meshBox: () => positionsBox(store.state.mesh?.positions),
    /** Each view's camera: the direction from its target toward it, and the target. */
    cameras: () =>
      Object.fromEntries(
        (['frame', 'surface'] as const).map((name) => {
          const v = name === 'frame' ? frameView : surfaceView;
          return [name, { direction: v.viewDirection().toArray(), target: v.controls.target.toArray(), position: v.camera.position.toArray(), near: v.camera.near, far: v.camera.far }];
        }),
      ),
    /** What the surface view shows: its material, zebra settings, curvature scale. */
    analysis: () => ({
      material: surfaceView.mesh.material === surfaceView.zebraMaterial ? 'zebra' : (surfaceView.mesh.material as { vertexColors?: boolean }).vertexColors ? 'curvature' : 'shaded',
      stripes: surfaceView.zebraMaterial.uniforms.stripes.value as number,
      axis: (surfaceView.zebraMaterial.uniforms.axis.value as { toArray(): number[] }).toArray(),
      curvatureRange: surfaceView.curvatureRange,
      analyticCurvature: surfaceView.analyticCurvature,
    }),
    /** The surface overlay's line vertices (the boundary curves), flat xyz. */
    overlayPoints: () => {
      const p = surfaceView.overlay.object.geometry.getAttribute('position');
      return p ? Array.from(p.array as Float32Array) : [];
    },
    /** A client point on the surface inside frame `f`'s patch (the modeller's picking): its
     * centre S(½, ½), the point farthest from the patch's vertices (a click near one picks
     * the vertex); else a triangle of the patch. */
    patchScreen: async (f: number) => {
      const mesh = store.state.mesh;
      if (!mesh) return null;
      const centre = await modellerTools.forces?.uvScreen(f, [0.5, 0.5]);
      if (centre) return centre;
      const { ids } = await api.patchIds(mesh.resolution);
      const mine = [...ids.keys()].filter((t) => ids[t] === f);
      return mine.length ? surfaceView.triangleScreen(mine[Math.floor(mine.length / 2)]) : null;
    },
    /** The selection: vertices in pick order, frames. */
    selection: () => ({ vertices: [...store.state.selectedVertices], frames: [...store.state.selectedFrames].sort((a, b) => a - b) }),
    /** The client point of the move gizmo's arrow along `axis` (null while it is hidden). */
    gizmoArrow: (axis: 'x' | 'y' | 'z') => modellerTools.gizmo?.handleScreen(axis) ?? null,
    /** The client point of the gizmo's handle of `axis`: arrow, scale box's stem, or a point
     * of the ring `angle` radians round (gizmo.ts handleScreen). */
    gizmoHandle: (axis: 'x' | 'y' | 'z', angle?: number) => modellerTools.gizmo?.handleScreen(axis, angle) ?? null,
    /** The client point of a handle of the selected force region (0..3 corners, 4 centre). */
    forceHandle: (h: number) => modellerTools.forces?.handleScreen(h) ?? null,
    /** The selected force's effect arrow: tail and tip in world coordinates, or null. */
    forceEffect: () => modellerTools.forces?.effect() ?? null,
    /** The shared force's effect arrows (over the selected frames): frame, tail, tip. */
    sharedForceEffects: () => modellerTools.forces?.sharedEffects() ?? [],
    /** The force outlines drawn on the surface: frame and region of each. */
    forceOutlines: () => modellerTools.forces?.drawn() ?? [],
    /** The client point of (u, v) on frame `f`'s patch. */
    uvScreen: (f: number, u: number, v: number) => modellerTools.forces?.uvScreen(f, [u, v]),
    /** Where vertex `v` of the model is in the surface view: client point, and whether it
     * is in front of the camera. */
    vertexSurfaceScreen: (v: number) => {
      const p = store.state.model?.vertices[v];
      return p ? surfaceView.toClient(new THREE.Vector3(...p)) : null;
    },
    /** The 3D cursor (cursor-tool.ts), and where it is on screen in each view. */
    cursor: () => ({
      p: [...store.state.cursor],
      frame: frameView.toClient(new THREE.Vector3(...store.state.cursor)),
      surface: surfaceView.toClient(new THREE.Vector3(...store.state.cursor)),
    }),
    /** The point of the surface shown under a client point of the frame view (what a drag
     * there snaps onto), or null. */
    surfaceUnder: (x: number, y: number) => {
      surfaceView.mesh.geometry.computeBoundingSphere();
      return onSurface(surfaceView.mesh, frameView, x, y);
    },
    /** The page's surface mesh positions, flat xyz. */
    meshPositions: () => Array.from(store.state.mesh?.positions ?? []),
  };
}
