import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { describe, expect, test } from 'vitest';
import { meshRefs, parseUrdfJoints } from '@armtwin/robot';
import { MODELS_DIR } from '@armtwin/motion/robot-folder';
import { loadRecordingRobot } from '../src/export/index.ts';
import { meshMediaType, selfContainedUrdf } from '../src/export/robot-description.ts';

/** The bytes of a `data:` URI. */
const bytesOf = (uri: string) => {
  const m = /^data:([^;,]+);base64,(.*)$/.exec(uri);
  if (!m) throw new Error(`not a base64 data URI: ${uri.slice(0, 40)}`);
  return { mediaType: m[1], bytes: Buffer.from(m[2]!, 'base64') };
};

describe('the robot description in an export: the URDF with its meshes inline', () => {
  test('so101: every mesh is a data: URI of the file in the robot folder; the joints are the same', () => {
    const robot = loadRecordingRobot('so101');
    const shipped = fs.readFileSync(path.join(MODELS_DIR, 'so101', 'so101.urdf'), 'utf8');
    const names = meshRefs(shipped).map((m) => m.filename);
    expect(names.length).toBeGreaterThan(5);
    const d = robot.description!;
    expect(d.missing).toEqual([]);
    expect(d.meshes.map((m) => m.filename)).toEqual(names);
    const inline = meshRefs(d.urdf).map((m) => m.filename);
    expect(inline).toHaveLength(names.length);
    inline.forEach((uri, i) => {
      const { mediaType, bytes } = bytesOf(uri);
      expect(mediaType).toBe('model/stl');
      expect(bytes.equals(fs.readFileSync(path.join(MODELS_DIR, 'so101', names[i]!)))).toBe(true);
    });
    const before = parseUrdfJoints(shipped);
    const after = parseUrdfJoints(d.urdf);
    expect(after.ok && before.ok && after.joints).toEqual(before.ok && before.joints);
  });

  test('package:// names the robot folder; a missing mesh or one outside the folder is listed, not fatal', () => {
    const models = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-desc-'));
    const dir = path.join(models, 'armtwin5');
    fs.cpSync(path.join(MODELS_DIR, 'armtwin5'), dir, { recursive: true });
    const file = path.join(dir, 'armtwin5.urdf');
    const urdf = fs.readFileSync(file, 'utf8');
    fs.writeFileSync(
      file,
      urdf
        .replace('"meshes/base.stl"', '"package://armtwin5_description/meshes/base.stl"')
        .replace('"meshes/turret.stl"', '"meshes/gone.stl"')
        .replace('"meshes/forearm.stl"', '"../../etc/forearm.stl"'),
    );
    try {
      const d = loadRecordingRobot('armtwin5', models).description!;
      const base = d.meshes.find((m) => m.filename.startsWith('package://'));
      expect(base?.bytes).toEqual(fs.readFileSync(path.join(dir, 'meshes', 'base.stl')));
      expect(d.missing).toEqual([
        expect.stringMatching(/^meshes\/gone\.stl: ENOENT/),
        '../../etc/forearm.stl: outside the robot folder',
      ]);
      expect(meshRefs(d.urdf).map((m) => m.filename)).toContain('meshes/gone.stl');
    } finally {
      fs.rmSync(models, { recursive: true, force: true });
    }
  });

  test('media types are the ones the 3D panel loads by; other kinds stay as named', () => {
    expect(['a.STL', 'b.dae', 'c.obj', 'd.ply'].map(meshMediaType)).toEqual([
      'model/stl',
      'model/vnd.collada+xml',
      'model/obj',
      undefined,
    ]);
    const urdf =
      '<robot name="r"><link name="a"><visual><geometry><mesh filename="m.ply"/></geometry></visual></link></robot>';
    const d = selfContainedUrdf(urdf, () => new Uint8Array([1]));
    expect(d.meshes).toEqual([]);
    expect(d.missing).toEqual(['m.ply: not a mesh kind armtwin reads (stl, obj, dae)']);
    expect(d.urdf).toBe(urdf);
  });
});
