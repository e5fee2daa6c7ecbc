/**
 * Real third-party robots imported as they come (rtb-data from PyPI, not edited): KUKA's LBR
 * iiwa 14 (`package://` DAE visuals) and ABB's IRB 140 (`package://` STL meshes) go
 * through `armtwin robot import` into a temporary models folder; `armtwin sim --profile NAME
 * --models DIR` runs each over Mosquitto; the numeric IK reaches FK-generated targets of each
 * within 1 mm.
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { chainFk, NumericIkSolver, targetFromTransform, type Chain } from '@armtwin/ik';
import { chainFromUrdf, parseProfile } from '@armtwin/robot';
import { RTB_ROBOTS, rtbDataDir } from '../helpers/rtb-data.ts';
import { useMosquitto } from '../helpers/use-services.ts';
import { armtwin, StatusWatcher } from './sim-helpers.ts';

const broker = useMosquitto();
let models = '';
const ROBOTS = [
  { name: 'iiwa14', source: RTB_ROBOTS.iiwa14, servos: 7, mesh: /\.dae$/ },
  { name: 'irb140', source: RTB_ROBOTS.irb140, servos: 6, mesh: /\.stl$/ },
] as const;

beforeAll(() => {
  models = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-import-'));
});
afterAll(() => {
  if (models) fs.rmSync(models, { recursive: true, force: true });
});

async function run(args: string[]) {
  const child = armtwin(args);
  const code = await new Promise<number | null>((resolve) => child.proc.once('exit', resolve));
  return { code, output: child.output() };
}

function loadChain(name: string): Chain {
  const dir = path.join(models, name);
  const parsed = parseProfile(JSON.parse(fs.readFileSync(path.join(dir, 'profile.json'), 'utf8')));
  if (!parsed.ok) throw new Error(parsed.errors.join('; '));
  const built = chainFromUrdf(
    parsed.profile,
    fs.readFileSync(path.join(dir, `${name}.urdf`), 'utf8'),
  );
  if (!built.ok) throw new Error(built.errors.join('; '));
  return built.chain;
}

describe('armtwin robot import: third-party robots from rtb-data', () => {
  test.each(ROBOTS)('imports $name as it comes', async ({ name, source, servos, mesh }) => {
    const from = path.join(rtbDataDir(), source);
    const r = await run(['robot', 'import', from, '--name', name, '--models', models]);
    expect(r.code, r.output).toBe(0);
    const dir = path.join(models, name);
    const urdf = fs.readFileSync(path.join(dir, `${name}.urdf`), 'utf8');
    expect(urdf).not.toContain('package://');
    const meshes = [...urdf.matchAll(/filename="([^"]+)"/g)].map((m) => m[1]!);
    expect(meshes.some((m) => mesh.test(m))).toBe(true);
    for (const m of meshes) expect(fs.existsSync(path.join(dir, m)), m).toBe(true);
    const profile = JSON.parse(fs.readFileSync(path.join(dir, 'profile.json'), 'utf8'));
    expect(profile.servos).toHaveLength(servos);
    expect(profile.ik).toMatchObject({ kind: 'numeric', tipLink: 'tool0' });
    expect(r.output).toContain('tool centre: link "tool0"');
  });

  test('imports the same robot from a .zip of its package (deflated)', async () => {
    const pkg = path.dirname(path.dirname(path.join(rtbDataDir(), RTB_ROBOTS.iiwa14)));
    const zip = path.join(models, 'iiwa.zip');
    execFileSync('python3', [
      '-c',
      'import shutil, sys; shutil.make_archive(sys.argv[1][:-4], "zip", sys.argv[2])',
      zip,
      pkg,
    ]);
    const r = await run(['robot', 'import', zip, '--name', 'iiwa14zip', '--models', models]);
    expect(r.code, r.output).toBe(0);
    const a = fs.readFileSync(path.join(models, 'iiwa14', 'profile.json'), 'utf8');
    const b = fs.readFileSync(path.join(models, 'iiwa14zip', 'profile.json'), 'utf8');
    expect(b.replace(/iiwa14zip/g, 'iiwa14')).toBe(a);
    expect(fs.readdirSync(path.join(models, 'iiwa14zip', 'meshes', 'visual')).sort()).toEqual(
      fs.readdirSync(path.join(models, 'iiwa14', 'meshes', 'visual')).sort(),
    );
  });

  test('refuses a folder holding two URDFs, naming them', async () => {
    const from = path.join(rtbDataDir(), 'xacro/abb_irb140_description');
    const r = await run(['robot', 'import', from, '--models', models]);
    expect(r.code).not.toBe(0);
    expect(r.output).toMatch(
      /2 \.urdf files in .*: give the one to import .*irb140\.urdf.*irb140QT\.urdf/,
    );
  });

  test('refuses to overwrite an imported robot without --force', async () => {
    const from = path.join(rtbDataDir(), RTB_ROBOTS.iiwa14);
    const r = await run(['robot', 'import', from, '--name', 'iiwa14', '--models', models]);
    expect(r.code).not.toBe(0);
    expect(r.output).toMatch(/exists: give another --name, or --force/);
  });

  test.each(ROBOTS)('armtwin sim runs $name from the models folder', async ({ name, servos }) => {
    const arm = `imp-${name}`;
    const w = await StatusWatcher.connect(broker().url, arm);
    await w.client.subscribeAsync(`arm/${arm}/profile`, { qos: 1 });
    const sim = armtwin([
      'sim',
      '--mqtt',
      broker().url,
      '--arm',
      arm,
      '--profile',
      name,
      '--models',
      models,
    ]);
    try {
      await w.until(
        () => (w.retained.get(`arm/${arm}/online`) === '1' ? true : undefined),
        20_000,
        'online 1',
      );
      // Every servo reports, each as its profile says (angle frames beyond 270° of travel).
      const reported = (id: number) =>
        w.items.filter(
          (it) =>
            'group' in it &&
            it.group.frames.some(
              (f) => (f.type === 'position' || f.type === 'angle') && f.id === id,
            ),
        ).length;
      await w.until(
        () =>
          Array.from({ length: servos }, (_, id) => reported(id)).every((n) => n >= 3)
            ? true
            : undefined,
        10_000,
        `all ${servos} servos`,
      );
      const announced = await w.until(() => w.retained.get(`arm/${arm}/profile`), 5000, 'profile');
      expect(JSON.parse(announced).name).toBe(name);
    } finally {
      await sim.stop('SIGKILL');
      await w.close();
    }
  });

  test.each(ROBOTS)('numeric IK reaches FK-generated targets of $name within 1 mm', ({ name }) => {
    const chain = loadChain(name);
    const solver = new NumericIkSolver(chain);
    let seed = 12345;
    const next = () => (seed = (seed * 1103515245 + 12345) % 2147483648) / 2147483648;
    const random = () =>
      Float64Array.from(chain.lower, (lo, i) => lo + (chain.upper[i]! - lo) * (0.1 + 0.8 * next()));
    let reached = 0;
    const N = 40;
    for (let k = 0; k < N; k++) {
      const target = chainFk(chain, random());
      const r = solver.solve(targetFromTransform(target, 'position'), random());
      if (r.code !== 0) continue;
      const got = chainFk(chain, r.joints);
      const mm = Math.hypot(got[12]! - target[12]!, got[13]! - target[13]!, got[14]! - target[14]!);
      if (mm < 1) reached++;
    }
    expect(reached).toBe(N);
  });
});
