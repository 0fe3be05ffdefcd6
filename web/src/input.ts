// What a number box accepts. No DOM here (web/test/input.test.ts).

export interface NumberRule {
  /** Named in the message ("x: type a number"). */
  label?: string;
  min?: number;
  max?: number;
  /** Refuse 0 (a magnification, a scale factor). */
  nonZero?: boolean;
}

/** The number `text` holds, or why it holds none: empty, not a number ("-", "1e", "abc"),
 * not finite, or outside the rule's range. Spaces around it are allowed. */
export function parseNumber(text: string, rule: NumberRule = {}): { value: number } | { error: string } {
  const name = rule.label ? `${rule.label}: ` : '';
  const t = text.trim();
  if (t === '') return { error: `${name}type a number (the box is empty)` };
  // Number() takes "0x10", "Infinity" and "" as numbers: accept decimal notation only.
  if (!/^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/.test(t)) return { error: `${name}"${t}" is not a number` };
  const value = Number(t);
  if (!Number.isFinite(value)) return { error: `${name}${t} is too large` };
  if (rule.nonZero && value === 0) return { error: `${name}must not be 0` };
  if (rule.min !== undefined && value < rule.min) return { error: `${name}must be at least ${rule.min}` };
  if (rule.max !== undefined && value > rule.max) return { error: `${name}must be at most ${rule.max}` };
  return { value };
}
