/**
 * Wires the bus gateway (`armtwin gateway --bus dynamixel|feetech`): the robot profile read
 * from disk (announced and followed: ./profile-follow.ts), a `SerialLink` (reopens with
 * back-off), an mqtt.js client (last will `0` on `arm/{id}/online`), `BusGatewayCore` and
 * motion requests on `arm/{id}/request` (./arm-services.ts), on the system clock.
 */
import type { MqttClient } from 'mqtt';
import { numericKms, zonesKeepOut } from '@armtwin/controller';
import { armSummary } from '@armtwin/controller/mqtt';
import type { Profile } from '@armtwin/robot';
import type { MotionRobot } from '@armtwin/motion';
import { MODELS_DIR, readRobotFolder } from '@armtwin/motion/robot-folder';
import { armTopics, SYSTEM_CLOCK, topic } from '@armtwin/protocol';
import type { BusProtocol } from '@armtwin/servo-bus';
import {
  BusGatewayCore,
  DEFAULT_BUS_GATEWAY_OPTIONS,
  type BusGatewayOptions,
} from './bus-gateway.ts';
import { startArmServices } from './arm-services.ts';
import { SerialLink } from './serial-link.ts';
import {
  connectGatewayMqtt,
  gatewayPublish,
  DEFAULT_GATEWAY_OPTIONS,
  wireGatewayMqtt,
  type GatewayOptions,
} from './start-gateway.ts';

/** The robots' folders (`public/models`). */
export const BUS_MODELS_DIR = MODELS_DIR;

/** The topic that turns torque off (`0`) and on (`1`): `arm/{id}/torque`, retained or not. */
export const torqueTopic = (armId: string) => topic(armId, 'torque');

export interface BusGatewayStartOptions extends GatewayOptions {
  bus: BusProtocol;
  stateRate: number;
  healthRate: number;
}

export interface BusGateway {
  core: BusGatewayCore;
  client: MqttClient;
  link: SerialLink;
  stop(): Promise<void>;
}

/**
 * Reads and parses `<modelsDir>/<name>/profile.json`, and builds its IK (a numeric profile's
 * from its URDF); throws with every problem found.
 */
export function loadProfile(
  name: string,
  modelsDir: string = BUS_MODELS_DIR,
): { profile: Profile; robot: MotionRobot } {
  const { profile, robot } = readRobotFolder(name, modelsDir);
  return { profile, robot };
}

export function startBusGateway(
  options: Partial<BusGatewayStartOptions> &
    Pick<BusGatewayStartOptions, 'serialPath' | 'mqttUrl' | 'armId' | 'bus' | 'profile'>,
): BusGateway {
  const o = {
    ...DEFAULT_GATEWAY_OPTIONS,
    baudRate: DEFAULT_BUS_GATEWAY_OPTIONS.baudRate,
    stateRate: DEFAULT_BUS_GATEWAY_OPTIONS.stateRate,
    healthRate: DEFAULT_BUS_GATEWAY_OPTIONS.healthRate,
    ...options,
  };
  const { log } = o;
  const { profile, robot, raw } = readRobotFolder(o.profile, o.modelsDir);
  const topics = armTopics(o.armId);
  const torque = torqueTopic(o.armId);
  const client = connectGatewayMqtt(o);
  const link: SerialLink = new SerialLink(
    { ...o.serial, path: o.serialPath, baudRate: o.baudRate },
    {
      onOpen: () => {
        core.serialOpened();
        log?.info({ serial: o.serialPath, bus: o.bus }, 'serial line open');
      },
      onClose: (reason) => {
        core.serialClosed();
        log?.warn({ reason }, 'serial line closed; reopening');
      },
      onData: (chunk) => core.fromSerial(chunk),
    },
  );
  const coreOptions: Partial<BusGatewayOptions> &
    Pick<BusGatewayOptions, 'armId' | 'protocol' | 'profile'> = {
    armId: o.armId,
    protocol: o.bus,
    profile,
    baudRate: o.baudRate,
    stateRate: o.stateRate,
    healthRate: o.healthRate,
    operatorLeaseMs: o.operatorLeaseMs,
    kms: numericKms(robot),
    keepOut: zonesKeepOut(robot),
    robot,
  };
  const summary = armSummary(client, o.armId, SYSTEM_CLOCK);
  const core = new BusGatewayCore(coreOptions, {
    ...SYSTEM_CLOCK,
    publish: gatewayPublish(client, summary),
    write: (data) => link.write(Buffer.from(data.buffer, data.byteOffset, data.byteLength)),
    onFirst: o.onFirst,
  });
  const control = wireGatewayMqtt(client, o, core, { [torque]: (p) => core.fromTorque(p) });
  const services = startArmServices({ ...o, client, raw, robot, core, control });
  summary.start(
    () => core.controller,
    () => control.holder,
  );
  link.start();
  log?.info(
    { arm: o.armId, bus: o.bus, profile: o.profile, ids: core.joints.map((j) => j.id) },
    'bus gateway running',
  );
  return {
    core,
    client,
    link,
    async stop() {
      services.stop();
      core.operator.reset();
      control.reset();
      core.serialClosed();
      await summary.stop();
      if (client.connected)
        await client.publishAsync(topics.online, '0', { qos: 1, retain: true }).catch(() => {});
      await client.endAsync().catch(() => {});
      await link.stop();
      log?.info(
        { counters: core.counters, line: core.lineCounters, serial: link.counters },
        'gateway stopped',
      );
    },
  };
}
