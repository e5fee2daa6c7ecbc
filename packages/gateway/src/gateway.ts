/**
 * The edge gateway's logic, without sockets: serial bytes → protocol reader → frames
 * re-encoded into one `$TIM`-stamped status payload per serial chunk (groups stay groups);
 * control payloads → the serial line verbatim; presence `1` only while the serial line is open
 * and the broker connected. The deadman: the operator's `0`, or a beating operator whose lease
 * ran out (`OperatorWatch`), writes `#255PDST!`. The publish and write functions, the clock and
 * the timers are injected.
 */
import {
  armTopics,
  createReader,
  encodeControllerError,
  encodeFrame,
  encodeTime,
  OPERATOR_LEASE_MS,
  OperatorWatch,
  type Frame,
  type OperatorTimers,
} from '@armtwin/protocol';

export interface GatewayIo extends OperatorTimers {
  publish(topic: string, payload: Buffer | string, opts: { qos: 0 | 1; retain: boolean }): void;
  /** Writes to the serial line; false when it is not open. */
  write(data: Buffer): boolean;
  /** Unix epoch ms. */
  now(): number;
  /** Told the first time each kind of problem happens. */
  onFirst(kind: string, message: string): void;
}

export class GatewayCore {
  readonly counters = {
    serialChunks: 0,
    statusPayloads: 0,
    frames: 0,
    groups: 0,
    deviceStamps: 0,
    rejected: {} as Record<string, number>,
    controlWritten: 0,
    controlDropped: 0,
    /** `#255PDST!` written because the operator let go or its lease lapsed (the deadman). */
    deadmanStops: 0,
  };
  readonly operator: OperatorWatch;
  private readonly topics;
  private readonly pieces: string[] = [];
  private readonly reader;
  private serialOpen = false;
  private brokerUp = false;

  constructor(
    armId: string,
    private readonly io: GatewayIo,
    operatorLeaseMs = OPERATOR_LEASE_MS,
  ) {
    this.topics = armTopics(armId);
    this.operator = new OperatorWatch(
      io,
      (reason) => {
        if (!this.io.write(Buffer.from('#255PDST!'))) return;
        this.counters.deadmanStops++;
        if (reason === 'lapsed')
          io.onFirst('deadman:lapsed', 'operator stopped beating: #255PDST! written');
      },
      operatorLeaseMs,
    );
    this.reader = createReader({
      onFrame: (frame) => {
        // The device's own `$TIM` (if any) is not epoch time we trust: the gateway stamps.
        if (frame.type === 'time') this.counters.deviceStamps++;
        else this.add(frame);
      },
      onGroup: (group) => {
        const inner: string[] = [];
        for (const f of group.frames) {
          const text = this.encode(f);
          if (text) inner.push(text);
        }
        if (inner.length === 0) return;
        this.counters.groups++;
        this.pieces.push(`{${inner.join('')}}`);
      },
      onError: (error) => {
        const n = (this.counters.rejected[error.kind] =
          (this.counters.rejected[error.kind] ?? 0) + 1);
        if (n === 1) io.onFirst(`serial:${error.kind}`, `serial input dropped: ${error.message}`);
      },
    });
  }

  private encode(frame: Frame): string {
    try {
      this.counters.frames++;
      const { time: _time, ...bare } = frame;
      return encodeFrame(bare as Frame);
    } catch {
      return '';
    }
  }

  private add(frame: Frame): void {
    const text = this.encode(frame);
    if (text) this.pieces.push(text);
  }

  /** A chunk from the serial line: everything it completes goes out as one payload. */
  fromSerial(chunk: Buffer): void {
    this.counters.serialChunks++;
    this.reader.feed(chunk);
    if (this.pieces.length === 0) return;
    const payload = encodeTime(Math.round(this.io.now())) + this.pieces.join('');
    this.pieces.length = 0;
    this.counters.statusPayloads++;
    this.io.publish(this.topics.status, payload, { qos: 0, retain: false });
  }

  /**
   * The deadman: a `0` on `arm/{id}/operator` — the operator let go or its last will fired, or
   * no operator holds the arm when the gateway (re)connects — or a beating operator's lease
   * running out writes `#255PDST!` to the controller. The gateway cannot tell whether the arm
   * moves, so it always stops it; a stop at rest changes nothing.
   */
  fromOperator(payload: Buffer): void {
    this.operator.receive(payload);
  }

  /** A control payload: written verbatim, or refused with `$ERR` on status when the line is down. */
  fromControl(payload: Buffer): void {
    if (this.io.write(payload)) {
      this.counters.controlWritten++;
      return;
    }
    this.counters.controlDropped++;
    if (this.counters.controlDropped === 1)
      this.io.onFirst('control-dropped', 'serial line down: control payloads dropped');
    const err =
      encodeTime(Math.round(this.io.now())) + encodeControllerError('gateway: serial line down');
    this.io.publish(this.topics.status, err, { qos: 0, retain: false });
  }

  serialOpened(): void {
    this.reader.reset();
    this.serialOpen = true;
    this.presence();
  }

  serialClosed(): void {
    this.reader.reset();
    this.serialOpen = false;
    this.presence();
  }

  brokerConnected(connected: boolean): void {
    this.brokerUp = connected;
    if (connected) this.presence();
  }

  private presence(): void {
    if (!this.brokerUp) return;
    this.io.publish(this.topics.online, this.serialOpen ? '1' : '0', { qos: 1, retain: true });
  }
}
