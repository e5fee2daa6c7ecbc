/**
 * The simulator follows its profile file for keep-out zones (docs/protocol.md, "Keep-out
 * zones"): when `<models>/<name>/profile.json` changes (the HUD's Zones section writes it
 * through `armtwin up`, or someone edits it), it is read again and, if it parses and drives the
 * same servos, its zones and link size are put in force at once (the frame check, `$KMS` and
 * motion requests) and the profile is announced again, retained, for the pages. A file that
 * does not parse leaves the arm stopped: every servo stops where it is and every move is
 * refused (`$ERR:zone: profile.json invalid!`) until a good file is written.
 */
import type { Stats } from 'node:fs';
import path from 'node:path';
import type { MqttClient } from 'mqtt';
import { refuseEveryMove } from '@armtwin/controller';
import { readRobotFolder } from '@armtwin/motion/robot-folder';
import { EMERGENCY_STOP, topic } from '@armtwin/protocol';
import { simProfile, type SimProfile } from './profile.ts';
import { followFile } from './shared-file-watch.ts';
import type { SimRunner } from './runner.ts';

/** How often the profile file is looked at, ms (a stat; renames are seen too). */
export const ZONES_POLL_MS = 500;

/** What the sim answers every move with while its profile file does not parse. */
export { INVALID_PROFILE_REASON } from '@armtwin/controller';

export interface ZonesFollowOptions {
  client: MqttClient;
  armId: string;
  /** Profile name (its folder) and the models folder. */
  name: string;
  modelsDir: string;
  /** The sim's profile, updated in place (the motion service reads it per request). */
  sim: SimProfile;
  runner: SimRunner;
  onFirst(kind: string, message: string): void;
  /** Told each time new zones are put in force, or the file is refused. */
  onReload?(ok: boolean, message: string): void;
  pollMs?: number;
}

export function followZones(o: ZonesFollowOptions): { stop(): void } {
  const file = path.join(o.modelsDir, o.name, 'profile.json');
  const ids = (s: SimProfile) => s.profile.servos.map((x) => `${x.key}:${x.joint}`).join(',');
  const reload = () => {
    let next: SimProfile;
    try {
      const { profile, raw, urdf } = readRobotFolder(o.name, o.modelsDir);
      next = simProfile(profile, raw, urdf);
    } catch (err) {
      const message = `${file} not taken, the arm is stopped: ${(err as Error).message}`;
      o.runner.receive(EMERGENCY_STOP);
      o.runner.model.setKeepOut(refuseEveryMove);
      o.onFirst('profile:invalid', message);
      return o.onReload?.(false, message);
    }
    if (ids(next) !== ids(o.sim)) {
      const message = `${file}: its servos changed; restart the sim to take it`;
      o.onFirst('profile:servos', message);
      return o.onReload?.(false, message);
    }
    o.sim.profile = next.profile;
    o.sim.robot = next.robot;
    o.sim.announcement = next.announcement;
    o.runner.model.setKeepOut(next.model.keepOut);
    if (o.client.connected)
      o.client.publish(topic(o.armId, 'profile'), next.announcement, { qos: 1, retain: true });
    o.onReload?.(true, `${next.profile.keepOut?.zones.length ?? 0} zone(s) in force`);
  };
  const onChange = (now: Stats, before: Stats) => {
    if (now.mtimeMs !== before.mtimeMs || now.ino !== before.ino) reload();
  };
  // One watcher per file however many arms of one profile follow it (shared-file-watch.ts).
  return { stop: followFile(file, o.pollMs ?? ZONES_POLL_MS, onChange) };
}
