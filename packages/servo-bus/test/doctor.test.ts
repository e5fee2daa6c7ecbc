/**
 * The servo doctor against the emulated bus, one injected fault at a time: each gives its
 * finding (and a healthy SO-101 bus none), through the real bus client and emulated servos.
 */
import { describe, expect, test } from 'vitest';
import {
  createEmulatedBus,
  diagnoseBus,
  emulatedDoctorLink,
  scanBus,
  type EmulatedServoSpec,
  type Finding,
} from '../src/index.ts';

const IDS = [1, 2, 3, 4, 5, 6];
const FEETECH_BAUDS = [1_000_000, 500_000, 250_000, 115_200];
const arm = (change: (s: EmulatedServoSpec) => EmulatedServoSpec = (s) => s) =>
  IDS.map((id) => change({ id }));

async function doctor(
  servos: EmulatedServoSpec[],
  o: { idClash?: 'collide'; full?: boolean } = {},
): Promise<Finding[]> {
  const bus = createEmulatedBus({ protocol: 'feetech', servos, idClash: o.idClash ?? 'refuse' });
  const scan = await scanBus(emulatedDoctorLink(bus), {
    protocol: 'feetech',
    bauds: FEETECH_BAUDS,
    ...(o.full ? { stopAtFirst: false } : { ids: IDS }),
  });
  return diagnoseBus(scan, { baud: 1_000_000, ids: IDS });
}
const kinds = (f: Finding[]) => f.map((x) => x.kind);

describe('the servo doctor on an emulated Feetech bus', () => {
  test('a healthy SO-101 bus: no finding', async () => {
    expect(await doctor(arm())).toEqual([]);
  });

  test('nothing on the line: no servos, with what to check', async () => {
    const f = await doctor([]);
    expect(kinds(f)).toEqual(['no-servos']);
    expect(f[0]!.fix).toMatch(/supply/);
  });

  test('servos at another baud rate: found there, and the flag to use', async () => {
    const f = await doctor(arm((s) => ({ ...s, fields: { baudRate: 1 } })));
    expect(kinds(f)).toEqual(['baud']);
    expect(f[0]).toMatchObject({ ids: IDS });
    expect(f[0]!.fix).toMatch(/--baud 500000/);
  });

  test('two servos with one id: a garbled answer (Incorrect status packet)', async () => {
    const f = await doctor([...arm(), { id: 3 }], { idClash: 'collide' });
    expect(kinds(f)).toEqual(['garbled']);
    expect(f[0]).toMatchObject({ ids: [3] });
    expect(f[0]!.finding).toMatch(/Incorrect status packet/);
  });

  test('a servo missing and a new one at id 1 elsewhere: missing and extra, with the fix', async () => {
    const servos = arm().filter((s) => s.id !== 4);
    servos.push({ id: 9 });
    const f = await doctor(servos);
    expect(kinds(f)).toEqual(['missing', 'extra']);
    expect(f[0]!.ids).toEqual([4]);
    expect(f[1]!.ids).toEqual([9]);
    expect(f[1]!.fix).toMatch(/missing ids \(4\)/);
  });

  test('another model and another firmware', async () => {
    const f = await doctor(
      arm((s) =>
        s.id === 2 ? { ...s, fields: { modelNumber: 1284, firmwareMinorVersion: 9 } } : s,
      ),
    );
    expect(kinds(f)).toEqual(['model', 'firmware']);
    expect(f[0]!.ids).toEqual([2]);
    expect(f[1]!.finding).toMatch(
      /3\.9 on 2; 3\.10 on 1, 3, 4, 5, 6|3\.10 on 1, 3, 4, 5, 6; 3\.9 on 2/,
    );
  });

  test('7.4 V servos on a 12 V supply: Input voltage error, switch it off', async () => {
    const f = await doctor(arm((s) => ({ ...s, voltageV: 12.1, fields: { maxVoltageLimit: 80 } })));
    expect(kinds(f)).toEqual(['voltage-variant']);
    expect(f[0]!.finding).toMatch(/12\.1 V .* at most 8\.0 V \("Input voltage error"/);
    expect(f[0]!.fix).toMatch(/switch the supply off/);
  });

  test('a weak supply, and one 7.4 V servo among 12 V ones', async () => {
    const weak = await doctor(arm((s) => ({ ...s, voltageV: 3.5 })));
    expect(kinds(weak)).toEqual(['undervoltage']);
    const mixed = await doctor(
      arm((s) => (s.id === 6 ? { ...s, fields: { maxVoltageLimit: 80 } } : s)),
    );
    expect(kinds(mixed)).toEqual(['mixed-variants']);
  });

  test('overheating and overload flags', async () => {
    const f = await doctor(
      arm((s) =>
        s.id === 5
          ? { ...s, temperatureC: 75 }
          : s.id === 2
            ? { ...s, fields: { status: 0x20 } }
            : s,
      ),
    );
    expect(kinds(f)).toEqual(['overheat', 'overload']);
    expect(f[0]!.ids).toEqual([5]);
    expect(f[1]!.ids).toEqual([2]);
  });

  test('a shaft at the encoder wrap: the calibration overflow warning', async () => {
    const f = await doctor(arm((s) => (s.id === 3 ? { ...s, position: 4090 } : s)));
    expect(kinds(f)).toEqual(['calibration-overflow']);
    expect(f[0]!.finding).toMatch(/tick 4090 of 4096.*lerobot#1296/);
  });

  test('a full scan (every id, every rate) finds servos split across two rates', async () => {
    const f = await doctor(
      arm((s) => (s.id > 3 ? { ...s, fields: { baudRate: 4 } } : s)),
      { full: true },
    );
    expect(kinds(f)).toEqual(['baud']);
    expect(f[0]).toMatchObject({ ids: [4, 5, 6] });
    expect(f[0]!.fix).toMatch(/--baud 115200/);
  });
});

describe('the servo doctor on an emulated Dynamixel bus', () => {
  /** At 1 Mbps (Baud Rate 3): an X-series servo leaves the factory at 57600. */
  const fast = (s: EmulatedServoSpec): EmulatedServoSpec => ({
    ...s,
    fields: { baudRate: 3, ...s.fields },
  });
  const scanDxl = async (servos: EmulatedServoSpec[]) => {
    const bus = createEmulatedBus({ protocol: 'dynamixel', servos });
    const scan = await scanBus(emulatedDoctorLink(bus), {
      protocol: 'dynamixel',
      bauds: [1_000_000, 57_600],
      ids: IDS,
    });
    return { scan, findings: diagnoseBus(scan, { baud: 1_000_000, ids: IDS }) };
  };

  test('a healthy Koch-like bus: described, no finding', async () => {
    const { scan, findings } = await scanDxl(arm(fast));
    expect(findings).toEqual([]);
    expect(scan.servos[0]).toMatchObject({ id: 1, modelNumber: 1020, voltageV: 12 });
  });

  test('an overload in Hardware Error Status, and a servo at 57600 baud', async () => {
    const { findings } = await scanDxl(
      arm((s) => fast(s.id === 2 ? { ...s, fields: { hardwareErrorStatus: 0x20 } } : s)),
    );
    expect(kinds(findings)).toEqual(['overload']);
    const slow = await scanDxl(arm()); // the factory's 57600
    expect(kinds(slow.findings)).toEqual(['baud']);
    expect(slow.findings[0]!.fix).toMatch(/--baud 57600/);
  });
});
