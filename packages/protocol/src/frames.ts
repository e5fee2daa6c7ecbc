/**
 * Every frame of the wire contract (docs/protocol.md), host → arm and arm → host.
 * The reader decodes both directions; a consumer ignores the kinds it does not expect.
 * `time` is the Unix epoch ms of the `$TIM` stamp that preceded the frame in the stream,
 * when there was one.
 */

/** `#IIIPppppTtttt!`: move servo `id` to `pwm` µs in `ms` milliseconds. */
export interface MoveFrame {
  type: 'move';
  id: number;
  pwm: number;
  ms: number;
  time?: number;
}
/**
 * `#IIIA±ddd.ddTtttt!` (§8): move servo `id` to servo angle `deg` (degrees, −999.99 …
 * +999.99) in `ms` milliseconds. For servos that are not pulse-width servos (bus servos).
 */
export interface AngleMoveFrame {
  type: 'angleMove';
  id: number;
  deg: number;
  ms: number;
  time?: number;
}
/** `#IIIPRAD!`: read position. */
export interface ReadPositionFrame {
  type: 'readPosition';
  id: number;
  time?: number;
}
/** `#IIIPRTV!`: read temperature and voltage. */
export interface ReadHealthFrame {
  type: 'readHealth';
  id: number;
  time?: number;
}
/** `#IIIPDST!`: stop servo `id` (255 = every servo: emergency stop). */
export interface StopFrame {
  type: 'stop';
  id: number;
  time?: number;
}
/** `$KMS:x,y,z[,a],t!`: move the gripper tip to (x, y, z) mm in `ms`; `alpha` in degrees. */
export interface KmsFrame {
  type: 'kms';
  x: number;
  y: number;
  z: number;
  alpha?: number;
  ms: number;
  time?: number;
}
/** `$PNG:n!`: ping (host → arm) or its echo (arm → host). */
export interface PingFrame {
  type: 'ping';
  seq: number;
  time?: number;
}
/** `#IIIPpppp!`: position report. */
export interface PositionFrame {
  type: 'position';
  id: number;
  pwm: number;
  time?: number;
}
/** `#IIIA±ddd.dd!` (§8): servo `id` is at servo angle `deg` (degrees, −999.99 … +999.99). */
export interface AngleFrame {
  type: 'angle';
  id: number;
  deg: number;
  time?: number;
}
/** `#IIITtttVvvvv!`: health report; `temp` in °C, `mv` supply voltage in millivolts. */
export interface HealthFrame {
  type: 'health';
  id: number;
  temp: number;
  mv: number;
  time?: number;
}
/** `$KMS:c!`: outcome of the last `$KMS` command (IK status code). */
export interface KmsResultFrame {
  type: 'kmsResult';
  code: number;
  time?: number;
}
/** `$TIM:ms!`: time stamp (Unix epoch ms) for the frames that follow. */
export interface TimeFrame {
  type: 'time';
  ms: number;
  time?: number;
}
/** `$ERR:text!`: the controller could not parse a command. */
export interface ControllerErrorFrame {
  type: 'controllerError';
  text: string;
  time?: number;
}

export type ControlFrame =
  | MoveFrame
  | AngleMoveFrame
  | ReadPositionFrame
  | ReadHealthFrame
  | StopFrame
  | KmsFrame
  | PingFrame;
export type StatusFrame =
  | PositionFrame
  | AngleFrame
  | HealthFrame
  | KmsResultFrame
  | PingFrame
  | TimeFrame
  | ControllerErrorFrame;
export type Frame = ControlFrame | StatusFrame;
export type FrameType = Frame['type'];

/**
 * A `{…}` group as the reader delivers it: the frames inside that decoded, and how many
 * did not (each of those is also reported as a ReaderError). A controller executes a group
 * only when `invalid` is 0 (all-or-nothing); a storage consumer keeps the valid frames.
 */
export interface Group {
  type: 'group';
  frames: Frame[];
  invalid: number;
  time?: number;
}

/**
 * Which topic each frame kind may travel on (§1): `control` (host → arm), `status`
 * (arm → host). A Record over FrameType, so a new frame kind fails to compile until it is
 * placed here. `$TIM` may stamp either direction; `$PNG` travels both ways.
 */
export const FRAME_TOPICS: Readonly<Record<FrameType, { control: boolean; status: boolean }>> = {
  move: { control: true, status: false },
  angleMove: { control: true, status: false },
  readPosition: { control: true, status: false },
  readHealth: { control: true, status: false },
  stop: { control: true, status: false },
  kms: { control: true, status: false },
  ping: { control: true, status: true },
  position: { control: false, status: true },
  angle: { control: false, status: true },
  health: { control: false, status: true },
  kmsResult: { control: false, status: true },
  time: { control: true, status: true },
  controllerError: { control: false, status: true },
};

/**
 * Ends an exhaustive `switch` over a union: `default: return unhandled(x)` compiles only
 * while every member has its case.
 */
export function unhandled(value: never): never {
  throw new Error(`unhandled case: ${JSON.stringify(value)}`);
}
