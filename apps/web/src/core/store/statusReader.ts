/**
 * Reads the arm's status stream (`arm/{id}/status`) into the store's updates (./ArmStore.ts):
 * a group's position and angle frames are one state report (stamped once, by the group's
 * `$TIM`), its health frames one health row; a lone frame is a report or a row of its own.
 * Host → arm frames someone else published there, and `$TIM` itself, say nothing about the arm.
 */
import {
  createReader,
  unhandled,
  type Frame,
  type Group,
  type Reader,
  type ReaderError,
} from '@armtwin/protocol';

/** Where the status stream's news goes. */
export interface StatusSink {
  /** `n` frames decoded (group members included). */
  counted(n: number): void;
  /** A state report begins (its first position or angle), stamped by `$TIM` (epoch ms) or not. */
  stateArrived(stamp: number | undefined): void;
  position(id: number, pwm: number): void;
  angle(id: number, deg: number): void;
  /** A health row begins. */
  healthRow(): void;
  health(id: number, temp: number, mv: number): void;
  /** The health row is complete. */
  healthDone(stamp: number | undefined): void;
  kmsResult(code: number): void;
  ping(seq: number): void;
  controllerError(text: string): void;
}

export function createStatusReader(sink: StatusSink, onError: (e: ReaderError) => void): Reader {
  const handle = (f: Frame): void => {
    switch (f.type) {
      case 'position':
        sink.stateArrived(f.time);
        sink.position(f.id, f.pwm);
        break;
      case 'angle':
        sink.stateArrived(f.time);
        sink.angle(f.id, f.deg);
        break;
      case 'health':
        sink.healthRow();
        sink.health(f.id, f.temp, f.mv);
        sink.healthDone(f.time);
        break;
      case 'kmsResult':
        sink.kmsResult(f.code);
        break;
      case 'ping':
        sink.ping(f.seq);
        break;
      case 'controllerError':
        sink.controllerError(f.text);
        break;
      // `$TIM` stamps the frames after it (the reader does that).
      case 'time':
      case 'move':
      case 'angleMove':
      case 'readPosition':
      case 'readHealth':
      case 'stop':
      case 'kms':
        break;
      default:
        return unhandled(f);
    }
  };
  const onGroup = (g: Group): void => {
    let positions = 0;
    let health = 0;
    sink.healthRow();
    sink.counted(g.frames.length);
    for (const f of g.frames) {
      if (f.type === 'position') {
        if (positions++ === 0) sink.stateArrived(g.time);
        sink.position(f.id, f.pwm);
      } else if (f.type === 'angle') {
        if (positions++ === 0) sink.stateArrived(g.time);
        sink.angle(f.id, f.deg);
      } else if (f.type === 'health') {
        health++;
        sink.health(f.id, f.temp, f.mv);
      } else {
        handle(f);
      }
    }
    if (health > 0) sink.healthDone(g.time);
  };
  return createReader({
    onFrame: (f) => {
      sink.counted(1);
      handle(f);
    },
    onGroup,
    onError,
  });
}
