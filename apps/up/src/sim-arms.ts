/**
 * The simulated arms of `armtwin up`: which arms and profiles (`--arms`, or one arm with the
 * default profile), checked before anything starts, and each arm started on the embedded broker
 * in-process with the device role, following the keep-out zones edited in the HUD.
 */
import fs from 'node:fs';
import path from 'node:path';
import type { Broker } from '@armtwin/broker';
import { isModelArmId, linkOptions, MODEL_ARM_SUFFIX } from '@armtwin/protocol';
import {
  DEFAULT_PROFILE,
  followZones,
  loadSimProfile,
  simWill,
  startMqttSim,
  type MqttSim,
} from '@armtwin/sim';
import type { UpOptions } from './up-options.ts';

export interface ArmSpec {
  id: string;
  profile: string;
}

/** The arms to simulate, refused with why when an id is the SO-101's or a model copy's. */
export function armSpecsOf(o: Pick<UpOptions, 'arms' | 'armId' | 'so101'>): ArmSpec[] {
  const armSpecs = o.arms?.length ? o.arms : [{ id: o.armId, profile: DEFAULT_PROFILE }];
  if (o.so101 && armSpecs.some((a) => a.id === o.so101))
    throw new Error(
      `arm id "${o.so101}" is the SO-101 on the emulated bus: give the simulated arm another id, or leave the SO-101 out (--no-so101)`,
    );
  for (const a of armSpecs)
    if (isModelArmId(a.id))
      throw new Error(
        `arm id "${a.id}": ids ending in ${MODEL_ARM_SUFFIX} are reserved for model copies (docs/protocol.md § Modes)`,
      );
  return armSpecs;
}

/** Each arm's profile, loaded (a bad profile fails here, before anything starts). */
export function loadArmProfiles(
  armSpecs: readonly ArmSpec[],
  modelDirs: readonly string[],
): ReturnType<typeof loadSimProfile>[] {
  return armSpecs.map((a) => loadSimProfile(a.profile, profileDir(modelDirs, a.profile)));
}

/** Starts every arm on `broker`, in `armSpecs` order; each one's stop() also stops its zones. */
export function startSimArms(
  broker: Broker,
  armSpecs: readonly ArmSpec[],
  profiles: readonly ReturnType<typeof loadSimProfile>[],
  o: Pick<UpOptions, 'rate' | 'onFirst'> & { modelDirs: readonly string[] },
): MqttSim[] {
  return armSpecs.map(({ id }, k) => {
    const client = broker.connectInProcess(
      { name: `sim-${id}`, role: 'device', arm: id },
      {
        clientId: `armtwin-sim-${id}`,
        will: simWill(id),
        ...linkOptions(),
        queueQoSZero: false,
      },
    );
    const profile = profiles[k]!;
    const started = startMqttSim(client, {
      armId: id,
      rate: o.rate,
      onFirst: o.onFirst,
      model: profile.model,
      profile,
    });
    // Zones edited in the HUD (PUT …/keep-out) reach this sim through the profile file.
    const name = armSpecs[k]!.profile;
    const zones = followZones({
      client,
      armId: id,
      name,
      modelsDir: profileDir(o.modelDirs, name),
      sim: profile,
      runner: started.runner,
      onFirst: o.onFirst,
    });
    const stop = () => {
      zones.stop();
      return started.stop();
    };
    return { ...started, stop };
  });
}

/** The first of `dirs` that holds `<name>/profile.json` (the last one otherwise, for its error). */
export function profileDir(dirs: readonly string[], name: string): string {
  return dirs.find((d) => fs.existsSync(path.join(d, name, 'profile.json'))) ?? dirs.at(-1)!;
}
