/**
 * Issue 20 item 2, early warnings kept (docs/protocol.md § A thermal model of each servo): `armtwin sim` on real
 * Mosquitto, the middleware storing in a real InfluxDB 1.8. A servo stalls against a jam; the
 * middleware's thermal watch publishes one early warning on `arm/{id}/alert` for that servo,
 * long before 60 °C, and the same event is in the arm's log, read back through
 * `/history/audit` as an operator looking back would.
 */
import mqtt, { type MqttClient } from 'mqtt';
import { afterAll, describe, expect, test } from 'vitest';
import type { AuditAnswer } from '@armtwin/api';
import { encodeMove, TEMP_WARNING_C, US_PER_DEG } from '@armtwin/protocol';
import {
  parseThermalAlert,
  THERMAL_ALERT_BY,
  thermalAlertTopic,
  type ThermalAlert,
} from '@armtwin/thermal';
import { useInflux, useMosquitto } from '../helpers/use-services.ts';
import { useMiddlewares } from '../helpers/use-middlewares.ts';
import { armtwin, type Child } from './sim-helpers.ts';

const ARM = 'alerts1';
const broker = useMosquitto();
const influx = useInflux();
const mws = useMiddlewares('mw-alerts', () => ({ mqttUrl: broker().url, influx: influx() }));
const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));
let sim: Child | undefined;
let client: MqttClient | undefined;
afterAll(async () => {
  await client?.endAsync(true);
  await sim?.stop();
});

async function until<T>(what: string, get: () => T | undefined | Promise<T | undefined>) {
  for (let i = 0; i < 300; i++) {
    const v = await get();
    if (v !== undefined) return v;
    await sleep(100);
  }
  throw new Error(`timed out waiting for ${what}`);
}

describe('early warnings kept (sim → Mosquitto → middleware → InfluxDB 1.8)', () => {
  test(
    'a stall is warned of on arm/{id}/alert and the warning is in the history',
    { timeout: 120_000 },
    async () => {
      const mw = await mws.spawn({ env: { FLUSH_INTERVAL_MS: '500' } });
      client = await mqtt.connectAsync(broker().url, { clientId: `alerts-${process.pid}` });
      const alerts: ThermalAlert[] = [];
      let online = false;
      let hottest = 0;
      client.on('message', (topic, payload) => {
        if (topic === thermalAlertTopic(ARM)) {
          const a = parseThermalAlert(payload);
          if (a) alerts.push(a);
        } else if (topic === `arm/${ARM}/online`) online = String(payload) === '1';
        else if (topic === `arm/${ARM}/status`)
          for (const m of String(payload).matchAll(/#001T(\d{3})V/g))
            hottest = Math.max(hottest, Number(m[1]));
      });
      await client.subscribeAsync(
        [thermalAlertTopic(ARM), `arm/${ARM}/online`, `arm/${ARM}/status`],
        { qos: 1 },
      );
      sim = armtwin(['sim', '--mqtt', broker().url, '--arm', ARM]);
      await until('the sim online', () => (online ? true : undefined));
      await sleep(4000); // the watch's window fills with the arm at rest: nothing to say
      expect(alerts).toEqual([]);

      const start = Date.now();
      await client.publishAsync(`arm/${ARM}/sim`, JSON.stringify({ fault: 'stall', id: 1 }), {
        qos: 1,
      });
      await client.publishAsync(
        `arm/${ARM}/control`,
        encodeMove(1, Math.round(1500 - 30 * US_PER_DEG), 1000),
        { qos: 1 },
      );
      const warning = await until('an early warning', () =>
        alerts.find((a) => a.kind === 'thermal-warning'),
      );
      console.log(
        `stall warned of ${(warning.at - start) / 1000} s after it began, at ${warning.tempC} °C: ${warning.detail}`,
      );
      expect(warning.id).toBe('001');
      expect(warning.tempC).toBeLessThan(TEMP_WARNING_C);
      expect(warning.secondsToLimit).toBeGreaterThan(0);
      expect(warning.detail).toContain('servo 001 heats');
      expect(alerts.filter((a) => a.id !== '001')).toEqual([]);
      // Freed before it gets hot.
      await client.publishAsync(`arm/${ARM}/sim`, JSON.stringify({ fault: 'clear' }), { qos: 1 });

      // An operator looking back: the warning is in the arm's log, at its own time.
      const url = `http://127.0.0.1:${mw.port}/api/history/audit?arm=${ARM}&start=${start - 60_000}&stop=${Date.now() + 60_000}`;
      const stored = await until('the warning in the history', async () => {
        const res = await fetch(url);
        expect(res.status).toBe(200);
        const answer = (await res.json()) as AuditAnswer;
        return answer.events.find((e) => e.kind === 'thermal-warning');
      });
      expect(stored).toEqual({
        at: warning.at,
        by: THERMAL_ALERT_BY,
        kind: 'thermal-warning',
        detail: warning.detail,
      });
      expect(hottest).toBeLessThan(TEMP_WARNING_C);
    },
  );
});
