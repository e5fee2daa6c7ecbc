/**
 * The two real Foxglove clients the tests drive: npm `@foxglove/ws-protocol`'s FoxgloveClient
 * (foxglove.websocket.v1, what Lichtblick speaks) on a `ws` socket, and a Python
 * foxglove.sdk.v1 client on `websockets` in the cached venv (scripts/pyenv-foxglove.sh,
 * tests/helpers/foxglove/sdk_client.py). Missing venv is an error, not a skip.
 */
import { execFile } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { FoxgloveClient } from '@armtwin/foxglove/ws-protocol';
import {
  type Channel,
  type MessageData,
  type Service,
  type ServiceCallFailure,
  type ServiceCallResponse,
  type StatusMessage,
} from '@foxglove/ws-protocol';
import WebSocket from 'ws';
import { armtwinCacheDir } from '@armtwin/ros2';
import { REPO_ROOT } from './services.ts';

export interface Received {
  ns: bigint;
  body: Record<string, unknown>;
}

const basic = (user: string) => `Basic ${Buffer.from(`${user}:${user}-demo`).toString('base64')}`;

/** A connected npm FoxgloveClient, with what the server advertised and sent. */
export class NpmFoxglove {
  readonly channels = new Map<string, Channel>();
  readonly services = new Map<string, Service>();
  readonly statuses: StatusMessage[] = [];
  private readonly received = new Map<number, Received[]>();
  private readonly bySub = new Map<number, number>();
  private waiters: (() => void)[] = [];
  private nextCall = 1;
  private readonly answers = new Map<number, ServiceCallResponse | ServiceCallFailure>();

  private constructor(
    readonly client: FoxgloveClient,
    readonly ws: WebSocket,
  ) {
    client.on('advertise', (cs) => {
      for (const c of cs) this.channels.set(c.topic, c);
      this.wake();
    });
    client.on('advertiseServices', (ss) => {
      for (const s of ss) this.services.set(s.name, s);
      this.wake();
    });
    client.on('status', (s) => {
      this.statuses.push(s);
      this.wake();
    });
    client.on('message', (m: MessageData) => {
      const channelId = this.bySub.get(m.subscriptionId);
      if (channelId === undefined) return;
      const body = JSON.parse(new TextDecoder().decode(m.data)) as Record<string, unknown>;
      this.received.get(channelId)!.push({ ns: m.timestamp, body });
      this.wake();
    });
    const answer = (r: ServiceCallResponse | ServiceCallFailure) => {
      this.answers.set(r.callId, r);
      this.wake();
    };
    client.on('serviceCallResponse', answer);
    client.on('serviceCallFailure', answer);
  }

  /** Connects offering only foxglove.websocket.v1, as `user` (password `<user>-demo`) if given. */
  static connect(url: string, user?: string): Promise<NpmFoxglove> {
    const ws = new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL], {
      headers: user ? { authorization: basic(user) } : {},
    });
    const fox = new NpmFoxglove(new FoxgloveClient({ ws: ws as never }), ws);
    return new Promise((resolve, reject) => {
      ws.once('open', () => resolve(fox));
      ws.once('unexpected-response', (_req, res) =>
        reject(new Error(`upgrade refused: ${res.statusCode} ${res.statusMessage}`)),
      );
      ws.once('error', reject);
    });
  }

  private wake() {
    const w = this.waiters;
    this.waiters = [];
    for (const f of w) f();
  }

  async until<T>(test: () => T | undefined | false, what: string, timeoutMs = 15_000): Promise<T> {
    const deadline = Date.now() + timeoutMs;
    for (;;) {
      const v = test();
      if (v !== undefined && v !== false) return v;
      if (Date.now() > deadline) throw new Error(`timed out waiting for ${what}`);
      await new Promise<void>((r) => {
        this.waiters.push(r);
        setTimeout(r, 200);
      });
    }
  }

  /** Subscribes to `topic` (advertised); its messages collect from now on. */
  async subscribe(topic: string): Promise<Received[]> {
    const channel = await this.until(() => this.channels.get(topic), `channel ${topic}`);
    const list: Received[] = [];
    this.received.set(channel.id, list);
    this.bySub.set(this.client.subscribe(channel.id), channel.id);
    return list;
  }

  /** Calls a std_srvs/Trigger-like service; its JSON answer, or the failure's message. */
  async call(name: string): Promise<{ ok: boolean; body: string }> {
    const service = await this.until(() => this.services.get(name), `service ${name}`);
    const callId = this.nextCall++;
    this.client.sendServiceCallRequest({
      serviceId: service.id,
      callId,
      encoding: 'json',
      data: new DataView(new TextEncoder().encode('{}').buffer),
    });
    const a = await this.until(() => this.answers.get(callId), `answer of ${name}`);
    return 'message' in a
      ? { ok: false, body: a.message }
      : { ok: true, body: new TextDecoder().decode(a.data) };
  }

  /** Advertises `topic` (JSON) and publishes `message` on it. */
  publish(topic: string, message: unknown): void {
    const id = this.client.advertise({ topic, encoding: 'json', schemaName: topic });
    this.client.sendMessage(id, new TextEncoder().encode(JSON.stringify(message)));
  }

  close(): void {
    this.client.close();
  }
}

export const foxgloveVenvPython = (): string => {
  const python = path.join(armtwinCacheDir(process.env), 'pyenv-foxglove', 'bin', 'python');
  if (!fs.existsSync(python))
    throw new Error(`no Foxglove venv (${python}): run \`bash scripts/install-deps.sh\``);
  return python;
};

export interface SdkClientResult {
  protocol: string;
  serverInfo: { name: string; capabilities: string[] };
  channels: string[];
  messages: Record<string, { ns: string; body: Record<string, unknown> }[]>;
}

/** Runs the Python foxglove.sdk.v1 client: the first `count` messages of each topic. */
export function sdkClient(
  url: string,
  user: string | undefined,
  topics: Record<string, number>,
): Promise<SdkClientResult> {
  const input = JSON.stringify({
    url,
    ...(user ? { user, password: `${user}-demo` } : {}),
    topics,
    timeout: 30,
  });
  return new Promise((resolve, reject) => {
    const child = execFile(
      foxgloveVenvPython(),
      [path.join(REPO_ROOT, 'tests', 'helpers', 'foxglove', 'sdk_client.py')],
      { maxBuffer: 64 << 20 },
      (err, stdout, stderr) =>
        err
          ? reject(new Error(`sdk_client.py: ${stderr || err.message}`))
          : resolve(JSON.parse(stdout) as SdkClientResult),
    );
    child.stdin!.end(input);
  });
}
