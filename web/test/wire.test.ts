// The mesh wire format (apps/studio/README.md): whole meshes and deltas parsed as the server
// lays them out, deltas written into their mesh, and malformed answers refused.
import { describe, expect, it } from 'vitest';
import { applyDelta, parseMesh } from '../src/wire';
import type { MeshData, MeshDelta } from '../src/wire';

/** A whole mesh as the server sends it (sendMesh in apps/studio/server.cpp). */
function fullBuffer(v: number, t: number, revision: number, resolution: number): ArrayBuffer {
  const buffer = new ArrayBuffer(16 + 4 * (6 * v + 3 * t));
  new Uint32Array(buffer, 0, 4).set([v, t, revision, resolution]);
  const positions = new Float32Array(buffer, 16, 3 * v);
  const normals = new Float32Array(buffer, 16 + 12 * v, 3 * v);
  positions.forEach((_, i) => (positions[i] = i + 0.5));
  normals.forEach((_, i) => (normals[i] = -i));
  const indices = new Uint32Array(buffer, 16 + 24 * v, 3 * t);
  indices.forEach((_, i) => (indices[i] = i % v));
  return buffer;
}

/** A delta (sendMeshDelta): runs (start, count), then the changed positions and normals. */
function deltaBuffer(v: number, t: number, revision: number, runs: number[], value: (k: number) => number): ArrayBuffer {
  const changed = runs.reduce((n, x, i) => (i % 2 ? n + x : n), 0);
  const buffer = new ArrayBuffer(20 + 4 * runs.length + 24 * changed);
  new Uint32Array(buffer, 0, 5).set([v, t, revision, 9, runs.length / 2]);
  new Uint32Array(buffer, 20, runs.length).set(runs);
  const data = new Float32Array(buffer, 20 + 4 * runs.length, 6 * changed);
  data.forEach((_, k) => (data[k] = value(k)));
  return buffer;
}

const headers = (extra: Record<string, string> = {}) =>
  new Headers({ 'X-Mesh-Id': '7', 'X-Solve-Ms': '1.5', 'X-Tessellate-Ms': '0.25', 'X-C0-Gap': '0', ...extra });

describe('parseMesh', () => {
  it('reads a whole mesh without copying, with its headers', () => {
    const buffer = fullBuffer(4, 2, 3, 9);
    const m = parseMesh(buffer, headers()) as MeshData;
    expect(m.kind).toBe('full');
    expect([m.vertexCount, m.triangleCount, m.revision, m.resolution]).toEqual([4, 2, 3, 9]);
    expect(Array.from(m.positions.subarray(0, 3))).toEqual([0.5, 1.5, 2.5]);
    expect(m.normals[11]).toBe(-11);
    expect(Array.from(m.indices)).toEqual([0, 1, 2, 3, 0, 1]);
    expect(m.positions.buffer).toBe(buffer);
    expect([m.id, m.solveMs, m.tessellateMs, m.c0Gap]).toEqual([7, 1.5, 0.25, 0]);
  });

  it('refuses a whole mesh whose size disagrees with its header', () => {
    const buffer = fullBuffer(4, 2, 3, 9).slice(0, 100);
    expect(() => parseMesh(buffer, headers())).toThrow(/100 bytes, expected 136/);
    expect(() => parseMesh(new ArrayBuffer(8), headers())).toThrow(/truncated header/);
  });

  it('reads a delta when the answer names its base', () => {
    const d = parseMesh(deltaBuffer(4, 2, 4, [1, 2], (k) => 100 + k), headers({ 'X-Mesh-Base': '6' })) as MeshDelta;
    expect(d.kind).toBe('delta');
    expect(d.base).toBe(6);
    expect(Array.from(d.runs)).toEqual([1, 2]);
    expect(d.positions.length).toBe(6);
    expect(d.normals[0]).toBe(106);
  });

  it('refuses a delta whose runs or data are cut short', () => {
    const full = deltaBuffer(4, 2, 4, [0, 1, 2, 2], () => 1);
    expect(() => parseMesh(full.slice(0, full.byteLength - 4), headers({ 'X-Mesh-Base': '6' }))).toThrow(/expected/);
    expect(() => parseMesh(full.slice(0, 24), headers({ 'X-Mesh-Base': '6' }))).toThrow(/truncated runs/);
  });
});

describe('applyDelta', () => {
  const base = () => parseMesh(fullBuffer(4, 2, 3, 9), headers()) as MeshData;
  const delta = (runs: number[], extra: Record<string, string> = {}) =>
    parseMesh(deltaBuffer(4, 2, 4, runs, (k) => 100 + k), headers({ 'X-Mesh-Base': '7', 'X-Mesh-Id': '8', ...extra })) as MeshDelta;

  it('writes the changed runs, and only them, and takes the new id and revision', () => {
    const m = base();
    const before = Array.from(m.positions);
    expect(applyDelta(m, delta([1, 1, 3, 1]))).toBe(true);
    // Vertex 1 and 3 take the delta's positions (100..105) and normals (106..111).
    expect(Array.from(m.positions.subarray(3, 6))).toEqual([100, 101, 102]);
    expect(Array.from(m.positions.subarray(9, 12))).toEqual([103, 104, 105]);
    expect(Array.from(m.normals.subarray(3, 6))).toEqual([106, 107, 108]);
    expect(Array.from(m.positions.subarray(0, 3))).toEqual(before.slice(0, 3));
    expect(Array.from(m.positions.subarray(6, 9))).toEqual(before.slice(6, 9));
    expect([m.id, m.revision]).toEqual([8, 4]);
  });

  it('does not apply a delta made against another mesh, or running past its end', () => {
    const m = base();
    expect(applyDelta(m, delta([0, 1], { 'X-Mesh-Base': '5' }))).toBe(false);
    expect(applyDelta(m, delta([3, 2]))).toBe(false);
    expect(m.id).toBe(7);
  });
});
