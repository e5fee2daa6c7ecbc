/**
 * `armtwin robot import`'s pure core on a small URDF written for the rules: the chain to the
 * tool centre, servos in order, limits and units, continuous and mimic joints, mesh paths
 * (package://, relative) resolved and rewritten, and the refusals.
 */
import { describe, expect, test } from 'vitest';
import {
  deriveProfile,
  meshTriangles,
  parseProfile,
  planImport,
  resolveMeshPath,
  type ImportSource,
} from '../src/index.ts';

const joint = (name: string, type: string, parent: string, child: string, extra = '') =>
  `<joint name="${name}" type="${type}"><parent link="${parent}"/><child link="${child}"/>` +
  `<origin xyz="0 0 0.1" rpy="0 0 0"/><axis xyz="0 0 1"/>${extra}</joint>`;
const link = (name: string, mesh?: string) =>
  mesh
    ? `<link name="${name}"><visual><geometry><mesh filename="${mesh}"/></geometry></visual></link>`
    : `<link name="${name}"/>`;

const ARM = `<?xml version="1.0"?>
<robot name="Test Arm 1">
  ${link('base', 'package://test_description/meshes/base.stl')}
  ${link('l1', '../meshes/l1.dae')}
  ${link('l2', 'package://test_description/meshes/l2.obj')}
  ${link('l3')}
  ${link('flange')}
  ${link('finger_a')}
  ${link('finger_b')}
  ${joint('j1', 'revolute', 'base', 'l1', '<limit lower="-2.9671" upper="2.9671" velocity="1.5" effort="1"/>')}
  ${joint('j2', 'prismatic', 'l1', 'l2', '<limit lower="0" upper="0.5" velocity="0.2" effort="1"/>')}
  ${joint('j3', 'continuous', 'l2', 'l3')}
  ${joint('to_flange', 'fixed', 'l3', 'flange')}
  ${joint('finger_a_joint', 'prismatic', 'flange', 'finger_a', '<limit lower="0" upper="0.04" velocity="0.1" effort="1"/>')}
  ${joint('finger_b_joint', 'prismatic', 'flange', 'finger_b', '<limit lower="0" upper="0.04" velocity="0.1" effort="1"/><mimic joint="finger_a_joint"/>')}
</robot>`;

const STL = new TextEncoder().encode(
  'solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid a\n',
);
const DAE = new TextEncoder().encode(
  '<COLLADA><library_geometries><triangles count="12"/></library_geometries></COLLADA>',
);
const OBJ = new TextEncoder().encode('v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3 4\n');

function source(urdf: string, files: Record<string, Uint8Array>): ImportSource {
  const map = new Map(Object.entries(files));
  return {
    urdfPath: 'src/test_description/urdf/arm.urdf',
    urdfText: urdf,
    has: (p) => map.has(p),
    read: (p) => map.get(p)!,
  };
}

const TREE = {
  'src/test_description/meshes/base.stl': STL,
  'src/test_description/meshes/l1.dae': DAE,
  'src/test_description/meshes/l2.obj': OBJ,
};

describe('deriveProfile', () => {
  const r = deriveProfile(ARM, 'arm', 'arm.urdf');
  if (!r.ok) throw new Error(r.errors.join('; '));
  const json = r.derived.json as {
    ik: unknown;
    servos: Record<string, unknown>[];
    poses: unknown;
    $import: { mimic: unknown };
  };

  test('is a valid profile whose chain runs from the root to the link named like a flange', () => {
    expect(parseProfile(json).ok).toBe(true);
    expect(json.ik).toEqual({ kind: 'numeric', baseLink: 'base', tipLink: 'flange' });
    expect(r.derived.notes[0]).toMatch(/tool centre: link "flange"/);
  });

  test('servos: chain joints in order, then the free finger; the mimic finger is no servo', () => {
    expect(json.servos.map((s) => [s.id, s.joint])).toEqual([
      ['000', 'j1'],
      ['001', 'j2'],
      ['002', 'j3'],
      ['003', 'finger_a_joint'],
    ]);
    expect(json.$import.mimic).toEqual([{ joint: 'finger_b_joint', follows: 'finger_a_joint' }]);
  });

  test('limits in degrees and mm, rounded inwards; > 270° and continuous on angle frames', () => {
    const [j1, j2, j3] = json.servos;
    expect(j1).toMatchObject({ type: 'revolute', units: 'angle', min: -170, max: 170 });
    expect(j1!.maxSpeed).toBeCloseTo(85.94, 2);
    expect(j2).toMatchObject({ type: 'prismatic', min: 0, max: 500, maxSpeed: 200 });
    expect(j2!.units).toBeUndefined();
    expect(j3).toMatchObject({
      type: 'revolute',
      units: 'angle',
      min: -180,
      max: 180,
      maxSpeed: 90,
    });
    expect(json.poses).toEqual({
      home: { unit: 'joint', servos: { '000': 0, '001': 0, '002': 0, '003': 0 } },
    });
  });

  test('a tcp link is added at the deepest link when none is named like a tool centre', () => {
    const plain = ARM.replace(/flange/g, 'wrist')
      .replace(/<link name="finger_[ab]"\/>/g, '')
      .replace(/<joint name="finger_[ab]_joint"[\s\S]*?<\/joint>/g, '');
    const d = deriveProfile(plain, 'arm', 'arm.urdf');
    if (!d.ok) throw new Error(d.errors.join('; '));
    expect((d.derived.json.ik as { tipLink: string }).tipLink).toBe('tcp');
    expect(d.derived.urdf).toMatch(
      /<joint name="tcp_joint" type="fixed">\s*<parent link="wrist"\/>\s*<child link="tcp"\/>/,
    );
    expect(d.derived.notes[0]).toMatch(/added at the deepest link "wrist"/);
  });

  test('a joint range wider than ±135° but within 270° is centred by its offset', () => {
    const skew = ARM.replace('lower="-2.9671" upper="2.9671"', 'lower="0" upper="4"');
    const d = deriveProfile(skew, 'arm', 'arm.urdf');
    expect(d.ok && (d.derived.json.servos as Record<string, unknown>[])[0]).toMatchObject({
      offset: 114.59,
    });
  });

  test('refuses a URDF without a movable joint, and a bad name', () => {
    const fixed = `<robot name="r">${link('a')}${link('b')}${joint('f', 'fixed', 'a', 'b')}</robot>`;
    expect(deriveProfile(fixed, 'r', 'r.urdf')).toEqual({
      ok: false,
      errors: [expect.stringMatching(/no movable joint/)],
    });
    expect(deriveProfile(ARM, 'Bad Name', 'x.urdf').ok).toBe(false);
  });
});

