/**
 * MQTT message → line-protocol lines. One protocol reader per (arm, topic), because a frame
 * may continue in the next message of the same topic; the `$TIM` stamp is cleared before
 * each message, so an unstamped payload's frames get its arrival time.
 *
 * `$KMS` pairing: a `$KMS:x,y,z[,a],t!` on `arm/{id}/control` is held as the arm's pending
 * request; the next `$KMS:c!` on `arm/{id}/status` writes ONE `ik` point at the result's
 * time with `code` and the request's x, y, z, a. A request superseded before any result is
 * written alone (no `code`) at its own time; a result with no request seen writes `code`
 * only. Control frames of a group that had an invalid frame are not stored (the controller
 * executes such a group not at all) and are counted as `group-not-executed`.
 * A command on a user's own control topic (`arm/{id}/control/{user}`, docs/protocol.md
 * § Control) is stored like one on `arm/{id}/control`, with its author as the tag `user`.
 * The profile an arm announces (retained `arm/{id}/profile`) is stored as one `profile` point
 * (`name`, `title`) at its arrival, once per middleware run and again whenever it changes, so an
 * export of any range finds the robot the arm was (`armtwin export` without `--profile`).
 */
import {
  createReader,
  FRAME_TOPICS,
  MAX_PAYLOAD_BYTES,
  isValidArmId,
  parseAudit,
  parseTopic,
  parseUserTopic,
  unhandled,
  type Frame,
  type KmsFrame,
  type Reader,
} from '@armtwin/protocol';
import { parseAnnouncement } from '@armtwin/robot';
import type { Metrics } from './metrics.ts';
import type { LogOnce } from './log.ts';
import {
  angleCommandFields,
  angleFields,
  auditLine,
  auditSeries,
  commandFields,
  commandSeries,
  healthFields,
  ikFields,
  ikSeries,
  healthClock,
  positionFields,
  profileLine,
  servoSeries,
  SeriesClock,
} from './points.ts';

/** `arm/{id}/audit`: the controller's control events, stored as measurement `audit`. */
const AUDIT_TOPIC = /^arm\/([^/]+)\/audit$/;
/** `arm/{id}/profile`: the robot the arm announces (retained), stored as measurement `profile`. */
const PROFILE_TOPIC = /^arm\/([^/]+)\/profile$/;

export interface IngestOptions {
  /** A bigger message is refused whole and counted once as `oversize`. */
  maxPayloadBytes: number;
  /**
   * Most (arm, topic) readers kept; beyond it the least recently created is forgotten (its
   * partial frame, if any, is lost), so a stream of new arm ids cannot grow memory without end.
   */
  maxReaders: number;
}

export const DEFAULT_INGEST_OPTIONS: IngestOptions = {
  maxPayloadBytes: MAX_PAYLOAD_BYTES,
  maxReaders: 4096,
};

/** What a topic says: the reader's key, and the arm and author of its frames. */
interface TopicInfo {
  key: string;
  arm: string;
  kind: 'status' | 'control';
  author: string;
}

/**
 * A reader, and the series names of its frames built once per servo id (the command series
 * with the author's tag; the clock of each servo's health points): a message's points only add
 * their fields and time.
 */
interface ReaderEntry {
  reader: Reader;
  servo: string[];
  health: string[];
  command: string[];
}

/** Topics remembered (parsed once); beyond it the memory is cleared and fills again. */
const MAX_TOPICS = 8192;

export class Ingest {
  private readonly readers = new Map<string, ReaderEntry>();
  private readonly topics = new Map<string, TopicInfo | null>();
  private readonly o: IngestOptions;
  private readonly pendingKms = new Map<string, KmsFrame & { at: number }>();
  /** The profile point last written per arm (its line's fields), so a repeat writes nothing. */
  private readonly profiles = new Map<string, string>();
  readonly clock = new SeriesClock();
  /**
   * Given the frames of each message on a status topic (the thermal watch: one parse of a
   * payload, not two). Called before `handle` returns; the array is reused after.
   */
  onStatusFrames: ((arm: string, frames: readonly Frame[]) => void) | null = null;
  private readonly statusFrames: Frame[] = [];
  // The message being handled (the readers' callbacks write here).
  private arm = '';
  private onControl = false;
  /** The author of the message being read (its per-user control topic), '' = unknown. */
  private author = '';
  private arrival = 0;
  private entry: ReaderEntry | null = null;
  private out: string[] = [];

  constructor(
    private readonly metrics: Metrics,
    private readonly once?: LogOnce,
    options: Partial<IngestOptions> = {},
  ) {
    this.o = { ...DEFAULT_INGEST_OPTIONS, ...options };
  }

