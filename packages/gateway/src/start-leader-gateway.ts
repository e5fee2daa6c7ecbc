/**
 * Wires a leader arm (`armtwin gateway --bus feetech|dynamixel --serial PATH --leader-of ARM`):
 * its servo bus on a `SerialLink` (the profile's ids pinged at each open, torque turned off so a
 * hand moves it, positions read by SYNC READ at `stateRate`, a missing one pinged again every
 * second), an mqtt.js client, and
 * `LeaderTeleop` (./leader-teleop.ts) turning each read into the follower's targets through the
 * follower's controller. The last will says the leader no longer follows.
 */
import { connectBrokers, parseBrokerList } from '@armtwin/link';
import { readRobotFolder } from '@armtwin/motion/robot-folder';
import { CLEAN_SESSION_SUBSCRIBE_QOS, linkOptions, SYSTEM_CLOCK } from '@armtwin/protocol';
import type { BusProtocol } from '@armtwin/servo-bus';
import { BusLine } from './bus-line.ts';
import { busJoints } from './bus-servos.ts';
import { LeaderTeleop } from './leader-teleop.ts';
import { SerialLink } from './serial-link.ts';
import { DEFAULT_GATEWAY_OPTIONS, type GatewayOptions } from './start-gateway.ts';
import { BUS_MODELS_DIR } from './start-bus-gateway.ts';

/** The holder's keep-alive on the follower's claim topic, ms (the HUD's beat). */
export const LEADER_BEAT_MS = 500;

export interface LeaderGatewayOptions extends Pick<
  GatewayOptions,
  'serialPath' | 'baudRate' | 'mqttUrl' | 'username' | 'password'
> {
  bus: BusProtocol;
  /** The leader's profile (its servos' ids and names): `<modelsDir>/<name>/profile.json`. */
  profile: string;
  modelsDir: string;
  /** The follower's arm id. */
  follower: string;
  /** Who the leader is to the follower's controller: its lease and commands are this user's. */
  user: string;
  /** Leader reads per second. */
  stateRate: number;
  onFirst: (kind: string, message: string) => void;
  log?: GatewayOptions['log'];
}

export interface LeaderGateway {
  teleop: LeaderTeleop;
  line: BusLine;
  stop(): Promise<void>;
}

export function startLeaderGateway(
  options: Partial<LeaderGatewayOptions> &
    Pick<LeaderGatewayOptions, 'serialPath' | 'mqttUrl' | 'bus' | 'profile' | 'follower' | 'user'>,
): LeaderGateway {
  const o = {
    baudRate: 1_000_000,
    modelsDir: BUS_MODELS_DIR,
    stateRate: 30,
    onFirst: DEFAULT_GATEWAY_OPTIONS.onFirst,
    ...options,
  };
  const { log } = o;
  const { profile } = readRobotFolder(o.profile, o.modelsDir);
  const joints = busJoints(profile);
  const teleop = new LeaderTeleop(
    {
      follower: o.follower,
      user: o.user,
      servos: profile.servos.map((s) => ({ id: s.id, name: s.name })),
    },
    {
      ...SYSTEM_CLOCK,
      publish: (t, p, opts) => {
        // Every change of whether it follows is logged (the retained state says it too).
        if (t === topics.state) log?.info({ follower: o.follower, state: p }, 'leader: state');
        if (client.connected) client.publish(t, p, opts);
      },
      onFirst: o.onFirst,
    },
  );
  const topics = teleop.topics;
  const client = connectBrokers(parseBrokerList(o.mqttUrl), {
    clientId: `armtwin-leader-${o.follower}-${o.user}-${process.pid}`,
    ...(o.username ? { username: o.username, password: o.password ?? '' } : {}),
    will: {
      topic: topics.state,
      payload: Buffer.from(
        JSON.stringify({ following: false, reason: 'the leader gateway is gone' }),
      ),
      qos: 1,
      retain: true,
    },
    ...linkOptions(),
    queueQoSZero: false,
  });
  const handlers: Record<string, (payload: string) => void> = {
    [topics.profile]: (p) => teleop.followerProfile(p),
    [topics.holder]: (p) => teleop.holderRecord(p),
    [topics.audit]: (p) => teleop.audit(p),
    [topics.enable]: (p) => teleop.enable(p),
  };
  client.on('connect', () => {
    (client.stream as { setNoDelay?: (on: boolean) => void } | undefined)?.setNoDelay?.(true);
    client.subscribe(Object.keys(handlers), { qos: CLEAN_SESSION_SUBSCRIBE_QOS }, (err) => {
      if (err) o.onFirst('subscribe', err.message);
      else teleop.connected();
    });
    log?.info({ follower: o.follower, user: o.user }, 'leader: broker connected');
  });
  client.on('error', (err) => o.onFirst(`mqtt:${err.message}`, `mqtt: ${err.message}`));
  client.on('message', (t, payload) => handlers[t]?.(payload.toString()));

  // The leader's bus: found servos, torque off, positions read at the rate.
  const found: number[] = [];
  const line: BusLine = new BusLine(o.bus, joints, o.baudRate, {
    ...SYSTEM_CLOCK,
    write: (data) => link.write(Buffer.from(data.buffer, data.byteOffset, data.byteLength)),
    onFirst: o.onFirst,
  });
  let nextPingMs = 0;
  /** Positions of the servos found; one that did not answer is pinged again each second. */
  const read = () => {
    if (!line.ready) return;
    if (found.length && !line.has('positions'))
      line.readPositions(found, (r) => teleop.leaderPose(r.servos));
    const lost = joints.map((j) => j.id).filter((id) => !found.includes(id));
    if (lost.length && Date.now() >= nextPingMs && !line.has('ping')) {
      nextPingMs = Date.now() + 1000;
      line.ping(lost, (back) => {
        const ids = new Set([...found, ...back]);
        found.splice(0, found.length, ...joints.map((j) => j.id).filter((id) => ids.has(id)));
        line.torque(false, back);
      });
    }
  };
  const link: SerialLink = new SerialLink(
    { path: o.serialPath, baudRate: o.baudRate },
    {
      onOpen: () => {
        line.reset();
        found.length = 0;
        line.ping(
          joints.map((j) => j.id),
          (yes, missing) => {
            found.push(...yes);
            if (missing.length)
              o.onFirst(
                'leader:missing',
                `leader servos missing: ${missing.join(' ')} (pinged again)`,
              );
            line.torque(false, yes);
            line.markReady();
          },
        );
        log?.info({ serial: o.serialPath, bus: o.bus }, 'leader: serial line open');
      },
      onClose: (reason) => {
        line.reset();
        log?.warn({ reason }, 'leader: serial line closed; reopening');
      },
      onData: (chunk) => line.fromSerial(chunk),
    },
  );
  const poll = setInterval(read, 1000 / o.stateRate);
  const beat = setInterval(() => teleop.beat(), LEADER_BEAT_MS);
  link.start();
  log?.info(
    { follower: o.follower, user: o.user, bus: o.bus, profile: o.profile },
    'leader gateway running',
  );
  return {
    teleop,
    line,
    async stop() {
      clearInterval(poll);
      clearInterval(beat);
      teleop.release();
      await client.endAsync().catch(() => {});
      await link.stop();
      log?.info({ counters: teleop.counters, line: line.counters }, 'leader gateway stopped');
    },
  };
}
