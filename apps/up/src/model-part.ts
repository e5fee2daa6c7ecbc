/**
 * Model mode's part of `armtwin up` (docs/protocol.md § Modes): the model copies
 * (./model-copies.ts) of the arms it simulates and of any arm whose announced profile
 * (./announced-profiles.ts) is in its models folders, each copy an in-process device of
 * `{id}-model` on the embedded broker, and their route, `/api/arms/{id}/model`
 * (./model-copy-route.ts).
 */
import fs from 'node:fs';
import type http from 'node:http';
import path from 'node:path';
import type { Broker } from '@armtwin/broker';
import { linkOptions } from '@armtwin/protocol';
import { watchAnnouncedProfiles } from './announced-profiles.ts';
import type { Authorize } from './calibration-route.ts';
import { ModelCopies, type ModelArmSource, type ModelCopiesOptions } from './model-copies.ts';
import { isModelCopyRequest, modelCopyRoute } from './model-copy-route.ts';

export interface ModelPartOptions extends Partial<ModelCopiesOptions> {
  broker: Broker;
  /** The arms `armtwin up` simulates, by id. */
  simulated: ReadonlyMap<string, ModelArmSource>;
  /** Models folders, searched in order, for an announced profile. */
  modelDirs: readonly string[];
  mayDrive: Authorize;
  mayRead: Authorize;
  onFirst(kind: string, message: string): void;
  say(message: string): void;
}

export interface ModelPart {
  copies: ModelCopies;
  /** Whether `req` is for `/api/arms/{id}/model`. */
  handles(req: http.IncomingMessage): boolean;
  handle(req: http.IncomingMessage, res: http.ServerResponse): Promise<void>;
  /** Stops every copy and the announcements' subscriber. */
  stop(): Promise<void>;
}

export function createModelPart(o: ModelPartOptions): ModelPart {
  const { broker, simulated, modelDirs, mayDrive, mayRead, onFirst, say, ...options } = o;
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
  const route = modelCopyRoute({ copies, mayDrive, mayRead, onFirst });
  return {
    copies,
    handles: isModelCopyRequest,
    handle: route.handle,
    async stop() {
      await copies.stopAll();
      await announced.stop();
    },
  };
}
