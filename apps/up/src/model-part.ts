/**
 * Model mode's part of `armtwin up` (docs/protocol.md § Modes): the model copies
 * (./model-copies.ts) of the arms it simulates and of any arm whose announced profile
 * (./announced-profiles.ts) is in its models folders, each copy an in-process device of
 * `{id}-model` on the embedded broker: the host the HTTP API's `/api/arms/{id}/model` route
 * (`@armtwin/http-api`) runs them on.
 */
import fs from 'node:fs';
import path from 'node:path';
import type { Broker } from '@armtwin/broker';
import { linkOptions } from '@armtwin/protocol';
import { watchAnnouncedProfiles } from './announced-profiles.ts';
import { ModelCopies, type ModelArmSource, type ModelCopiesOptions } from './model-copies.ts';

export interface ModelPartOptions extends Partial<ModelCopiesOptions> {
  broker: Broker;
  /** The arms `armtwin up` simulates, by id. */
  simulated: ReadonlyMap<string, ModelArmSource>;
  /** Models folders, searched in order, for an announced profile. */
  modelDirs: readonly string[];
  onFirst(kind: string, message: string): void;
  say(message: string): void;
}

export interface ModelPart {
  copies: ModelCopies;
  /** Stops every copy and the announcements' subscriber. */
  stop(): Promise<void>;
}

export function createModelPart(o: ModelPartOptions): ModelPart {
  const { broker, simulated, modelDirs, onFirst, say, ...options } = o;
  const announced = watchAnnouncedProfiles(
    broker.connectInProcess(
      { name: 'model-copies', role: 'viewer' },
      { clientId: 'armtwin-model-copies', ...linkOptions() },
    ),
    onFirst,
  );
  const announcedSource = (id: string): ModelArmSource | undefined => {
    const name = announced.nameOf(id);
    const dir = name && modelDirs.find((d) => fs.existsSync(path.join(d, name, 'profile.json')));
    return dir ? { profile: name, modelsDir: dir } : undefined;
  };
  const copies = new ModelCopies(
    {
      source: (id) => simulated.get(id) ?? announcedSource(id),
      connect: (copyId, opts) =>
        broker.connectInProcess({ name: `sim-${copyId}`, role: 'device', arm: copyId }, opts),
      onFirst,
      say,
    },
    options,
  );
  return {
    copies,
    async stop() {
      await copies.stopAll();
      await announced.stop();
    },
  };
}
