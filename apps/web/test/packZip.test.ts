/**
 * The page's zip writer against the server's zip reader (`readZip` of @armtwin/robot/import-node)
 * and Python's zipfile (which checks every CRC): what is packed comes back byte for byte; the
 * reader refuses an archive whose files unpack to more than its bound, and what is not a zip.
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { expect, test } from 'vitest';
import { zipSync } from 'fflate';
import { readZip } from '@armtwin/robot/import-node';
import { packZip } from '../src/ui/panels/Import/packZip.ts';

const entries = [
  { path: 'robot/robot.urdf', data: new TextEncoder().encode('<robot name="r"/>') },
  { path: 'robot/meshes/base ü.stl', data: Uint8Array.from({ length: 3000 }, (_, i) => i % 251) },
  { path: 'empty.txt', data: new Uint8Array(0) },
];

test('packed files read back whole, by our reader and by Python zipfile', () => {
  const zip = packZip(entries);
  const back = readZip(Buffer.from(zip));
  expect([...back.keys()]).toEqual(entries.map((e) => e.path));
  for (const e of entries) expect(Buffer.from(back.get(e.path)!)).toEqual(Buffer.from(e.data));
  const file = path.join(fs.mkdtempSync(path.join(os.tmpdir(), 'packzip-')), 'a.zip');
  fs.writeFileSync(file, zip);
  const tested = execFileSync('python3', [
    '-c',
    'import zipfile,sys; z=zipfile.ZipFile(sys.argv[1]); print(z.testzip(), len(z.namelist()))',
    file,
  ]).toString();
  expect(tested.trim()).toBe('None 3');
});

test('a zip bomb is refused before it is inflated; what is not a zip says so', () => {
  // 8 MB of zeros deflate to a few KB: bound the reader at 1 MB.
  const bomb = zipSync({ 'big.stl': new Uint8Array(8 * 1024 * 1024) }, { level: 9 });
  expect(bomb.length).toBeLessThan(64 * 1024);
  expect(() => readZip(Buffer.from(bomb), 1024 * 1024)).toThrow(
    /unpack to more than 1048576 bytes/,
  );
  expect(readZip(Buffer.from(bomb)).get('big.stl')?.length).toBe(8 * 1024 * 1024);
  expect(() => readZip(Buffer.from('PK\u0003\u0004 but not a zip'))).toThrow(/not a readable zip/);
});
