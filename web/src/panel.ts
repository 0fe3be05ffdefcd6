// The side panel of a vertex-frame model: the selected vertex's coordinates, the a1 / a2
// sliders of the selected frames, and their forces (regions, f0 sliders).
import type { Edit, FrameForce, Region, Vec3 } from './api';
import { $, numberBox, readNumber } from './dom';
import { forceDisplacement, forceEffectText, sharedEffectText, sharedForceOf } from './regions';
import type { State } from './store';
import type { Studio } from './studio';

const AXES = ['x', 'y', 'z'] as const;

/** A power of ten (signed) that puts |value| in (0.1, 1]: the default magnification. */
export function niceMagnification(value: number): number {
  if (value === 0 || !Number.isFinite(value)) return 1;
  const m = Math.pow(10, Math.ceil(Math.log10(Math.abs(value)) - 1e-9));
  return Math.sign(value) * Math.max(m, 1);
}

interface SliderRow {
  set(value: number | null): void;
}

/** A slider with its range box (the slider runs from 0 to the range: value = slider ×
 * range) and a box with the actual value, which takes a typed number or expression (the
 * range then follows it). The gesture (pointer down to change) is one undo group; a typed
 * value or range is one step. */
function sliderRow(
  studio: Studio,
  parent: HTMLElement,
  id: string,
  label: string,
  onValue: (value: number) => void,
): SliderRow {
  const row = document.createElement('div');
  row.className = 'slider ranged';
  const name = document.createElement('span');
  name.className = 'name';
  name.textContent = label;
  const range = document.createElement('input');
  range.type = 'range';
  range.min = '0';
  range.max = '1';
  range.step = '0.001';
  range.dataset.testid = id;
  const mag = document.createElement('input');
  numberBox(mag);
  mag.title = `${label}: the slider's range (it runs from 0 to this)`;
  mag.dataset.testid = `${id}-mag`;
  const value = document.createElement('input');
  numberBox(value);
  value.className = 'value';
  value.title = `${label} (a number or an expression: 1/3, 2*pi)`;
  value.dataset.testid = `${id}-value`;
  const times = document.createElement('span');
  times.className = 'range-label';
  times.textContent = '0 …';
  row.append(name, range, times, mag, value);
  parent.append(row);

  let magnification = 1; // the last number the box held
  const current = () => Number(range.value) * magnification;
  const show = () => {
    value.value = String(+current().toFixed(6));
    value.classList.remove('invalid');
    value.setCustomValidity('');
  };
  value.addEventListener('change', () => {
    const v = readNumber(value, { label }, (message) => studio.showError(message));
    if (v === null) return; // refused in place: nothing changes, nothing is recorded
    magnification = niceMagnification(v);
    mag.value = String(magnification);
    range.value = String(v / magnification);
    studio.beginGesture(id);
    onValue(v); // exactly what was typed, not the slider's rounding of it
    void studio.endGesture();
  });
  let gesture = false; // from the first input to the change event: one undo group
  range.addEventListener('input', () => {
    if (!gesture) studio.beginGesture(id);
    gesture = true;
    show();
    onValue(current());
  });
  range.addEventListener('change', () => {
    gesture = false;
    void studio.endGesture();
  });
  mag.addEventListener('change', () => {
    const m = readNumber(mag, { label: `${label} magnification`, nonZero: true }, (message) => studio.showError(message));
    if (m === null) return; // refused in place: nothing changes, nothing is recorded
    magnification = m;
    show();
    studio.beginGesture(id);
    onValue(current());
    void studio.endGesture();
  });
  return {
    set(v: number | null) {
      row.classList.toggle('disabled', v === null);
      range.disabled = mag.disabled = value.disabled = v === null;
      if (v === null) {
        value.value = '';
        return;
      }
      magnification = niceMagnification(v);
      mag.value = String(magnification);
      mag.classList.remove('invalid');
      mag.setCustomValidity('');
      range.value = String(v / magnification);
      if (document.activeElement !== value) value.value = String(+v.toFixed(6));
    },
  };
}

function sub(parent: HTMLElement, text: string): void {
  const d = document.createElement('div');
  d.className = 'sub';
  d.textContent = text;
  parent.append(d);
}

const selectedFrameList = (state: Readonly<State>) => [...state.selectedFrames].sort((a, b) => a - b);


