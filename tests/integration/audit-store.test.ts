/**
 * The record of who did what (issue 18): the simulated arm's own control events, published on
 * `arm/arm1/audit` when alice takes control and bob's move is refused, are stored by the
 * middleware in InfluxDB beside the arm's data and read back by the history API, in JSON and
 * CSV, on the real Mosquitto and influxd.
 */
import mqtt from 'mqtt';
import { afterAll, describe, expect, test } from 'vitest';
import type { AuditAnswer } from '@armtwin/api';
import { useInflux, useMosquitto } from '../helpers/use-services.ts';
import { useMiddlewares } from '../helpers/use-middlewares.ts';
import { waitForValue } from '../../apps/middleware/test/support/harness.ts';
import { armtwin, type Child } from './sim-helpers.ts';

const broker = useMosquitto();
const influx = useInflux();
const mws = useMiddlewares('mw-audit', () => ({ mqttUrl: broker().url, influx: influx() }));
let sim: Child | undefined;
afterAll(async () => {
  await sim?.stop();
});

describe('control events → InfluxDB → /history/audit', () => {
  test("the arm's control events come back in order, as JSON and CSV: control taken, a refused move, an emergency stop and who set the arm going again", async () => {
    const mw = await mws.spawn({ env: { FLUSH_INTERVAL_MS: '200' } });
    sim = armtwin(['sim', '--arm', 'audit1', '--mqtt', broker().url]);
    const client = await mqtt.connectAsync(broker().url, { clientId: `audit-${process.pid}` });
    await client.subscribeAsync('arm/audit1/online', { qos: 1 });
    await new Promise<void>((resolve) =>
      client.on('message', (t, m) => t === 'arm/audit1/online' && String(m) === '1' && resolve()),
    );
    const start = Date.now() - 1000;
    // The demo has no users file: alice's name is her own claim (SECURITY.md).
    await client.publishAsync('arm/audit1/claim/alice', 'take', { qos: 1 });
    await client.publishAsync('arm/audit1/control/bob', '#000P2000T500!', { qos: 1 });
    const url = `http://127.0.0.1:${mw.port}/api/history/audit?arm=audit1&start=${start}&stop=${Date.now() + 60_000}`;
    const kinds = await waitForValue(
      async () => {
        const res = await fetch(url);
        const body = (await res.json()) as AuditAnswer;
        return (body.events ?? []).map((e) => `${e.kind} by ${e.by}`).join('; ');
      },
      'taken by alice; refused-command by bob',
      20_000,
    );
    expect(kinds).toBe('taken by alice; refused-command by bob');
    const csv = await (await fetch(`${url}&format=csv`)).text();
    const lines = csv.trim().split('\n');
    expect(lines[0]).toBe('time,by,kind,detail');
    expect(lines.slice(1).map((l) => l.split(',').slice(1, 3).join(','))).toEqual([
      'alice,taken',
      'bob,refused-command',
    ]);
    // An emergency stop and the move that sets the arm going again are recorded with their senders.
    await client.publishAsync('arm/audit1/control', '#255PDST!', { qos: 1 });
    await client.publishAsync('arm/audit1/claim/alice', 'release', { qos: 1 });
    await client.publishAsync('arm/audit1/control/carol', '#000P1600T500!', { qos: 1 });
    const later = await waitForValue(
      async () => {
        const body = (await (await fetch(url)).json()) as AuditAnswer;
        return body.events
          .slice(2)
          .map((e) => `${e.kind} by ${e.by}`)
          .join('; ');
      },
      'e-stop by ; released by alice; e-stop-released by carol',
      20_000,
    );
    expect(later).toBe('e-stop by ; released by alice; e-stop-released by carol');
    await client.endAsync();
  });
});
