import fs from 'node:fs';
import path from 'node:path';
import { describe, expect, test } from 'vitest';
import { profileAnnouncement } from '@armtwin/robot';
import { MODELS_DIR } from '@armtwin/motion/robot-folder';
import { Ingest } from '../src/ingest.ts';
import { Metrics } from '../src/metrics.ts';

const T = 1_700_000_000_000;
const raw = (name: string): unknown =>
  JSON.parse(fs.readFileSync(path.join(MODELS_DIR, name, 'profile.json'), 'utf8'));
const announce = (name: string) => {
  const r = raw(name) as { name: string; title: string };
  return profileAnnouncement(r.name, r.title, r);
};

describe('the profile an arm announces (retained arm/{id}/profile)', () => {
  test('is stored once as a profile point at its arrival, and again when it changes', () => {
    const metrics = new Metrics();
    const ingest = new Ingest(metrics);
    expect(ingest.handle('arm/arm1/profile', announce('so101'), T)).toEqual([
      `profile,arm=arm1 name="so101",title="SO-101 arm (follower; LeRobot ids 1-6)" ${T * 1000}`,
    ]);
    // the same announcement again (a reconnect's retained copy): nothing new
    expect(ingest.handle('arm/arm1/profile', announce('so101'), T + 5)).toEqual([]);
    // another arm, then a change of robot
    expect(ingest.handle('arm/arm2/profile', announce('armtwin5'), T + 6)).toHaveLength(1);
    const [line] = ingest.handle('arm/arm1/profile', Buffer.from(announce('armtwin5')), T + 9);
    expect(line).toMatch(/^profile,arm=arm1 name="armtwin5",title=".+" \d+$/);
    expect(line!.endsWith(` ${(T + 9) * 1000}`)).toBe(true);
    expect(metrics.messages['profile']).toBe(4);
  });

  test('a bad announcement is refused, counted, and stores nothing; a cleared one is ignored', () => {
    const metrics = new Metrics();
    const ingest = new Ingest(metrics);
    for (const bad of ['not json', '{"name":"x"}', '{"profile":{"name":"x"}}'])
      expect(ingest.handle('arm/arm1/profile', bad, T)).toEqual([]);
    expect(ingest.handle('arm/arm1/profile', '', T)).toEqual([]);
    expect(metrics.rejected['bad-profile']).toBe(3);
  });
});
