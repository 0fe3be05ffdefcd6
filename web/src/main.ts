// The studio page: builds the context (studio.ts: store, views, edit pump, mesh sync) and
// mounts the parts that read and change it, the way the three.js editor mounts its
// viewport, sidebar and menubar on its `editor`. The server holds the model; the page keeps
// a copy that it updates as it sends edits (so a drag is smooth) and reloads after undo,
// redo, open and any refused edit.
import './style.css';
import { mountAnalysis } from './analysis';
import { mountCurveEditor } from './curve-editor';
import { mountCursor } from './cursor-tool';
import { mountDragTool } from './drag';
import { mountKeys } from './keys';
import { mountModeller } from './modeller';
import { mountPanel } from './panel';
import { mountSceneSync } from './scene-sync';
import { mountSolver } from './solver';
import { mountStatusBar } from './statusbar';
import { Studio } from './studio';
import { mountToolbar } from './toolbar';
import { mountTransform } from './transform';
import { makeTransformGrids } from './transform-grid';
import { mountViews } from './views';

makeTransformGrids(); // before the parts that read its boxes mount
const studio = new Studio();
mountStatusBar(studio);
mountSceneSync(studio);
const dragTool = mountDragTool(studio); // before the orbit controls: a press on a handle must not orbit
mountCurveEditor(studio); // the same for the handles of spectral and B-spline models
studio.frameView.attachControls();
studio.surfaceView.attachControls();
mountPanel(studio);
mountTransform(studio);
const toolbar = mountToolbar(studio);
mountAnalysis(studio);
const modeller = mountModeller(studio, toolbar.mayLeave, toolbar.refreshFiles, dragTool);
mountCursor(studio);
mountSolver(studio);
mountKeys(studio, mountViews(studio), modeller);

function frame(): void {
  studio.frameView.renderIfNeeded();
  studio.surfaceView.renderIfNeeded();
  requestAnimationFrame(frame);
}

void (async () => {
  if (navigator.webdriver || new URLSearchParams(location.search).has('test'))
    (await import('./test-hooks')).installTestHooks(studio);
  studio.store.update(['model', 'selection', 'status'], () => {});
  frame();
  await studio.reloadAll(true);
  await toolbar.refreshFiles();
  document.body.dataset.ready = 'true';
})();
