// The page's elements by their data-testid, and reading numbers typed into boxes.
import { parseNumber } from './input';
import type { NumberRule } from './input';

export function $<T extends HTMLElement = HTMLElement>(id: string): T {
  const el = document.querySelector<T>(`[data-testid="${id}"]`);
  if (!el) throw new Error(`missing element ${id}`);
  return el;
}

/** A button of the page made from a table: its data-testid, label, title and click. */
export function makeButton(id: string, label: string, title: string, click: () => void): HTMLButtonElement {
  const button = document.createElement('button');
  button.dataset.testid = id;
  button.textContent = label;
  button.title = title;
  button.addEventListener('click', click);
  return button;
}

export function plural(n: number, word: string): string {
  return `${n} ${word}${n === 1 ? '' : 's'}`;
}

/** The number in a box, or null when it holds none: then the box is marked invalid, says
 * why (the browser's validity bubble, and `report`) and nothing is done with it. The mark
 * goes when the box next holds a number. */
export function readNumber(
  input: HTMLInputElement,
  rule: NumberRule,
  report: (message: string) => void,
): number | null {
  // A browser's own number box holding text it cannot parse reports value "" and badInput.
  const text = input.validity?.badInput ? '?' : input.value;
  const parsed = parseNumber(text, { label: input.title || input.dataset.testid, ...rule });
  const error = 'error' in parsed ? parsed.error : '';
  input.setCustomValidity(error);
  input.classList.toggle('invalid', error !== '');
  input.setAttribute('aria-invalid', String(error !== ''));
  if (error) {
    input.reportValidity();
    report(error);
    return null;
  }
  return (parsed as { value: number }).value;
}

/** Makes `input` a number box that takes expressions (`1/3`, `2*pi`: input.ts): a text box
 * with the decimal keyboard (a browser's number box would refuse the expression's text). */
export function numberBox(input: HTMLInputElement): void {
  input.type = 'text';
  input.inputMode = 'decimal';
  input.dataset.number = '';
}
