/**
 * A TCP proxy in front of a server, for dropping a browser's connection the hard way: `stall()`
 * stops forwarding in both directions and refuses new connections, WITHOUT closing the sockets
 * to the server. The server sees what a frozen page or a pulled cable looks like: silence, no
 * FIN, no MQTT DISCONNECT; only its keep-alive can notice.
 */
import net from 'node:net';
import type { AddressInfo } from 'node:net';

export interface StallProxy {
  url: string;
  port: number;
  /** Freeze every connection now and refuse new ones. */
  stall(): void;
  close(): Promise<void>;
}

export async function startStallProxy(targetPort: number, host = '127.0.0.1'): Promise<StallProxy> {
  const pairs = new Set<[net.Socket, net.Socket]>();
  let stalled = false;
  const server = net.createServer((client) => {
    client.on('error', () => {});
    if (stalled) return void client.destroy();
    const upstream = net.connect(targetPort, host);
    upstream.on('error', () => client.destroy());
    const pair: [net.Socket, net.Socket] = [client, upstream];
    pairs.add(pair);
    client.pipe(upstream);
    upstream.pipe(client);
    const forget = () => pairs.delete(pair);
    client.on('close', () => {
      if (!stalled) upstream.destroy();
      forget();
    });
    upstream.on('close', () => {
      if (!stalled) client.destroy();
    });
  });
  await new Promise<void>((resolve) => server.listen(0, host, resolve));
  const { port } = server.address() as AddressInfo;
  const all: net.Socket[] = [];
  server.on('connection', (s) => all.push(s));
  const upstreams = () => [...pairs].map(([, u]) => u);
  let held: net.Socket[] = [];
  return {
    url: `http://${host}:${port}/`,
    port,
    stall() {
      stalled = true;
      for (const [c, u] of pairs) {
        c.unpipe(u);
        u.unpipe(c);
        c.pause();
        u.pause();
      }
      held = upstreams();
    },
    close: () =>
      new Promise<void>((resolve) => {
        for (const s of [...all, ...held, ...upstreams()]) s.destroy();
        server.close(() => resolve());
      }),
  };
}
