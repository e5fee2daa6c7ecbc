import fs from 'node:fs';
import { once } from 'node:events';
import { Option, type Command } from 'commander';
import { historyReader, influxSource, loadConfig } from '@armtwin/middleware';
import {
  EXPORT_FORMATS,
  exportRecording,
  findArmProfile,
  loadRecordingRobot,
  type ExportFormat,
  type FoundProfile,
  type RecordingRobot,
} from '@armtwin/middleware/export';

interface ExportFlags {
  arm: string;
  from: string;
  to: string;
  format: ExportFormat;
  out: string;
  profile?: string;
  models?: string;
}

/** Epoch ms of an ISO 8601 time; a clear error for anything else. */
function isoTime(name: string) {
  return (value: string): number => {
    const ms = Date.parse(value);
    if (!/^\d{4}-\d\d-\d\d/.test(value) || !Number.isFinite(ms))
      throw new Error(
        `--${name} must be an ISO 8601 time such as 2026-11-24T06:00:00Z, got "${value}"`,
      );
    return ms;
  };
}

const FROM: Record<FoundProfile['source'], string> = {
  flag: '--profile',
  history: 'as the arm announced it, stored with its history',
  broker: "as the arm announces it on the broker (none in the range's history)",
};

/** The robot for the MCAP's 3D view, and a line saying which and why (or why none). */
function robotOf(
  found: FoundProfile | null,
  arm: string,
  models: string | undefined,
): { robot: RecordingRobot | null; note: string } {
  if (!found)
    return {
      robot: null,
      note: `no profile known for ${arm} (none stored in its history before --to, none retained on the broker): servo samples only; --profile NAME adds joint states, transforms and the robot description`,
    };
  let robot: RecordingRobot;
  try {
    robot = loadRecordingRobot(found.name, models, found.source);
  } catch (err) {
    if (found.source === 'flag') throw err;
    return {
      robot: null,
      note: `${arm} announced profile "${found.name}", which is not loadable here (${(err as Error).message.split('\n')[0]}): servo samples only; --models DIR names the folder that has it`,
    };
  }
  const missing = robot.description?.missing ?? [];
  return {
    robot,
    note:
      `profile ${found.name} (${FROM[found.source]}); ${robot.description?.meshes.length ?? 0} meshes inline` +
      (missing.length ? `; left out: ${missing.join('; ')}` : ''),
  };
}

export function registerExport(program: Command): void {
  program
    .command('export')
    .description("write an arm's stored history over a time range as MCAP (Foxglove) or CSV")
    .requiredOption('--arm <id>', 'arm id')
    .requiredOption('--from <iso-time>', 'start of the range (included)')
    .requiredOption('--to <iso-time>', 'end of the range (excluded)')
    .addOption(
      new Option('--format <format>', 'file format').choices(EXPORT_FORMATS).default('mcap'),
    )
    .requiredOption('--out <file>', 'file to write')
    .option(
      '--profile <name>',
      'the robot profile for the 3D view (MCAP; default: the one the arm announced, from its history or the broker)',
    )
    .option('--models <dir>', 'the folder of robot profiles (default public/models)')
    .addHelpText(
      'after',
      `
Reads InfluxDB with the middleware's settings: INFLUX_URL, INFLUX_TOKEN, INFLUX_ORG,
INFLUX_BUCKET (README, Configuration). The MCAP carries the robot description (meshes inline),
link transforms and joint states of the profile the arm announced: the one the middleware
stored with its history, else the arm's retained announcement on MQTT_URL. Open it in Foxglove
or Lichtblick with deploy/foxglove/armtwin-arm.json (docs/foxglove-mcap.md).

Example:
  INFLUX_URL=http://127.0.0.1:8086 armtwin export --arm arm1 \\
    --from 2026-11-24T06:00:00Z --to 2026-11-24T06:10:00Z --out arm1.mcap`,
    )
    .action(async (flags: ExportFlags, cmd: Command) => {
      let startMs: number, stopMs: number;
      try {
        startMs = isoTime('from')(flags.from);
        stopMs = isoTime('to')(flags.to);
        if (stopMs <= startMs) throw new Error('--to must be after --from');
      } catch (err) {
        return cmd.error((err as Error).message);
      }
      const config = loadConfig();
      if (!config.influxUrl) return cmd.error('INFLUX_URL is not set: nothing to read from');
      const reader = historyReader(influxSource(config, 120_000), config.influxQueryLanguage);
      let robot: RecordingRobot | null = null;
      let note = '';
      if (flags.format === 'mcap') {
        const found = await findArmProfile({
          reader,
          arm: flags.arm,
          stopMs,
          profile: flags.profile,
          broker: {
            url: config.mqttUrl,
            username: config.mqttUsername,
            password: config.mqttPassword,
          },
        });
        ({ robot, note } = robotOf(found, flags.arm, flags.models));
      }
      const out = fs.createWriteStream(flags.out);
      await once(out, 'open');
      const summary = await exportRecording({
        reader,
        arm: flags.arm,
        startMs,
        stopMs,
        format: flags.format,
        out,
        robot,
      });
      out.end();
      await once(out, 'close');
      const { servo, command, ik, audit } = summary.points;
      process.stderr.write(
        `${flags.out}: ${servo} servo, ${command} command and ${ik} ik points, ${audit} control events` +
          (flags.format === 'mcap'
            ? ` in ${Object.keys(summary.topics).length} topics\n${flags.out}: ${note}`
            : '') +
          '\n',
      );
    });
}
