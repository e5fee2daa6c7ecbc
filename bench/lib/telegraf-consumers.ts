/**
 * The two consumers the Telegraf section compares (bench/telegraf.ts), each started for one
 * message shape: Telegraf's `mqtt_consumer` (grok for single frames; the `value` parser and a
 * Starlark split for 6-servo groups) and armtwin's middleware, both into the same InfluxDB with
 * batches of 1,000 points flushed every second.
 */
import fs from 'node:fs';
import path from 'node:path';
import { REPO, startMiddleware } from './stack.ts';
import { spawnChild, until, type Child } from './proc.ts';
import type { BenchContext } from './types.ts';

export const TELEGRAF = path.join(REPO, '.tools', 'bin', 'telegraf');
export const FLUSH_MS = 1000;
export const BATCH = 1000;

export interface Consumer {
  name: string;
  /** Arm id prefix: the consumer stores under `<prefix>-<rate>`. */
  prefix: string;
  pid: number;
  stop(): Promise<void>;
}

/** What each message holds: one stamped frame, or a 6-servo group (the publisher's shapes). */
export type Shape = 'frame' | 'group';
export const FRAMES_PER_MESSAGE: Record<Shape, number> = { frame: 1, group: 6 };

/** Telegraf's parsing of each shape (inside `[[inputs.mqtt_consumer]]`), and any processor. */
const PARSING: Record<Shape, string> = {
  frame: `  data_format = "grok"
  grok_patterns = ['\\$TIM:%{NUMBER:time:ts-epochmilli}!#%{NUMBER:id:tag}P%{NUMBER:pwm:int}!']`,
  group: `  data_format = "value"
  data_type = "string"`,
};
const PROCESSORS: Record<Shape, string> = {
  frame: '',
  group: `
[[processors.starlark]]
  source = '''
def apply(metric):
    text = metric.fields["value"]
    head, _, body = text.partition("!")
    ns = int(head[5:]) * 1000000
    out = []
    for frame in body.strip("{}").split("!"):
        if len(frame) < 6:
            continue
        m = Metric("servo")
        m.tags["arm"] = metric.tags["arm"]
        m.tags["id"] = frame[1:4]
        m.fields["pwm"] = int(frame[5:])
        m.time = ns
        out.append(m)
    return out
'''
`,
};

/** Telegraf's configuration: every `arm/<id>/status` message, the arm from the topic. */
function telegrafConf(ctx: BenchContext, shape: Shape): string {
  const mqtt = new URL(ctx.broker.url);
  return `[agent]
  interval = "1s"
  flush_interval = "${FLUSH_MS / 1000}s"
  flush_jitter = "0s"
  metric_batch_size = ${BATCH}
  metric_buffer_limit = 10000000
  omit_hostname = true

[[inputs.mqtt_consumer]]
  servers = ["tcp://${mqtt.hostname}:${mqtt.port}"]
  topics = ["arm/+/status"]
  qos = 1
  client_id = "bench-telegraf-${process.pid}"
  topic_tag = ""
${PARSING[shape]}
  name_override = "servo"
  [[inputs.mqtt_consumer.topic_parsing]]
    topic = "arm/+/status"
    tags = "_/arm/_"
${PROCESSORS[shape]}
[[outputs.influxdb]]
  urls = ["${ctx.influx.url}"]
  database = "${ctx.influx.db}"
  skip_database_creation = true
  timeout = "10s"
`;
}

export async function startTelegraf(ctx: BenchContext, shape: Shape): Promise<Consumer> {
  const conf = path.join(ctx.logDir, `telegraf-${shape}.conf`);
  fs.writeFileSync(conf, telegrafConf(ctx, shape));
  const log = path.join(ctx.logDir, `telegraf-${shape}.log`);
  const child: Child = spawnChild(TELEGRAF, ['--config', conf], { logFile: log });
  // Ready once its MQTT client is subscribed (it logs "Connected").
  const ok = await until(
    async () => fs.existsSync(log) && /Connected \[tcp:/.test(fs.readFileSync(log, 'utf8')),
    30_000,
    100,
  );
  if (!ok) {
    await child.stop();
    throw new Error(`telegraf did not connect (log: ${log})`);
  }
  return { name: 'Telegraf', prefix: `tg${shape[0]}`, pid: child.pid, stop: () => child.stop() };
}

export async function startArmtwin(ctx: BenchContext, shape: Shape): Promise<Consumer> {
  const mw = await startMiddleware(
    {
      MQTT_URL: ctx.broker.url,
      MQTT_CLIENT_ID: `bench-vs-telegraf-${shape}-${process.pid}`,
      INFLUX_URL: ctx.influx.url,
      INFLUX_BUCKET: ctx.influx.bucket,
      SPOOL_DIR: fs.mkdtempSync(path.join(ctx.logDir, 'spool-tg-')),
      WRITE_MODE: 'batch',
      BATCH_SIZE: String(BATCH),
      FLUSH_INTERVAL_MS: String(FLUSH_MS),
    },
    path.join(ctx.logDir, `telegraf-middleware-${shape}.log`),
  );
  return {
    name: 'middleware',
    prefix: `mw${shape[0]}`,
    pid: mw.child.pid,
    stop: () => mw.child.stop(),
  };
}
