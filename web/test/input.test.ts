// What a number box accepts: numbers, and nothing that would move a vertex to 0 or record
// an undo step by accident (an empty box, a lone "-").
import { describe, expect, it } from 'vitest';
import { parseNumber } from '../src/input';

describe('parseNumber', () => {
  it('reads decimal numbers, signed, with exponents and spaces', () => {
    for (const [text, value] of [['0', 0], ['-1.5', -1.5], ['+2', 2], ['.5', 0.5], ['3.', 3], [' 1e-3 ', 0.001], ['-2E2', -200]] as const)
      expect(parseNumber(text)).toEqual({ value });
  });

  it('refuses an empty box, a lone sign, and what Number() would take but is no number', () => {
    for (const text of ['', '   ', '-', '+', '.', '1e', '0x10', 'Infinity', 'abc', '1,5', '--1'])
      expect(parseNumber(text, { label: 'x' })).toHaveProperty('error', expect.stringMatching(/^x: /));
    expect(parseNumber('')).toEqual({ error: 'type a number (the box is empty)' });
    expect(parseNumber('1e400')).toEqual({ error: '1e400 is too large' });
  });

  it('reads arithmetic expressions, parsed (never evaluated as code)', () => {
    for (const [text, value] of [
      ['1/3', 1 / 3],
      ['2*pi', 2 * Math.PI],
      [' -(0.5 + 1e-3) * 2 ', -1.002],
      ['2^-1', 0.5],
      ['-2^2', -4],
      ['2^3^2', 512],
      ['sqrt(2)/2', Math.SQRT1_2],
      ['cos(pi)', -1],
      ['1 - 2 - 3', -4],
      ['8/4/2', 1],
    ] as const)
      expect(parseNumber(text)).toEqual({ value });
    for (const text of ['1/', '2pi', '(1', '1)', 'alert(1)', 'pi()', 'sqrt 2', '1 2', 'Math.PI', '0/0'])
      expect(parseNumber(text)).toHaveProperty('error');
    expect(parseNumber('1/0')).toEqual({ error: '1/0 is too large' });
  });

  it('applies the rule: range and non-zero', () => {
    expect(parseNumber('1.5', { min: 0, max: 1 })).toEqual({ error: 'must be at most 1' });
    expect(parseNumber('-0.1', { min: 0, max: 1 })).toEqual({ error: 'must be at least 0' });
    expect(parseNumber('0', { nonZero: true })).toEqual({ error: 'must not be 0' });
    expect(parseNumber('1', { min: 0, max: 1 })).toEqual({ value: 1 });
  });
});
