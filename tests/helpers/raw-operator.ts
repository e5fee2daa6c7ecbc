/**
 * An operator on a raw MQTT socket, for deadman tests and the deadman benchmark: it holds
 * `arm/{id}/operator` with a retained `1` and the will `0`, stays alive with PINGREQs (and,
 * with `beatMs`, repeats its `1` as the HUD does), and on `silence()` stops sending anything
 * while leaving the TCP connection open — a frozen page or a pulled cable: no FIN, no
 * DISCONNECT, so only the broker's keep-alive or the controller's lease can notice.
 * mqtt.js is not used because it would answer for a dead client.
 */
import net from 'node:net';
import { generate } from 'mqtt-packet';

export interface RawOperatorOptions {
  host?: string;
  port: number;
  armId: string;
  keepaliveS: number;
  /** Repeat the retained `1` this often (the HUD's beat); unset: hold with a single `1`. */
  beatMs?: number;
}

export interface RawOperator {
  /** Sends one last packet (a beat, or a PINGREQ), then nothing more; returns when, in epoch ms. */
  silence(): number;
  close(): void;
}

export async function rawOperator(o: RawOperatorOptions): Promise<RawOperator> {
  const topic = `arm/${o.armId}/operator`;
  const sock = net.connect(o.port, o.host ?? '127.0.0.1');
  sock.setNoDelay(true);
  await new Promise<void>((resolve, reject) => {
    sock.once('connect', resolve);
    sock.once('error', reject);
  });
  sock.on('data', () => {});
  sock.on('error', () => {});
  sock.write(
    generate({
      cmd: 'connect',
      protocolId: 'MQTT',
      protocolVersion: 4,
      clean: true,
      clientId: `raw-operator-${o.armId}-${process.pid}-${Date.now()}`,
      keepalive: o.keepaliveS,
      will: { topic, payload: Buffer.from('0'), qos: 1, retain: true },
    }),
  );
  const hold = () =>
    sock.write(
      generate({
        cmd: 'publish',
        topic,
        payload: Buffer.from('1'),
        qos: 0,
        retain: true,
        dup: false,
      }),
    );
  const ping = () => sock.write(generate({ cmd: 'pingreq' }));
  const tick = o.beatMs ? hold : ping;
  hold();
  const timer = setInterval(tick, o.beatMs ?? Math.max(200, (o.keepaliveS * 1000) / 2));
  return {
    silence() {
      clearInterval(timer);
      tick();
      return Date.now();
    },
    close() {
      clearInterval(timer);
      sock.destroy();
    },
  };
}