  /** Lines for one message (possibly none); `arrivalMs` is the fallback time. */
  handle(topic: string, payload: Uint8Array | string, arrivalMs: number): string[] {
    let info = this.topics.get(topic);
    if (info === undefined) {
      const audit = AUDIT_TOPIC.exec(topic);
      if (audit && isValidArmId(audit[1]!)) return this.audit(audit[1]!, payload);
      const announced = PROFILE_TOPIC.exec(topic);
      if (announced && isValidArmId(announced[1]!))
        return this.profile(announced[1]!, payload, arrivalMs);
      info = frameTopic(topic);
      if (this.topics.size >= MAX_TOPICS) this.topics.clear();
      this.topics.set(topic, info);
    }
    this.metrics.count(this.metrics.messages, info?.kind ?? 'other');
    if (!info) {
      this.reject('bad-topic', topic);
      return [];
    }
    this.arm = info.arm;
    if (payload.length > this.o.maxPayloadBytes) {
      this.reject(
        'oversize',
        `${payload.length} bytes`,
        `message over ${this.o.maxPayloadBytes} bytes`,
      );
      return [];
    }
    this.onControl = info.kind === 'control';
    this.author = info.author;
    this.arrival = arrivalMs;
    this.out = [];
    const entry = (this.entry = this.reader(info.key));
    entry.reader.clearStamp();
    entry.reader.feed(
      typeof payload === 'string'
        ? payload
        : Buffer.isBuffer(payload) // mqtt.js's payloads: no second view of the bytes
          ? payload.toString('latin1')
          : latin1(payload),
    );
    this.entry = null;
    if (this.statusFrames.length > 0) {
      this.onStatusFrames?.(info.arm, this.statusFrames);
      this.statusFrames.length = 0;
    }
    const lines = this.out;
    this.out = [];
    this.metrics.pointsProduced += lines.length;
    this.metrics.timestampsBumped = this.clock.bumped;
    return lines;
  }

  /** A control event (docs/protocol.md § Control) → one `audit` point at its own time. */
  private audit(arm: string, payload: Uint8Array | string): string[] {
    this.metrics.count(this.metrics.messages, 'audit');
    this.arm = arm;
    if (payload.length > this.o.maxPayloadBytes) {
      this.reject(
        'oversize',
        `${payload.length} bytes`,
        `message over ${this.o.maxPayloadBytes} bytes`,
      );
      return [];
    }
    const e = parseAudit(payload);
    if (!e) {
      this.reject('bad-audit', String(payload).slice(0, 80), 'not a control event');
      return [];
    }
    const s = auditSeries(arm, e.kind);
    this.metrics.pointsProduced++;
    return [auditLine(s, e.by, e.detail, this.clock.next(s, Math.round(e.at) * 1000))];
  }

  /** A profile announcement → one `profile` point at its arrival, unless it repeats the last. */
  private profile(arm: string, payload: Uint8Array | string, arrivalMs: number): string[] {
    this.metrics.count(this.metrics.messages, 'profile');
    this.arm = arm;
    if (payload.length === 0) return []; // a retained announcement cleared
    const text = typeof payload === 'string' ? payload : Buffer.from(payload).toString('utf8');
    const r = parseAnnouncement(text);
    if (!r.ok) {
      this.reject('bad-profile', text.slice(0, 80), r.error);
      return [];
    }
    const fields = profileLine('', r.profile.name, r.profile.title, 0);
    if (this.profiles.get(arm) === fields) return [];
    this.profiles.set(arm, fields);
    const s = `profile,arm=${arm}`;
    this.metrics.pointsProduced++;
    return [profileLine(s, r.profile.name, r.profile.title, this.clock.next(s, arrivalMs * 1000))];
  }

  private reader(key: string): ReaderEntry {
    let r = this.readers.get(key);
    if (!r) {
      const reader = createReader({
        onFrame: (f) => this.frame(f, true),
        onGroup: (g) => {
          const executed = g.invalid === 0;
          for (const f of g.frames) this.frame(f, executed);
        },
        onError: (e) => this.reject(e.kind, e.text, e.message),
      });
      if (this.readers.size >= this.o.maxReaders) {
        this.readers.delete(this.readers.keys().next().value!);
        this.once?.warn(
          'readers-evicted',
          { max: this.o.maxReaders },
          'too many (arm, topic) readers: forgetting the oldest',
        );
      }
      r = { reader, servo: [], health: [], command: [] };
      this.readers.set(key, r);
    }
    return r;
  }

