/** `npm run bench`'s flags as commander reads them: defaults, every flag, and the refusals. */
import path from 'node:path';
import { describe, expect, it } from 'vitest';
import { parseBenchArgs } from '../lib/args.ts';

const SECTIONS = ['rtt', 'ik', 'soak'];
const parse = (...argv: string[]) => parseBenchArgs(argv, SECTIONS, '/hud/dist');

describe('parseBenchArgs', () => {
  it('gives the defaults for no flags', () => {
    expect(parse()).toEqual({
      quick: false,
      only: null,
      keepLogs: false,
      md: true,
      soakMinutes: 30,
      hudDist: '/hud/dist',
      gpu: false,
    });
  });

  it('reads every flag, with values after a space or an =', () => {
    expect(
      parse('--quick', '--only=rtt,soak', '--keep-logs', '--no-md', '--soak-minutes', '5'),
    ).toMatchObject({
      quick: true,
      only: new Set(['rtt', 'soak']),
      keepLogs: true,
      md: false,
      soakMinutes: 5,
    });
    expect(parse('--hud-dist', 'old/dist', '--gpu')).toMatchObject({
      hudDist: path.resolve('old/dist'),
      gpu: true,
    });
  });

  it('refuses an unknown section, a short soak, an unknown flag and a stray word, with the usage', () => {
    expect(() => parse('--only', 'rtt,bogus')).toThrow(
      /unknown section\(s\): bogus\nUsage: npm run bench/,
    );
    expect(() => parse('--soak-minutes', '2')).toThrow(/a whole number ≥ 3/);
    expect(() => parse('--soak-minutes', 'x')).toThrow(/a whole number ≥ 3/);
    expect(() => parse('--bogus')).toThrow(/unknown option '--bogus'/);
    expect(() => parse('--quick', 'extra')).toThrow(/too many arguments/);
  });
});
