// The toolbar and the surface view's bar: undo and redo, open, save, save as, export, the
// autosave's recovery, Live / Create / Res, zebra and the frame overlay.
import { api } from './api';
import { $, plural } from './dom';
import { overlayWanted } from './scene-sync';
import type { Studio } from './studio';

/** The formats the page exports: meshes (the surface tessellated) and CAD (B-spline faces,
 * as `pdesurf export` writes them). */
export const EXPORT_FORMATS = ['obj', 'stl', 'glb', 'ply', 'off', 'step', 'iges'] as const;

/** The export name a model's path suggests: its path without ".json". */
export function exportNameOf(path: string): string {
  return path.replace(/\.json$/, '');
}

type Choice = 'save' | 'discard' | 'cancel';

/** Asks what to do with unsaved edits before they would leave the page. */
function askUnsaved(path: string): Promise<Choice> {
  const dialog = $<HTMLDialogElement>('unsaved-dialog');
  $('unsaved-path').textContent = path;
  return new Promise((resolve) => {
    const done = (choice: Choice) => {
      for (const [id, fn] of handlers) $(id).removeEventListener('click', fn);
      dialog.removeEventListener('cancel', onCancel);
      dialog.close();
      resolve(choice);
    };
    const handlers: [string, () => void][] = [
      ['unsaved-save', () => done('save')],
      ['unsaved-discard', () => done('discard')],
      ['unsaved-cancel', () => done('cancel')],
    ];
    const onCancel = (ev: Event) => {
      ev.preventDefault();
      done('cancel'); // Escape
    };
    for (const [id, fn] of handlers) $(id).addEventListener('click', fn);
    dialog.addEventListener('cancel', onCancel);
    dialog.showModal();
  });
}

export function mountToolbar(studio: Studio): { refreshFiles: () => Promise<void>; mayLeave: () => Promise<boolean> } {
  const { store, surfaceView } = studio;

  /** Whether the current model may be left: saved, or the user chose to save or discard
   * its edits (a discarded edit stays in the autosave beside its file). */
  async function mayLeave(): Promise<boolean> {
    await studio.pump.end();
    if (!store.state.status?.dirty) return true;
    const choice = await askUnsaved(store.state.path);
    if (choice === 'cancel') return false;
    if (choice === 'save') await save();
    return true;
  }

  async function save(): Promise<void> {
    const s = await api.save();
    studio.say(`saved ${s.path}`);
    await studio.reloadModel();
  }

  async function undo(): Promise<void> {
    await studio.run(async () => {
      const status = await api.undo();
      store.update(['status'], (s) => (s.status = status));
      await studio.reloadAll();
    });
  }
  async function redo(): Promise<void> {
    await studio.run(async () => {
      const status = await api.redo();
      store.update(['status'], (s) => (s.status = status));
      await studio.reloadAll();
    });
  }
  $('undo').addEventListener('click', () => void undo());
  $('redo').addEventListener('click', () => void redo());

  async function refreshFiles(): Promise<void> {
    try {
      const files = await api.files();
      const select = $<HTMLSelectElement>('file-select');
      select.replaceChildren(
        ...files.map((f) => {
          const o = document.createElement('option');
          o.value = o.textContent = f;
          return o;
        }),
      );
      if (files.includes(store.state.path)) select.value = store.state.path;
    } catch (e) {
      studio.showError(e);
    }
  }

  $('open').addEventListener('click', () =>
    void studio.run(async () => {
      const select = $<HTMLSelectElement>('file-select');
      const path = select.value;
      if (!path) return;
      if (!(await mayLeave())) {
        // Cancelled: the list names the model still open again, not the one not opened.
        if ([...select.options].some((o) => o.value === store.state.path)) select.value = store.state.path;
        return;
      }
      await api.open(path);
      studio.say(`opened ${path}`);
      await studio.reloadAll(true);
    }),
  );
  $('save').addEventListener('click', () => void studio.run(save));
  $('save-as').addEventListener('click', () =>
    void studio.run(async () => {
      const input = $<HTMLInputElement>('saveas-path');
      let path = input.value.trim();
      if (!path) throw new Error('Save as: type a file name (.json) first');
      if (!path.endsWith('.json')) path += '.json';
      const s = await api.saveAs(path);
      studio.say(`saved as ${s.path}`);
      await studio.reloadModel();
      await refreshFiles();
    }),
  );

  // The export name follows the model's file (open, save as); a name typed in the box
  // stays until the model's file changes.
  let exportPath: string | null = null;
  store.subscribe(['model', 'status'], (state) => {
    if (state.path === exportPath) return;
    exportPath = state.path;
    $<HTMLInputElement>('export-name').value = exportNameOf(state.path);
  });
  for (const ext of EXPORT_FORMATS) {
    $(`export-${ext}`).addEventListener('click', () =>
      void studio.run(async () => {
        const name = $<HTMLInputElement>('export-name').value.trim() || 'surface';
        const r = await api.exportFile(`${name}.${ext}`);
        studio.say(
          r.faces !== undefined
            ? `exported ${r.path} (${plural(r.faces, 'face')}, max deviation ${r.maxDeviation?.toPrecision(2)})`
            : `exported ${r.path} (${plural(r.triangles ?? 0, 'triangle')})`,
        );
      }),
    );
  }

  $('recover').addEventListener('click', () =>
    void studio.run(async () => {
      await api.recover();
      studio.say('recovered the autosave');
      await studio.reloadAll(true);
    }),
  );
  $('discard').addEventListener('click', () =>
    void studio.run(async () => {
      await api.discardRecovery();
      studio.say('discarded the autosave');
      await studio.reloadModel();
    }),
  );
  $('create').addEventListener('click', () => void studio.meshes.request());
  $('live').addEventListener('change', () => {
    if (studio.live() && store.state.meshStale) void studio.meshes.request();
  });
  $('resolution').addEventListener('change', () => void studio.meshes.request());
  $<HTMLInputElement>('zebra').addEventListener('change', (ev) =>
    surfaceView.setZebra((ev.target as HTMLInputElement).checked),
  );
  $<HTMLInputElement>('overlay').addEventListener('change', () => surfaceView.setOverlay(overlayWanted(studio)));

  // Leaving the page with unsaved edits: the browser asks (the autosave keeps them anyway).
  window.addEventListener('beforeunload', (ev) => {
    if (store.state.status?.dirty) ev.preventDefault();
  });

  return { refreshFiles, mayLeave };
}