  private reject(reason: string, text: string, message = reason): void {
    this.metrics.count(this.metrics.rejected, reason);
    this.once?.warn(
      `rejected:${reason}`,
      { text: text.slice(0, 80), arm: this.arm },
      `dropped input: ${message}`,
    );
  }

  private frame(f: Frame, executed: boolean): void {
    this.metrics.count(this.metrics.frames, f.type);
    if (!this.onControl && this.onStatusFrames) this.statusFrames.push(f);
    const allowed = FRAME_TOPICS[f.type];
    if (!(this.onControl ? allowed.control : allowed.status)) {
      this.reject(
        'wrong-direction',
        f.type,
        `${f.type} frame on a ${this.onControl ? 'control' : 'status'} topic`,
      );
      return;
    }
    const ms = f.time ?? this.arrival;
    // A stamped report received twice is one report (SeriesClock); unstamped ones are not.
    const stamped = f.time !== undefined;
    const arm = this.arm;
    const names = this.entry!;
    switch (f.type) {
      case 'position':
        return this.point(this.servo(names, f.id), ms, stamped, positionFields(f.pwm));
      case 'angle':
        return this.point(this.servo(names, f.id), ms, stamped, angleFields(f));
      case 'health': {
        const series = this.servo(names, f.id);
        const clock = (names.health[f.id] ??= healthClock(series));
        return this.point(series, ms, stamped, healthFields(f), clock);
      }
      case 'move':
        if (!executed) return void this.metrics.count(this.metrics.rejected, 'group-not-executed');
        return this.point(this.command(names, f.id), ms, stamped, commandFields(f));
      case 'angleMove':
        if (!executed) return void this.metrics.count(this.metrics.rejected, 'group-not-executed');
        return this.point(this.command(names, f.id), ms, stamped, angleCommandFields(f));
      case 'kms': {
        this.flushPendingKms(arm);
        this.pendingKms.set(arm, { ...f, at: ms });
        return;
      }
      case 'kmsResult': {
        const req = this.pendingKms.get(arm);
        this.pendingKms.delete(arm);
        return this.point(ikSeries(arm), ms, stamped, ikFields(f.code, req));
      }
      case 'ping':
      case 'time':
      case 'controllerError':
      case 'readPosition':
      case 'readHealth':
      case 'stop':
        return; // counted only
      default:
        return unhandled(f);
    }
  }

  /** The servo series of servo `id` of the message's arm (made once per reader). */
  private servo(names: ReaderEntry, id: number): string {
    return (names.servo[id] ??= servoSeries(this.arm, id));
  }

  /** The command series, with its author's tag (user names need no line-protocol escaping). */
  private command(names: ReaderEntry, id: number): string {
    return (names.command[id] ??= this.author
      ? `${commandSeries(this.arm, id)},user=${this.author}`
      : commandSeries(this.arm, id));
  }

  /**
   * One point of `series` with its `fields`, at the report's time `ms` as its `clock` (the
   * series', or its kind's: points.ts healthClock, still one series a clock) places it. For a
   * `stamped` report (its own `$TIM`) the fields tell the clock the same report received again
   * (points.ts SeriesClock: it keeps each clock's points apart, so the fields alone say a repeat,
   * and the line is built once).
   */
  private point(
    series: string,
    ms: number,
    stamped: boolean,
    fields: string,
    clock = series,
  ): void {
    const at = this.clock.next(clock, ms * 1000, stamped ? fields : '');
    this.out.push(`${series} ${fields} ${at}`);
  }

  /** Writes an unanswered request alone (no code). */
  private flushPendingKms(arm: string): void {
    const req = this.pendingKms.get(arm);
    if (!req) return;
    this.pendingKms.delete(arm);
    const s = ikSeries(arm);
    this.out.push(`${s} ${ikFields(undefined, req)} ${this.clock.next(s, req.at * 1000)}`);
  }
}

/** A status or control topic (plain, or a user's own control topic); null for anything else. */
function frameTopic(topic: string): TopicInfo | null {
  const byUser = parseUserTopic(topic);
  if (byUser?.kind === 'control') {
    const { armId: arm, user: author } = byUser;
    return { key: `control/${arm}/${author}`, arm, kind: 'control', author };
  }
  const parsed = parseTopic(topic);
  if (!parsed || (parsed.kind !== 'status' && parsed.kind !== 'control')) return null;
  return {
    key: `${parsed.kind}/${parsed.armId}`,
    arm: parsed.armId,
    kind: parsed.kind,
    author: '',
  };
}

/** A payload's bytes as text, one character per byte (Node's own conversion, not a loop). */
const latin1 = (bytes: Uint8Array): string =>
  Buffer.from(bytes.buffer, bytes.byteOffset, bytes.length).toString('latin1');
