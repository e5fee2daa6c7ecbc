/**
 * A simulated arm (`armtwin sim` at `rateHz`) with this process recording its status stream
 * (./stream-recorder.ts: the arm's true trajectory) and, when asked, hearing its control topic
 * (when each scripted move went out). The browser and twin sections measure the HUD against it.
 */
import path from 'node:path';
import type { MqttClient } from 'mqtt';
import { connectMqtt, startSim } from './stack.ts';
import type { Child } from './proc.ts';
import type { BenchContext } from './types.ts';
import { StreamRecorder } from './stream-recorder.ts';

export interface RecordedArm {
  sim: Child;
  /** This process's client: records the status stream, publishes the scripted moves. */
  client: MqttClient;
  rec: StreamRecorder;
  /** Ends the client and the simulator. */
  close(): Promise<void>;
}

export interface RecordedArmOptions {
  /** The arm's id (`arm/{id}/…`). */
  arm: string;
  rateHz: number;
  servos: number;
  /** The simulator's log, in the run's log folder. */
  logName: string;
  clientId: string;
  /** Called for each message on the arm's control topic (none subscribed without it). */
  onControl?: (rec: StreamRecorder) => void;
}

export async function startRecordedArm(
  ctx: BenchContext,
  o: RecordedArmOptions,
): Promise<RecordedArm> {
  const sim = await startSim(ctx.broker.url, o.arm, o.rateHz, path.join(ctx.logDir, o.logName));
  const client = await connectMqtt(ctx.broker.url, o.clientId);
  const rec = new StreamRecorder(o.servos);
  client.on('message', (topic, payload) => {
    if (topic.endsWith('/control')) o.onControl?.(rec);
    else rec.feed(payload);
  });
  await client.subscribeAsync(`arm/${o.arm}/status`, { qos: 0 });
  if (o.onControl) await client.subscribeAsync(`arm/${o.arm}/control`, { qos: 0 });
  return {
    sim,
    client,
    rec,
    close: async () => {
      await client.endAsync().catch(() => {});
      await sim.stop();
    },
  };
}
