import { spawn, spawnSync } from 'node:child_process';
import { once } from 'node:events';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';

const BIN = fileURLToPath(new URL('../../apps/cli/bin/armtwin.mjs', import.meta.url));
const armtwin = (args: string[], input?: string) =>
  spawnSync(process.execPath, [BIN, ...args], { input, encoding: 'utf8' });
const lines = (text: string) =>
  text
    .trim()
    .split('\n')
    .map((l) => JSON.parse(l));

describe('armtwin decode', () => {
  it('prints one JSON object per frame, errors included', () => {
    const run = armtwin(
      ['decode'],
      '$TIM:1700000000000!{#000P1500!#001P1612!}#001T045V7400!xx#000P2600!',
    );
    expect(run.status).toBe(0);
    expect(lines(run.stdout)).toEqual([
      { type: 'time', ms: 1700000000000 },
      { type: 'position', id: 0, pwm: 1500, time: 1700000000000, group: 1 },
      { type: 'position', id: 1, pwm: 1612, time: 1700000000000, group: 1 },
      { type: 'health', id: 1, temp: 45, mv: 7400, time: 1700000000000 },
      { type: 'error', kind: 'junk', reason: expect.any(String), text: 'xx' },
      {
        type: 'error',
        kind: 'out-of-range',
        reason: 'pwm 2600 outside 500–2500',
        text: '#000P2600!',
      },
    ]);
  });

  it('streams: a frame is printed as soon as its "!" arrives, before end of input', async () => {
    const child = spawn(process.execPath, [BIN, 'decode']);
    child.stdin.write('#000P15');
    child.stdin.write('00!#001P');
    const [chunk] = (await once(child.stdout, 'data')) as [Buffer];
    expect(JSON.parse(chunk.toString().trim())).toEqual({ type: 'position', id: 0, pwm: 1500 });
    expect(child.exitCode).toBeNull(); // still running: stdin is open
    child.stdin.end('1612!');
    const [code] = await once(child, 'exit');
    expect(code).toBe(0);
  });
});

describe('armtwin ik', () => {
  it('solves the home pose', () => {
    const run = armtwin(['ik', '0', '0', '453', '90']);
    expect(run.status).toBe(0);
    expect(JSON.parse(run.stdout)).toMatchObject({
      code: 0,
      alpha: 90,
      pwm: [1500, 1500, 1500, 1500],
    });
  });

  it('searches the pitch when it is omitted and accepts negative numbers', () => {
    const out = JSON.parse(armtwin(['ik', '0', '-150', '60']).stdout);
    expect(out.code).toBe(0);
    expect(out.pwm).toHaveLength(4);
    expect(out.alpha).toBeGreaterThanOrEqual(-90);
  });

  it('exits 0 with the status code for an unreachable target', () => {
    const run = armtwin(['ik', '1000', '0', '100']);
    expect(run.status).toBe(0);
    const out = JSON.parse(run.stdout);
    expect(out).toMatchObject({ code: 2, alpha: -90 });
    expect(out.pwm).toBeUndefined();
  });

  it('rejects a non-numeric argument with a one-line reason and a non-zero exit', () => {
    const run = armtwin(['ik', '1', 'north', '3']);
    expect(run.status).not.toBe(0);
    expect(run.stderr.split('\n')[0]).toMatch(/y must be a number/);
  });
});

describe('armtwin --help', () => {
  it('lists the commands, and each command has --help', () => {
    const help = armtwin(['--help']).stdout;
    expect(help).toMatch(/decode/);
    expect(help).toMatch(/ik <x> <y> <z>/);
    expect(armtwin(['decode', '--help']).stdout).toMatch(/mosquitto_sub/);
    expect(armtwin(['ik', '--help']).stdout).toMatch(/alpha/);
  });
});
