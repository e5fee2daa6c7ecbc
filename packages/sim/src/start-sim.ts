/**
 * `armtwin sim`: the simulated controller on its own, over MQTT (a client of its own, with the
 * retained `0` will) or on a serial line (as real firmware, behind the gateway). Loads the
 * profile, starts the runner with the faults in force, and logs what it does; the caller
 * decides when to stop.
 */
import readline from 'node:readline';
import type { Logger } from 'pino';
import { connectBrokers } from '@armtwin/link';
import { linkOptions, OPERATOR_LEASE_MS } from '@armtwin/protocol';
import { describeBroker, parseBrokerList, redactBrokerUrl } from '@armtwin/link';
import type { BenchFault, BusProtocol } from '@armtwin/servo-bus';
import { startBusSim, type BusSimCore } from './bus-sim.ts';
import type { Fault } from './faults.ts';
import { parseHandLine } from './hand.ts';
import { simWill, startMqttSim } from './mqtt-sim.ts';
import type { ReportUnits } from './options.ts';
import { DEFAULT_PROFILE, loadSimProfile, MODELS_DIR } from './profile.ts';
import { followZones } from './zones-follow.ts';
import { DEFAULT_SIM_RUNNER_OPTIONS, type PayloadKind, type SimRunner } from './runner.ts';
import { startSerialSim } from './serial-sim.ts';

export interface SimOptions {
  /**
   * The broker to connect to (MQTT mode), or an ordered, comma-separated list: the first is
   * preferred, the others are fall-backs (docs/protocol.md § Several brokers).
   */
  mqttUrl: string;
  /** Broker credentials ('' = anonymous). */
  username: string;
  password: string;
  /** The arm id: `[a-z0-9-]{1,32}`. */
  armId: string;
  /** Robot profile: `<modelsDir>/<name>/profile.json`. */
  profile: string;
  /** The folder of robot profiles (default: the repository's `public/models`). */
  modelsDir: string;
  /** Position reports: as the profile says (`auto`), all §8 angle frames, or all pulse widths. */
  report: ReportUnits;
  /** Heat runs this many times faster than the clock (`SimModelOptions.thermalTimeScale`). */
  thermalTimeScale: number;
  /** State and health rates, Hz. */
  rate: number;
  healthRate: number;
  /** Speak on this serial line instead of MQTT ('' = MQTT): no `$TIM`, no presence. */
  serialPath: string;
  baudRate: number;
  /** On the serial line, answer as a Dynamixel or Feetech bus of the profile's servos ('' = frames). */
  bus: '' | BusProtocol;
  /** Faults in force from the start. */
  faults: Fault[];
  /** On a servo bus: faults of the bench (absent, extra, clashing servos, fields). */
  benchFaults: BenchFault[];
  /** A beating operator is let go after this long without a `1`, ms (0 = only a `0`). */
  operatorLeaseMs: number;
  /** On a servo bus: hand moves, one line each (`1:30,2:-15`, ./hand.ts), e.g. stdin. */
  handInput?: NodeJS.ReadableStream;
  log: Logger;
  /** Told the first time each kind of problem happens (later ones are only counted). */
  onFirst: (kind: string, message: string) => void;
}

export const DEFAULT_SIM_OPTIONS = {
  username: '',
  password: '',
  profile: DEFAULT_PROFILE,
  modelsDir: MODELS_DIR,
  report: 'auto',
  thermalTimeScale: 1,
  rate: DEFAULT_SIM_RUNNER_OPTIONS.rate,
  healthRate: DEFAULT_SIM_RUNNER_OPTIONS.healthRate,
  serialPath: '',
  baudRate: 115200,
  bus: '',
  faults: [],
  benchFaults: [],
  operatorLeaseMs: OPERATOR_LEASE_MS,
  onFirst: () => {},
} satisfies Partial<SimOptions>;

export interface Sim {
  /** The frame controller (absent on a servo bus). */
  runner?: SimRunner;
  /** The emulated servo bus (`bus` set). */
  bus?: BusSimCore;
  /** On MQTT: the status payloads handed to the client so far, and their `$TIM` samples, by kind (mqtt-sim.ts). */
  published?: Readonly<Record<PayloadKind, number>>;
  publishedSamples?: Readonly<Record<PayloadKind, number>>;
  /** Resolves with the reason when the serial line closes under the sim; never on MQTT. */
  closed: Promise<string>;
  /** Stops the loops; on MQTT, says offline and disconnects. */
  stop(): Promise<void>;
}

