// The move / rotate / scale grid (number boxes and a button per row), made for the whole
// model's Transform panel and for the chosen curve's (web/index.html's `data-transform-grid`
// placeholders) before the parts that use its boxes mount (transform.ts, curve-editor.ts).

export interface TransformGrid {
  /** Starts every test id: '' for the model's grid, 'curve-' for the curve's. */
  prefix: string;
  /** Ends each button's test id ('-apply': move-apply; '': curve-move). */
  buttonSuffix: string;
  /** What the rotation's axis goes through, for its tooltip. */
  centre: string;
  degrees: number;
  factor: number;
}

export const TRANSFORM_GRIDS: Record<string, TransformGrid> = {
  model: { prefix: '', buttonSuffix: '-apply', centre: 'the centre', degrees: 90, factor: 2 },
  curve: { prefix: 'curve-', buttonSuffix: '', centre: "the curve's centre", degrees: 15, factor: 1.2 },
};

/** The grid's markup (every value here is the page's own, none from a user). */
export function transformGridHtml(g: TransformGrid): string {
  const id = (name: string) => `data-testid="${g.prefix}${name}"`;
  const button = (name: string, label: string) => `<button ${id(name + g.buttonSuffix)}>${label}</button>`;
  const offset = (axis: string) => `<input ${id(`move-${axis}`)} type="text" inputmode="decimal" data-number step="0.1" value="0" title="d${axis}" />`;
  return [
    '<span class="name">move</span>',
    offset('x'),
    offset('y'),
    offset('z'),
    button('move', 'Move'),
    '<span class="name">rotate</span>',
    `<select ${id('rotate-axis')} title="axis through ${g.centre}"><option>x</option><option>y</option><option selected>z</option></select>`,
    `<label><input ${id('rotate-degrees')} type="text" inputmode="decimal" data-number step="15" value="${g.degrees}" title="degrees" />°</label>`,
    '<span></span>',
    button('rotate', 'Rotate'),
    '<span class="name">scale</span>',
    `<label>×<input ${id('scale-factor')} type="text" inputmode="decimal" data-number step="0.1" min="0" value="${g.factor}" title="factor" /></label>`,
    '<span></span><span></span>',
    button('scale', 'Scale'),
  ].join('\n');
}

/** Fills every `data-transform-grid` placeholder of the page. */
export function makeTransformGrids(root: ParentNode = document): void {
  for (const host of root.querySelectorAll<HTMLElement>('[data-transform-grid]')) {
    const grid = TRANSFORM_GRIDS[host.dataset.transformGrid ?? ''];
    if (!grid) throw new Error(`unknown transform grid "${host.dataset.transformGrid}"`);
    host.innerHTML = transformGridHtml(grid);
  }
}
