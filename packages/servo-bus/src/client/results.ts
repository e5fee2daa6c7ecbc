/** What the bus client hands back for each request, typed per request. */
import type { StatusProblem } from '../status-errors.ts';

/** The status error byte of a reply, and what it says. */
export interface ReplyStatus {
  error: number;
  /** Empty when all is well. */
  problems: StatusProblem[];
}

export interface ServoPosition {
  id: number;
  /** Present position as the servo reports it. */
  ticks: number;
  /** Joint angle after the servo's zero and direction. */
  degrees: number;
  status: ReplyStatus;
}

export interface ServoHealth {
  id: number;
  temperatureC: number;
  voltageV: number;
  status: ReplyStatus;
}

export const BUS_RESULT_KINDS = ['ping', 'model', 'positions', 'health', 'read', 'write'] as const;
export type BusResultKind = (typeof BUS_RESULT_KINDS)[number];

export type BusResult =
  | {
      kind: 'ping';
      id: number;
      found: boolean;
      status?: ReplyStatus;
      modelNumber?: number;
      firmware?: number;
    }
  | {
      kind: 'model';
      id: number;
      found: boolean;
      status?: ReplyStatus;
      modelNumber?: number;
      modelName?: string;
    }
  | { kind: 'positions'; servos: ServoPosition[]; missing: number[] }
  | { kind: 'health'; servos: ServoHealth[]; missing: number[] }
  | { kind: 'read'; id: number; found: boolean; status?: ReplyStatus; data?: Uint8Array }
  | { kind: 'write'; id: number; found: boolean; status?: ReplyStatus };
