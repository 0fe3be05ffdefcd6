// Keyboard shortcuts, and the help panel (?) that lists them: both from SHORTCUTS, so the
// help never disagrees with the keys.
import { $ } from './dom';
import type { Studio } from './studio';
import type { ModellerActions } from './modeller';
import { VIEWS } from './views';
import type { ViewActions } from './views';

interface Shortcut {
  /** As shown in the help ("Ctrl+Z"). */
  keys: string;
  what: string;
  /** Whether a keydown is this shortcut. */
  matches(ev: KeyboardEvent): boolean;
  run(): void;
}

const ctrl = (ev: KeyboardEvent) => ev.ctrlKey || ev.metaKey;
const plain = (key: string) => (ev: KeyboardEvent) => !ctrl(ev) && !ev.altKey && ev.key.toLowerCase() === key;

/** Whether a key typed into this element is text (a shortcut must not take it). */
function typing(target: EventTarget | null): boolean {
  if (target instanceof HTMLInputElement) return ['text', 'number', 'search'].includes(target.type);
  return target instanceof HTMLTextAreaElement || target instanceof HTMLSelectElement;
}

export function mountKeys(studio: Studio, views: ViewActions, modeller?: ModellerActions): void {
  const { store } = studio;
  const click = (id: string) => () => $<HTMLButtonElement>(id).click();
  /** Whether the open model is a spectral, cross-section or B-spline PDE one (its curves are
   * what the transform keys act on: curve-editor.ts). */
  const shapeModel = () => !!store.state.handles;
  const toggle = (id: string) => () => {
    const box = $<HTMLInputElement>(id);
    box.checked = !box.checked;
    box.dispatchEvent(new Event('change'));
  };
  const help = $('help');
  const showHelp = (on: boolean) => {
    help.hidden = !on;
    $('help-button').setAttribute('aria-pressed', String(on));
  };

  const shortcuts: Shortcut[] = [
    { keys: 'Ctrl+Z', what: 'Undo', matches: (e) => ctrl(e) && !e.shiftKey && e.key.toLowerCase() === 'z', run: click('undo') },
    { keys: 'Ctrl+Shift+Z, Ctrl+Y', what: 'Redo', matches: (e) => ctrl(e) && ((e.shiftKey && e.key.toLowerCase() === 'z') || e.key.toLowerCase() === 'y'), run: click('redo') },
    { keys: 'Ctrl+S', what: 'Save', matches: (e) => ctrl(e) && e.key.toLowerCase() === 's', run: click('save') },
    { keys: 'Escape', what: 'Close this help, else clear the selection', matches: (e) => e.key === 'Escape', run: () => {
      if (!help.hidden) return showHelp(false);
      store.update(['selection', 'forces'], (s) => {
        s.selectedVertex = null;
        s.selectedVertices = [];
        s.selectedFrames = new Set();
        s.selectedForce = 0;
      });
    } },
    { keys: 'Shift+Delete', what: "Remove the selected frame's selected force", matches: (e) => e.shiftKey && (e.key === 'Delete' || e.key === 'Backspace'), run: () => {
      const remove = document.querySelector<HTMLButtonElement>('.force.selected [data-testid$="-remove"]');
      if (remove) remove.click();
      else studio.say('Shift+Delete: select a frame and one of its forces first');
    } },
    { keys: 'F', what: 'Fit the selection (all when nothing is selected)', matches: (e) => plain('f')(e) && !e.shiftKey, run: () => views.fitSelection() },
    { keys: 'Shift+F, Home', what: 'Fit all', matches: (e) => (plain('f')(e) && e.shiftKey) || e.key === 'Home', run: () => views.fitAll() },
    ...VIEWS.map((v) => ({ keys: v.key, what: v.what, matches: plain(v.key), run: () => views.view(v.name) })),
    { keys: 'K', what: 'Link the two cameras (on/off)', matches: plain('k'), run: () => views.toggleLink() },
    { keys: 'Z', what: 'Zebra stripes (on/off)', matches: (e) => plain('z')(e) && !e.shiftKey, run: toggle('zebra') },
    { keys: 'C', what: 'Curvature colours: off, mean, Gaussian', matches: plain('c'), run: () => {
      const select = $<HTMLSelectElement>('curvature');
      select.selectedIndex = (select.selectedIndex + 1) % select.options.length;
      select.dispatchEvent(new Event('change'));
    } },
    { keys: 'B', what: 'Frame boundaries over the surface (on/off)', matches: plain('b'), run: toggle('overlay') },
    { keys: 'L', what: 'Live surface (on/off)', matches: plain('l'), run: toggle('live') },
    { keys: '?', what: 'This help (on/off)', matches: (e) => e.key === '?', run: () => showHelp(help.hidden) },
  ];
  // The modeller's tools (modeller.ts), on the selection.
  if (modeller)
    shortcuts.push(
      { keys: 'N', what: 'New model (one frame, a grid or a tube)', matches: plain('n'), run: () => modeller.newModel() },
      { keys: 'E', what: 'Extrude the selected boundary edges (both corners selected)', matches: plain('e'), run: () => modeller.extrude() },
      { keys: 'A', what: 'Add a frame on the 4 selected corners (picked in turn)', matches: plain('a'), run: () => modeller.addFrame() },
      { keys: 'Delete, X', what: 'Delete the selected frames (one undo step)', matches: (e) => (e.key === 'Delete' || e.key === 'Backspace' || plain('x')(e)) && !e.shiftKey, run: () => modeller.deleteFrames() },
      { keys: 'S', what: 'Split the selected frames (Ctrl+A: all) into 2 × 2; the cuts run on through the neighbours', matches: (e) => plain('s')(e) && !e.shiftKey, run: () => modeller.split('4') },
      { keys: 'W', what: 'Weld 2 selected vertices, or 2 selected boundary edges', matches: plain('w'), run: () => modeller.weld() },
      { keys: 'R', what: "Flip the selected frames' u direction", matches: (e) => plain('r')(e) && !e.shiftKey, run: () => modeller.flip() },
      { keys: 'M', what: "Mirror: copy the selected frames across the panel's symmetry plane, welded at the seam", matches: plain('m'), run: () => modeller.mirror() },
      { keys: 'G', what: "Gizmo on the selection, or on the chosen curve's centre (on/off)", matches: (e) => plain('g')(e) && !e.shiftKey, run: () => modeller.toggleGizmo() },
      { keys: 'Shift+G', what: "The gizmo's next handles: arrows (move), rings (rotate), boxes (scale), along the panel's axes", matches: (e) => plain('g')(e) && e.shiftKey, run: () => modeller.cycleGizmo() },
      { keys: 'Shift+S', what: "Scale the selection, or the chosen curve, about the panel's pivot (its factor)", matches: (e) => plain('s')(e) && e.shiftKey, run: () => (shapeModel() ? click('curve-scale')() : modeller.scaleSelection()) },
      { keys: 'Shift+R', what: "Rotate the selection, or the chosen curve, about the panel's pivot (its axis and degrees)", matches: (e) => plain('r')(e) && e.shiftKey, run: () => (shapeModel() ? click('curve-rotate')() : modeller.rotateSelection()) },
      { keys: 'D', what: 'Draw force: drag a rectangle on a patch (on/off)', matches: plain('d'), run: () => modeller.toggleDrawForce() },
      { keys: 'Ctrl+A', what: 'Select all: every frame and vertex', matches: (e) => ctrl(e) && !e.shiftKey && e.key.toLowerCase() === 'a', run: () => modeller.select('all') },
      { keys: 'Ctrl+I', what: 'Invert the selection', matches: (e) => ctrl(e) && e.key.toLowerCase() === 'i', run: () => modeller.select('inverse') },
      { keys: 'Ctrl+L', what: 'Select linked: every frame joined to the selection, with its vertices', matches: (e) => ctrl(e) && e.key.toLowerCase() === 'l', run: () => modeller.select('linked') },
      // By the key's place (e.code): Alt+letter types another character on some layouts.
      { keys: 'Alt+L', what: 'Loop select: the strip of frames through each selected frame along its u (across u = 0 and u = 1), round a tube too', matches: (e) => e.altKey && !ctrl(e) && e.code === 'KeyL', run: () => modeller.select('loop') },
      { keys: 'Alt+R', what: 'Ring select: the strip of frames through each selected frame along its v (across v = 0 and v = 1)', matches: (e) => e.altKey && !ctrl(e) && e.code === 'KeyR', run: () => modeller.select('ring') },
    );

  // The help: one row per shortcut, and what the mouse does.
  const table = $('help-keys');
  for (const s of shortcuts) {
    const row = document.createElement('tr');
    const k = document.createElement('td');
    for (const [i, part] of s.keys.split(', ').entries()) {
      if (i) k.append(' or ');
      const kbd = document.createElement('kbd');
      kbd.textContent = part;
      k.append(kbd);
    }
    const w = document.createElement('td');
    w.textContent = s.what;
    row.append(k, w);
    table.append(row);
  }
  $('help-button').addEventListener('click', () => showHelp(help.hidden));
  $('help-close').addEventListener('click', () => showHelp(false));

  document.addEventListener('keydown', (ev) => {
    if (ev.defaultPrevented || $<HTMLDialogElement>('unsaved-dialog').open || $<HTMLDialogElement>('new-dialog').open) return;
    // In a text or number box keys are text, except Escape (leave the box).
    if (typing(ev.target)) {
      if (ev.key === 'Escape') (ev.target as HTMLElement).blur();
      return;
    }
    const shortcut = shortcuts.find((s) => s.matches(ev));
    if (!shortcut) return;
    ev.preventDefault();
    shortcut.run();
  });
}