/** Moves the bus's shafts by the lines of `input` (./hand.ts); bad lines are told once, by kind. */
function followHand(
  input: NodeJS.ReadableStream,
  core: BusSimCore,
  onFirst: SimOptions['onFirst'],
): readline.Interface {
  const lines = readline.createInterface({ input });
  lines.on('line', (line) => {
    try {
      for (const m of parseHandLine(line))
        if (!core.hand(m, Date.now()))
          onFirst('hand:no-servo', `hand: no servo ${m.id} on the bus`);
    } catch (err) {
      onFirst('hand:bad-line', (err as Error).message);
    }
  });
  return lines;
}

export async function startSim(
  options: Partial<SimOptions> & Pick<SimOptions, 'mqttUrl' | 'armId' | 'log'>,
): Promise<Sim> {
  const o: SimOptions = { ...DEFAULT_SIM_OPTIONS, ...options };
  const { log } = o;
  const profile = loadSimProfile(o.profile, o.modelsDir);
  const runnerOptions = {
    model: { ...profile.model, report: o.report, thermalTimeScale: o.thermalTimeScale },
    rate: o.rate,
    healthRate: o.healthRate,
    faults: o.faults,
    onFirst: o.onFirst,
  };
  if (o.serialPath && o.bus) {
    const sim = await startBusSim({
      protocol: o.bus,
      profile: profile.profile,
      faults: o.faults,
      benchFaults: o.benchFaults,
      path: o.serialPath,
      baudRate: o.baudRate,
      onFirst: o.onFirst,
    });
    const hands = o.handInput && followHand(o.handInput, sim.core, o.onFirst);
    log.info(
      { serial: o.serialPath, bus: o.bus, ids: profile.profile.servos.map((s) => s.id) },
      'simulated servo bus on the serial line',
    );
    return {
      bus: sim.core,
      closed: sim.closed,
      stop: async () => {
        hands?.close();
        await sim.stop();
      },
    };
  }
  if (o.serialPath) {
    const sim = await startSerialSim({
      ...runnerOptions,
      path: o.serialPath,
      baudRate: o.baudRate,
    });
    log.info({ serial: o.serialPath, rate: o.rate }, 'simulated controller on the serial line');
    return sim;
  }
  const urls = parseBrokerList(o.mqttUrl);
  const client = connectBrokers(
    urls,
    {
      clientId: `armtwin-sim-${o.armId}-${process.pid}`,
      ...(o.username ? { username: o.username, password: o.password } : {}),
      will: simWill(o.armId),
      ...linkOptions(),
      queueQoSZero: false,
    },
    {
      onMove: (move) =>
        move.from &&
        log.info(
          { arm: o.armId, from: move.from.index + 1, to: move.to.index + 1, reason: move.reason },
          `broker move: ${describeBroker(move.to)}`,
        ),
    },
  );
  client.on('connect', () => {
    // Frames are small: don't let Nagle's algorithm hold them back (~40 ms tails otherwise).
    (client.stream as { setNoDelay?: (on: boolean) => void } | undefined)?.setNoDelay?.(true);
    const b = client.brokers.choice;
    log.info(
      { url: redactBrokerUrl(b.url), broker: b.index + 1, brokers: b.count, arm: o.armId },
      'connected',
    );
  });
  client.on('error', (err) => log.warn({ err: err.message }, 'mqtt error'));
  const sim = startMqttSim(client, {
    ...runnerOptions,
    armId: o.armId,
    profile,
    operatorLeaseMs: o.operatorLeaseMs,
    statusQos: urls.length > 1 ? 1 : 0,
  });
  // Keep-out zones follow the profile file (the HUD's Zones section writes it): zones-follow.ts.
  const zones = followZones({
    client,
    armId: o.armId,
    name: o.profile,
    modelsDir: o.modelsDir,
    sim: profile,
    runner: sim.runner,
    onFirst: o.onFirst,
    onReload: (ok, message) => (ok ? log.info : log.warn).call(log, { arm: o.armId }, message),
  });
  log.info(
    {
      arm: o.armId,
      profile: o.profile,
      report: o.report,
      ...(o.thermalTimeScale !== 1 ? { thermalTimeScale: o.thermalTimeScale } : {}),
      rate: o.rate,
      healthRate: o.healthRate,
      faults: sim.runner.faults,
    },
    'sim running',
  );
  return {
    runner: sim.runner,
    published: sim.published,
    publishedSamples: sim.publishedSamples,
    closed: new Promise<string>(() => {}),
    async stop() {
      zones.stop();
      await sim.stop();
      log.info(
        {
          counters: sim.runner.counters,
          model: sim.runner.model.counters,
          published: sim.published,
          statusMessages: sim.statusMessages,
          brokerMoves: client.brokers.moves,
        },
        'sim stopped',
      );
    },
  };
}
