// What a number box accepts. No DOM here (web/test/input.test.ts).

export interface NumberRule {
  /** Named in the message ("x: type a number"). */
  label?: string;
  min?: number;
  max?: number;
  /** Refuse 0 (a magnification, a scale factor). */
  nonZero?: boolean;
}

/** A decimal number (Number() alone takes "0x10", "Infinity" and "" as numbers). */
const DECIMAL = /^(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?/;
/** The names an expression may use: constants and functions of one argument (radians). */
const CONSTANTS: Record<string, number> = { pi: Math.PI, e: Math.E };
const FUNCTIONS: Record<string, (x: number) => number> = {
  sqrt: Math.sqrt,
  sin: Math.sin,
  cos: Math.cos,
  tan: Math.tan,
  abs: Math.abs,
};

/** The value of an arithmetic expression (`1/3`, `2*pi`, `-(0.5 + 1e-3)^2`, `sqrt(2)/2`),
 * parsed by recursive descent, never evaluated as code; null when `text` is not one. The
 * grammar: sum = product (('+' | '-') product)*, product = power (('*' | '/') power)*,
 * power = ('+' | '-')? atom ('^' power)? (so -2^2 = -4, 2^-1 = 0.5), atom = number |
 * constant | function '(' sum ')' | '(' sum ')'. */
export function evaluateExpression(text: string): number | null {
  let i = 0;
  const space = () => {
    while (text[i] === ' ') ++i;
  };
  const eat = (c: string) => {
    space();
    if (text[i] !== c) return false;
    ++i;
    return true;
  };
  const sum = (): number | null => {
    let v = product();
    while (v !== null) {
      if (eat('+')) v = add(v, product(), 1);
      else if (eat('-')) v = add(v, product(), -1);
      else break;
    }
    return v;
  };
  const add = (a: number, b: number | null, sign: number) => (b === null ? null : a + sign * b);
  const product = (): number | null => {
    let v = power();
    while (v !== null) {
      if (eat('*')) {
        const b = power();
        v = b === null ? null : v * b;
      } else if (eat('/')) {
        const b = power();
        v = b === null ? null : v / b;
      } else break;
    }
    return v;
  };
  const power = (): number | null => {
    const sign = eat('-') ? -1 : (eat('+'), 1); // one sign at most: "--1" is a typo
    const base = atom();
    if (base === null || !eat('^')) return base === null ? null : sign * base;
    const exponent = power();
    return exponent === null ? null : sign * Math.pow(base, exponent);
  };
  const atom = (): number | null => {
    space();
    const number = DECIMAL.exec(text.slice(i));
    if (number) {
      i += number[0].length;
      return Number(number[0]);
    }
    if (eat('(')) {
      const v = sum();
      return v !== null && eat(')') ? v : null;
    }
    const name = /^[a-z]+/.exec(text.slice(i));
    if (!name) return null;
    i += name[0].length;
    if (name[0] in CONSTANTS) return CONSTANTS[name[0]];
    const f = FUNCTIONS[name[0]];
    if (!f || !eat('(')) return null;
    const v = sum();
    return v !== null && eat(')') ? f(v) : null;
  };
  const value = sum();
  space();
  return value !== null && i === text.length ? value : null;
}

/** The number `text` holds, or why it holds none: empty, not a number or expression ("-",
 * "1e", "abc"), not finite, or outside the rule's range. Spaces around it are allowed; an
 * arithmetic expression (evaluateExpression) stands for its value. */
export function parseNumber(text: string, rule: NumberRule = {}): { value: number } | { error: string } {
  const name = rule.label ? `${rule.label}: ` : '';
  const t = text.trim();
  if (t === '') return { error: `${name}type a number (the box is empty)` };
  const value = evaluateExpression(t);
  if (value === null || Number.isNaN(value)) return { error: `${name}"${t}" is not a number` };
  if (!Number.isFinite(value)) return { error: `${name}${t} is too large` };
  if (rule.nonZero && value === 0) return { error: `${name}must not be 0` };
  if (rule.min !== undefined && value < rule.min) return { error: `${name}must be at least ${rule.min}` };
  if (rule.max !== undefined && value > rule.max) return { error: `${name}must be at most ${rule.max}` };
  return { value };
}