describe('planImport', () => {
  test('resolves package:// and relative meshes, rewrites them, copies them and names the robot', () => {
    const r = planImport(source(ARM, TREE));
    if (!r.ok) throw new Error(r.errors.join('; '));
    expect(r.plan.name).toBe('test_arm_1');
    expect(r.plan.files.map((f) => f.path).sort()).toEqual([
      'meshes/base.stl',
      'meshes/l1.dae',
      'meshes/l2.obj',
      'profile.json',
      'test_arm_1.urdf',
    ]);
    const urdf = r.plan.files.find((f) => f.path === 'test_arm_1.urdf')!.data as string;
    expect(urdf).toContain('filename="meshes/base.stl"');
    expect(urdf).toContain('filename="meshes/l1.dae"');
    expect(urdf).not.toContain('package://');
    expect(r.plan.warnings).toEqual([]);
  });

  test('refuses a missing visual mesh and an unreadable format, naming each', () => {
    const missing = { ...TREE } as Record<string, Uint8Array>;
    delete missing['src/test_description/meshes/l2.obj'];
    const r = planImport(source(ARM.replace('l1.dae', 'l1.ply'), missing), { name: 'arm' });
    expect(r.ok).toBe(false);
    expect(!r.ok && r.errors).toEqual([
      expect.stringMatching(/l1\.ply .*format not readable/),
      expect.stringMatching(/l2\.obj .*is missing/),
    ]);
  });

  test('warns about meshes too large for a page', () => {
    const r = planImport(source(ARM, TREE), { maxMeshBytes: 50, maxMeshTriangles: 10 });
    if (!r.ok) throw new Error(r.errors.join('; '));
    expect(r.plan.warnings).toContainEqual(
      expect.stringMatching(/meshes\/base\.stl: .* MB, heavy/),
    );
    expect(r.plan.warnings).toContainEqual(
      expect.stringMatching(/meshes\/l1\.dae: 12 triangles, heavy/),
    );
    expect(r.plan.warnings).not.toContainEqual(expect.stringMatching(/l2\.obj: \d+ triangles/));
  });
});

describe('meshes', () => {
  test('package:// is found in a folder of that name, or the nearest ancestor holding the path', () => {
    const has = (p: string) => ['a/my_pkg/meshes/x.stl', 'b/meshes/y.stl'].includes(p);
    expect(resolveMeshPath('package://my_pkg/meshes/x.stl', 'a/my_pkg/urdf/r.urdf', has)).toBe(
      'a/my_pkg/meshes/x.stl',
    );
    expect(resolveMeshPath('package://other_name/meshes/y.stl', 'b/urdf/r.urdf', has)).toBe(
      'b/meshes/y.stl',
    );
    expect(resolveMeshPath('package://p/meshes/z.stl', 'b/urdf/r.urdf', has)).toBeNull();
  });

  test('triangles of ASCII and binary STL, OBJ and DAE', () => {
    const bin = new Uint8Array(84 + 50 * 7);
    new DataView(bin.buffer).setUint32(80, 7, true);
    expect(meshTriangles('stl', bin)).toBe(7);
    expect(meshTriangles('stl', STL)).toBe(1);
    expect(meshTriangles('obj', OBJ)).toBe(2);
    expect(meshTriangles('dae', DAE)).toBe(12);
    expect(meshTriangles('dae', new TextEncoder().encode('<html>'))).toBeNaN();
  });
});
