/**
 * A simulated arm of any bundled robot (`armtwin sim --profile <name>`), online and streaming
 * all its servos, with an observer on its topics; and the bundled profiles, parsed.
 */
import fs from 'node:fs';
import path from 'node:path';
import { parseProfile, type Profile } from '@armtwin/robot';
import { REPO_ROOT } from '../../helpers/services.ts';
import { ArmObserver, startSim, until, type SimProcess } from './sim.ts';

/** `public/models/<name>/profile.json`, parsed (throws if it does not parse). */
export function loadProfile(name: string): Profile {
  const file = path.join(REPO_ROOT, 'public/models', name, 'profile.json');
  const r = parseProfile(JSON.parse(fs.readFileSync(file, 'utf8')));
  if (!r.ok) throw new Error(r.errors.join('; '));
  return r.profile;
}

export interface ProfiledArm {
  id: string;
  sim: SimProcess;
  observer: ArmObserver;
  stop(): Promise<void>;
}

/** Starts a sim on `id` as `profile`; resolves once it is online with every servo reported. */
export async function startProfiledArm(
  mqttUrl: string,
  id: string,
  profile: Profile,
  logFile: string,
): Promise<ProfiledArm> {
  const observer = await ArmObserver.connect(mqttUrl, id);
  const sim = startSim(mqttUrl, id, logFile, ['--profile', profile.name]);
  const stop = async () => {
    await sim.stop();
    await observer.close();
  };
  try {
    await until(
      () =>
        observer.online === '1' &&
        // pulse servos report pulses, angle servos (the SO-101's bus) angles
        Math.max(
          observer.pwm.filter(Number.isFinite).length,
          observer.angles.filter(Number.isFinite).length,
        ) === profile.servos.length,
      30_000,
      `sim ${id} (${profile.name}) online and streaming`,
    );
  } catch (err) {
    await stop();
    throw err;
  }
  return { id, sim, observer, stop };
}
