import fs from 'node:fs';
import path from 'node:path';
import { describe, expect, test } from 'vitest';
import { MODELS_DIR } from '@armtwin/motion/robot-folder';
import { fetchRobotAsset, urdfWithPackagePaths } from '../src/robot-assets.ts';

describe('urdfWithPackagePaths', () => {
  test('relative mesh paths go under package://<profile>/; others stay', () => {
    const urdf =
      '<mesh filename="meshes/a.stl"/><mesh filename="./b.stl"/>' +
      '<mesh filename="package://other/c.stl"/><mesh filename="/abs/d.stl"/>';
    expect(urdfWithPackagePaths(urdf, 'so101')).toBe(
      '<mesh filename="package://so101/meshes/a.stl"/><mesh filename="package://so101/b.stl"/>' +
        '<mesh filename="package://other/c.stl"/><mesh filename="/abs/d.stl"/>',
    );
  });
});

describe('fetchRobotAsset', () => {
  test("serves a robot folder's file, from the first folder that has it", async () => {
    const r = await fetchRobotAsset('package://armtwin5/meshes/base.stl', [
      '/nonexistent',
      MODELS_DIR,
    ]);
    expect(
      r.ok &&
        Buffer.from(r.data).equals(
          fs.readFileSync(path.join(MODELS_DIR, 'armtwin5/meshes/base.stl')),
        ),
    ).toBe(true);
  });

  test('never leaves the robot folder, and says why', async () => {
    for (const [uri, why] of [
      ['package://armtwin5/../../../etc/passwd', /outside the robot's folder/],
      ['package://armtwin5/%2e%2e/so101/profile.json', /outside the robot's folder/],
      ['file:///etc/passwd', /not an armtwin robot asset/],
      ['package://armtwin5/meshes/none.stl', /no such robot file/],
    ] as const) {
      const r = await fetchRobotAsset(uri, [MODELS_DIR]);
      expect(!r.ok && r.error).toMatch(why);
    }
  });
});
