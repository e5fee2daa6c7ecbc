import { describe, expect, test } from 'vitest';
import { Ingest } from '../src/ingest.ts';
import { Metrics } from '../src/metrics.ts';

const T = 1_700_000_000_000; // a $TIM stamp, ms
const setup = () => {
  const metrics = new Metrics();
  return { metrics, ingest: new Ingest(metrics) };
};

describe('angle frames → points (PROTOCOL §8: the angle field of §6, no pwm)', () => {
  test('an angle report becomes a servo point with angle and no pwm', () => {
    const { ingest } = setup();
    expect(ingest.handle('arm/arm1/status', `$TIM:${T}!#003A-012.50!#001A+350.00!`, 5)).toEqual([
      `servo,arm=arm1,id=003 angle=-12.5 ${T * 1000}`,
      `servo,arm=arm1,id=001 angle=350 ${T * 1000}`,
    ]);
  });

  test('an angle move on control becomes a command point with angle and ms, no pwm', () => {
    const { ingest } = setup();
    expect(ingest.handle('arm/arm1/control', `$TIM:${T}!#001A+270.00T1000!`, 5)).toEqual([
      `command,arm=arm1,id=001 angle=270,ms=1000i ${T * 1000}`,
    ]);
  });

  test('angle and pulse frames mix in one group and one message', () => {
    const { ingest } = setup();
    expect(ingest.handle('arm/arm1/status', '{#000P1500!#001A-359.99!}#002T045V7400!', 7)).toEqual([
      'servo,arm=arm1,id=000 pwm=1500i,angle=0 7000',
      'servo,arm=arm1,id=001 angle=-359.99 7000',
      'servo,arm=arm1,id=002 temp=45,volt=7.4 7000',
    ]);
  });

  test('an angle frame split across messages is joined; an out-of-range one is counted, not stored', () => {
    const { ingest, metrics } = setup();
    expect(ingest.handle('arm/arm1/status', '#001A+12', 1)).toEqual([]);
    expect(ingest.handle('arm/arm1/status', '3.45!#001A+1000.00!', 2)).toEqual([
      'servo,arm=arm1,id=001 angle=123.45 2000',
    ]);
    expect(metrics.rejected).toEqual({ 'out-of-range': 1 });
  });

  test('a group of angle moves with one bad frame is not stored; a report on control is refused', () => {
    const { ingest, metrics } = setup();
    expect(ingest.handle('arm/arm1/control', '{#000A+010.00T0500!#001AXT0500!}', 1)).toEqual([]);
    expect(ingest.handle('arm/arm1/control', '#001A+010.00!', 1)).toEqual([]);
    expect(metrics.rejected).toMatchObject({
      malformed: 1,
      'group-not-executed': 1,
      'wrong-direction': 1,
    });
  });
});
