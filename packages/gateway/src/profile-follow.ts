/**
 * A gateway's robot profile on MQTT and on disk (the servo bus's, the LSC board's, `gateway --ros2`'s). At every connect the profile is
 * announced, retained, on `arm/{id}/profile` as `{"name","title","profile"}` (what the
 * simulator announces: the HUD draws and drives the arm by it). The profile file is watched:
 * when it changes (the HUD's calibration wizard writes it through `armtwin up`, or someone
 * edits it) it is read again and, if it parses and drives the same servos, put in force at once
 * (`reconfigure`; on a bus: new polarity, offset and limits, the arm holding where it is)
 * and announced again. A file that does not parse is reported and leaves the arm stopped (an
 * emergency stop, then every move and `$KMS` refused) until a good file is written.
 */
import fs from 'node:fs';
import path from 'node:path';
import type { MqttClient } from 'mqtt';
import { readRobotFolder } from '@armtwin/motion/robot-folder';
import { EMERGENCY_STOP, topic } from '@armtwin/protocol';
import { parseProfile, profileAnnouncement } from '@armtwin/robot';
import { numericKms, refuseEveryMove, zonesKeepOut } from '@armtwin/controller';
import type { KeepOutCheck, KmsSolver } from '@armtwin/controller';
import type { MotionRobot } from '@armtwin/motion';
import type { Profile } from '@armtwin/robot';

/** What following the profile needs of a gateway's core (the bus's, the LSC board's). */
export interface ProfileCore {
  /** Puts a new profile of the same servos in force; '' or why not (nothing changed). */
  reconfigure(
    profile: Profile,
    kms?: KmsSolver,
    keepOut?: KeepOutCheck,
    robot?: MotionRobot,
  ): string;
  fromControl(payload: string): void;
}

/** How often the profile file is looked at, ms (a stat; renames are seen too). */
export const PROFILE_POLL_MS = 500;

export interface ProfileFollowOptions {
  client: MqttClient;
  armId: string;
  /** Profile name (its folder) and the models folder. */
  name: string;
  modelsDir: string;
  /** profile.json as read at start. */
  raw: unknown;
  core: ProfileCore;
  onFirst(kind: string, message: string): void;
  /** Told each time a new profile is put in force. */
  onReload?(name: string): void;
  pollMs?: number;
}

export function followProfile(o: ProfileFollowOptions): { stop(): void } {
  const file = path.join(o.modelsDir, o.name, 'profile.json');
  const t = topic(o.armId, 'profile');
  let announcement = '';
  const announce = (raw: unknown) => {
    const p = raw as { name?: unknown; title?: unknown };
    announcement = profileAnnouncement(p.name, p.title ?? p.name, raw);
    if (o.client.connected) o.client.publish(t, announcement, { qos: 1, retain: true });
  };
  const onConnect = () => o.client.publish(t, announcement, { qos: 1, retain: true });
  o.client.on('connect', onConnect);
  announce(o.raw);
  const reload = () => {
    try {
      const { profile, raw, robot } = readRobotFolder(o.name, o.modelsDir);
      const error = o.core.reconfigure(profile, numericKms(robot), zonesKeepOut(robot), robot);
      if (error) return o.onFirst('profile:reload', error);
      announce(raw);
      o.onReload?.(profile.name);
    } catch (err) {
      o.onFirst('profile:reload', `${file} not taken: ${(err as Error).message}`);
      stopUntilFixed();
    }
  };
  // A file that does not parse (a zone file with nonsense in it) leaves the arm stopped: every
  // servo stops where it is, and every move is refused until a good file is written.
  const started = parseProfile(o.raw);
  const stopUntilFixed = () => {
    o.core.fromControl(EMERGENCY_STOP);
    if (started.ok) o.core.reconfigure(started.profile, undefined, refuseEveryMove);
  };
  const onChange = (now: fs.Stats, before: fs.Stats) => {
    if (now.mtimeMs !== before.mtimeMs || now.ino !== before.ino) reload();
  };
  fs.watchFile(file, { interval: o.pollMs ?? PROFILE_POLL_MS, persistent: false }, onChange);
  return {
    stop() {
      fs.unwatchFile(file, onChange);
      o.client.removeListener('connect', onConnect);
    },
  };
}