export function mountPanel(studio: Studio): void {
  const { store, pump } = studio;
  const report = (message: string) => studio.showError(message);
  const firstFrame = () => {
    const s = store.state;
    return s.model && s.selectedFrames.size ? s.model.frames[selectedFrameList(s)[0]] : null;
  };

  // The selected vertex's coordinates.
  function renderVertexInputs(): void {
    const { selectedVertex: v, model } = store.state;
    $('vertex-index').textContent = v === null ? 'none' : `#${v}`;
    AXES.forEach((a, i) => {
      const input = $<HTMLInputElement>(`vertex-${a}`);
      input.disabled = v === null;
      if (document.activeElement !== input) {
        input.value = v === null || !model ? '' : String(+model.vertices[v][i].toFixed(5));
        input.classList.remove('invalid');
        input.setCustomValidity('');
      }
    });
  }
  AXES.forEach((a, i) => {
    const input = $<HTMLInputElement>(`vertex-${a}`);
    input.addEventListener('change', () => {
      const { selectedVertex: v, model } = store.state;
      if (v === null || !model) return;
      const value = readNumber(input, {}, report);
      if (value === null) return; // refused in place: the vertex stays, no undo step
      const position = [...model.vertices[v]] as Vec3;
      position[i] = value;
      store.update(['vertex'], (s) => (s.model!.vertices[v] = position));
      void pump.once('vertex', () => ({ op: 'move-vertex', vertex: v, position }));
    });
  });

  // a1, a2: set-parameters over the selected frames.
  const parameterRows: Record<'a1' | 'a2', SliderRow[]> = { a1: [], a2: [] };
  const parameters = document.getElementById('parameters')!;
  for (const p of ['a1', 'a2'] as const) {
    sub(parameters, `${p} (x, y, z)`);
    AXES.forEach((a, i) => {
      parameterRows[p].push(
        sliderRow(studio, parameters, `${p}-${a}`, `${p}.${a}`, (value) => {
          const frames = selectedFrameList(store.state);
          const frame = firstFrame();
          if (!frame || !store.state.model) return;
          const vec = [...(frame[p] ?? [1, 1, 1])] as Vec3;
          vec[i] = value;
          // The slider shows the value already: a change nothing needs to redraw.
          store.update([], (s) => {
            for (const f of frames) s.model!.frames[f][p] = [...vec] as Vec3;
          });
          pump.push(() => ({ op: 'set-parameters', frames, [p]: vec }) as Edit);
        }),
      );
    });
  }

  // f0 of the selected force: set-forces for one frame, set-shared-forces for several.
  const forceRows: SliderRow[] = [];
  const forceSliders = document.getElementById('force-sliders')!;
  sub(forceSliders, 'f0 (x, y, z) of the selected force');
  AXES.forEach((a, i) => {
    forceRows.push(
      sliderRow(studio, forceSliders, `f0-${a}`, `f0.${a}`, (value) => {
        const state = store.state;
        const model = state.model;
        if (!model) return;
        const frames = selectedFrameList(state);
        if (frames.length === 1) {
          const frame = model.frames[frames[0]];
          const force = frame.forces?.[state.selectedForce];
          if (!force) return;
          store.update([], () => {
            force.f0 = [...force.f0] as Vec3;
            force.f0[i] = value;
          });
          renderForceEffect();
          const forces = structuredClone(frame.forces!);
          pump.push(() => ({ op: 'set-forces', frame: frames[0], forces }));
        } else if (frames.length > 1) {
          store.update(['forces'], (s) => {
            const m = s.model!;
            m.forces ??= [];
            let shared = sharedForceOf(m, frames);
            if (!shared) {
              shared = { f0: [0, 0, 0], frames };
              m.forces.push(shared);
            }
            shared.f0 = [...shared.f0] as Vec3;
            shared.f0[i] = value;
          });
          const forces = structuredClone(model.forces!);
          pump.push(() => ({ op: 'set-shared-forces', forces }));
        }
      }),
    );
  });

  /** Sets a frame's forces in the page's copy and on the server (one undo step). */
  function setForces(f: number, forces: FrameForce[], selected?: number): void {
    store.update(['forces'], (s) => {
      s.model!.frames[f].forces = forces;
      if (selected !== undefined) s.selectedForce = selected;
    });
    const sent = structuredClone(forces);
    void pump.once('force', () => ({ op: 'set-forces', frame: f, forces: sent }));
  }

  function renderForceList(): void {
    const list = $('force-list');
    list.replaceChildren();
    const state = store.state;
    const model = state.model;
    const frames = selectedFrameList(state);
    $<HTMLButtonElement>('add-force').disabled = frames.length !== 1;
    renderForceEffect();
    if (!model || frames.length === 0) {
      list.textContent = 'Select a frame to edit its forces.';
      list.className = 'forces muted';
      forceRows.forEach((r) => r.set(null));
      return;
    }
    list.className = 'forces';
    if (frames.length > 1) {
      const shared = sharedForceOf(model, frames);
      const item = document.createElement('div');
      item.className = 'force shared selected';
      item.dataset.testid = 'shared-force';
      item.textContent = shared
        ? `shared force over frames ${frames.join(', ')}: f0 = [${shared.f0.map((x) => +x.toFixed(3)).join(', ')}]`
        : `no shared force over frames ${frames.join(', ')} yet: move an f0 slider to add one`;
      list.append(item);
      const f0 = shared?.f0 ?? [0, 0, 0];
      forceRows.forEach((r, i) => r.set(f0[i]));
      return;
    }
    const f = frames[0];
    const forces = model.frames[f].forces ?? [];
    const selectedForce = Math.min(state.selectedForce, Math.max(0, forces.length - 1));
    if (forces.length) {
      const head = document.createElement('div');
      head.className = 'force head';
      for (const text of ['', 'u0', 'u1', 'v0', 'v1', '']) {
        const cell = document.createElement('span');
        cell.textContent = text;
        head.append(cell);
      }
      list.append(head);
    }
    forces.forEach((force, k) => {
      const item = document.createElement('div');
      item.className = `force${k === selectedForce ? ' selected' : ''}`;
      item.dataset.testid = `force-${k}`;
      const tag = document.createElement('span');
      tag.className = 'tag';
      tag.textContent = `#${k}`;
      item.append(tag);
      const region: Region = force.region ?? [0, 1, 0, 1];
      ['u0', 'u1', 'v0', 'v1'].forEach((name, j) => {
        const input = document.createElement('input');
        numberBox(input);
        input.step = '0.05';
        input.min = '0';
        input.max = '1';
        input.title = name;
        input.value = String(region[j]);
        input.dataset.testid = `force-${k}-${name}`;
        input.addEventListener('change', () => {
          const value = readNumber(input, { label: `force #${k} ${name}`, min: 0, max: 1 }, report);
          if (value === null) return;
          const next = [...region] as Region;
          next[j] = value;
          const all = forces.map((x, i) => (i === k ? { ...x, region: next } : x));
          setForces(f, all);
        });
        item.append(input);
      });
      const remove = document.createElement('button');
      remove.textContent = '×';
      remove.title = 'Remove this force';
      remove.dataset.testid = `force-${k}-remove`;
      remove.addEventListener('click', (ev) => {
        ev.stopPropagation();
        setForces(f, forces.filter((_, j) => j !== k));
      });
      item.append(remove);
      item.addEventListener('click', () => store.update(['forces'], (s) => (s.selectedForce = k)));
      list.append(item);
    });
    if (forces.length === 0) {
      const none = document.createElement('div');
      none.className = 'muted';
      none.textContent = `Frame ${f} has no force.`;
      list.append(none);
    }
    const force = forces[selectedForce];
    forceRows.forEach((r, i) => r.set(force ? force.f0[i] : null));
    renderForceEffect();
  }

  /** The selected force's effect in words, live as its sliders move (its arrow on the
   * surface: forces-tool.ts): one frame's selected force, or the shared force over the selected
   * frames; else empty. */
  function renderForceEffect(): void {
    const state = store.state;
    const frames = selectedFrameList(state);
    const frame = frames.length === 1 ? state.model?.frames[frames[0]] : undefined;
    const force = frame?.forces?.[Math.min(state.selectedForce, frame.forces.length - 1)];
    const shared = frames.length > 1 && state.model ? sharedForceOf(state.model, frames) : undefined;
    $('force-effect').textContent = force
      ? forceEffectText(forceDisplacement(force.f0, frame!.a1 ?? [1, 1, 1], frame!.a2 ?? [1, 1, 1], force.region ?? [0, 1, 0, 1]))
      : shared
        ? sharedEffectText(state.model!, shared)
        : '';
  }

  $('add-force').addEventListener('click', () => {
    const frames = selectedFrameList(store.state);
    const model = store.state.model;
    if (!model || frames.length !== 1) return;
    const forces: FrameForce[] = [
      ...(model.frames[frames[0]].forces ?? []),
      { f0: [0, 0, 0], region: [0.25, 0.75, 0.25, 0.75] },
    ];
    setForces(frames[0], forces, forces.length - 1);
  });

  store.subscribe(['model', 'selection'], (state) => {
    // Vertex, frame and force tools only mean something for a vertex-frame model.
    for (const part of document.querySelectorAll<HTMLElement>('.frame-tools')) part.hidden = !state.hasEditableParts;
    renderVertexInputs();
    const frames = selectedFrameList(state);
    $('frame-selection').textContent = frames.length ? frames.map((f) => `#${f}`).join(' ') : 'none';
    const frame = firstFrame();
    for (const p of ['a1', 'a2'] as const)
      parameterRows[p].forEach((r, i) => r.set(frame ? (frame[p] ?? [1, 1, 1])[i] : null));
  });
  store.subscribe(['model', 'selection', 'forces'], () => renderForceList());
  store.subscribe(['vertex'], () => renderVertexInputs());
}
