/**
 * What a gateway with a robot profile runs beside its core on MQTT (the LSC board and the servo
 * bus alike): the profile announced and followed on disk (./profile-follow.ts), and motion
 * requests on `arm/{id}/request`, planned and executed by the controller core
 * (@armtwin/controller), on the system clock.
 */
import type { MqttClient } from 'mqtt';
import type { Logger } from 'pino';
import { MotionRequests, type ControlArbiter, type ControllerCore } from '@armtwin/controller';
import { startMotionService } from '@armtwin/controller/mqtt';
import type { MotionRobot } from '@armtwin/motion';
import { armTopics, SYSTEM_CLOCK } from '@armtwin/protocol';
import { followProfile, type ProfileCore } from './profile-follow.ts';

export interface ArmServicesOptions {
  client: MqttClient;
  armId: string;
  /** Profile name (its folder), the models folder, and profile.json as read at start. */
  profile: string;
  modelsDir: string;
  raw: unknown;
  /** The planner's robot of that profile. */
  robot: MotionRobot;
  core: ProfileCore & { readonly controller: ControllerCore; readonly robot?: MotionRobot };
  control: ControlArbiter;
  onFirst(kind: string, message: string): void;
  /** Logs each new profile put in force. */
  log?: Logger;
}

export function startArmServices(o: ArmServicesOptions): { stop(): void } {
  const follow = followProfile({
    ...o,
    name: o.profile,
    onReload: (name) => o.log?.info({ profile: name }, 'profile file changed: now in force'),
  });
  const motion = startMotionService(
    o.client,
    new MotionRequests(o.core.controller, () => o.core.robot ?? o.robot, SYSTEM_CLOCK.now(), {
      mayExecute: (user) => o.control.refusal(user, 'a motion request on the arm'),
      onFirst: o.onFirst,
      controlTopic: armTopics(o.armId).control,
    }),
    o.armId,
    SYSTEM_CLOCK,
    o.onFirst,
  );
  return {
    stop() {
      motion.stop();
      follow.stop();
    },
  };
}
