/**
 * The servo doctor on a serial line (`armtwin gateway --bus … --doctor`, and the same checks
 * before every bus gateway start): the scan and findings of `@armtwin/servo-bus` over a
 * serial port opened at each baud rate in turn, and the report in plain words.
 */
import {
  DYNAMIXEL_BAUD_RATES,
  FEETECH_BAUD_RATES,
  countFindings,
  diagnoseBus,
  scanBus,
  type BusProtocol,
  type BusScan,
  type DoctorLink,
  type Finding,
} from '@armtwin/servo-bus';
import { openSerialPort, type OpenPort, type PortLike } from './serial-link.ts';

/** Margin on each answer's wire time, ms: USB adapters' latency, a loaded machine. */
export const DOCTOR_MARGIN_MS = 150;

export interface BusDoctorOptions {
  bus: BusProtocol;
  serialPath: string;
  /** The rate the gateway uses: tried first. */
  baudRate: number;
  /** The profile's servo ids. */
  ids: readonly number[];
  /** Every baud rate the servos know (`--doctor`), or only `baudRate` (at start). */
  allBauds: boolean;
  openPort?: OpenPort;
}

export interface BusDoctorReport {
  scan: BusScan;
  findings: Finding[];
  counts: ReturnType<typeof countFindings>;
}

/** A serial port as the doctor's line; `close()` when done. */
export function serialDoctorLink(
  path: string,
  openPort: OpenPort = openSerialPort,
): DoctorLink & { close(): Promise<void> } {
  let port: PortLike | undefined;
  let incoming: Buffer[] = [];
  let wake: (() => void) | undefined;
  const close = () =>
    new Promise<void>((resolve) => {
      const p = port;
      port = undefined;
      if (!p?.isOpen) return resolve();
      p.removeAllListeners();
      p.close(() => resolve());
    });
  return {
    async setBaud(baud) {
      await close();
      const p = openPort(path, baud);
      await new Promise<void>((resolve, reject) =>
        p.open((err) => (err ? reject(err) : resolve())),
      );
      p.on('data', (chunk) => {
        incoming.push(chunk);
        wake?.();
      });
      p.on('error', () => undefined);
      port = p;
    },
    async exchange(bytes, ms, expectBytes) {
      incoming = [];
      port?.write(Buffer.from(bytes));
      const have = () => incoming.reduce((n, c) => n + c.length, 0);
      await new Promise<void>((resolve) => {
        const timer = setTimeout(done, ms);
        function done() {
          clearTimeout(timer);
          wake = undefined;
          resolve();
        }
        wake = () => {
          if (expectBytes && have() >= expectBytes) done();
        };
      });
      return new Uint8Array(Buffer.concat(incoming));
    },
    close,
  };
}

/** The rates to try: the gateway's first, then the others the servos can be set to. */
export function doctorBauds(bus: BusProtocol, baudRate: number, all: boolean): number[] {
  if (!all) return [baudRate];
  const table = bus === 'feetech' ? FEETECH_BAUD_RATES : DYNAMIXEL_BAUD_RATES;
  return [baudRate, ...Object.values(table).filter((b) => b !== baudRate)];
}

export async function runBusDoctor(o: BusDoctorOptions): Promise<BusDoctorReport> {
  const link = serialDoctorLink(o.serialPath, o.openPort);
  try {
    const scan = await scanBus(link, {
      protocol: o.bus,
      bauds: doctorBauds(o.bus, o.baudRate, o.allBauds),
      ids: o.ids,
      stopAtFirst: !o.allBauds,
      searchAll: o.allBauds,
      marginMs: DOCTOR_MARGIN_MS,
    });
    const findings = diagnoseBus(scan, { baud: o.baudRate, ids: o.ids });
    return { scan, findings, counts: countFindings(findings) };
  } finally {
    await link.close();
  }
}

/** The report as a person reads it: what answered, then each finding and its fix. */
export function formatDoctorReport(r: BusDoctorReport): string {
  const lines: string[] = [];
  for (const b of r.scan.bauds)
    if (b.found.length || b.garbled.length)
      lines.push(
        `${b.baud} baud: ${b.found.length ? `servos ${b.found.join(', ')}` : 'no clean answer'}${b.garbled.length ? `; garbled answers from ${b.garbled.join(', ')}` : ''}`,
      );
  for (const s of r.scan.servos)
    lines.push(
      `  servo ${s.id}: model ${s.modelNumber}, firmware ${s.firmware}, ${s.voltageV.toFixed(1)} V (made for ${s.minVoltageV.toFixed(1)}–${s.maxVoltageV.toFixed(1)} V), ${s.temperatureC} °C, position ${s.position}${s.problems.length ? `, flags: ${s.problems.join(', ')}` : ''}`,
    );
  if (r.findings.length === 0) lines.push('no problem found');
  for (const f of r.findings)
    lines.push(
      `${f.severity === 'error' ? 'ERROR' : 'warning'} [${f.kind}] ${f.finding}`,
      `  fix: ${f.fix}`,
    );
  return `${lines.join('\n')}\n`;
}
