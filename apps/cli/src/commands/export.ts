import fs from 'node:fs';
import { once } from 'node:events';
import { InvalidArgumentError, Option, type Command } from 'commander';
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
import { DEFAULT_FPS } from '@armtwin/middleware/export/lerobot';
import { runLerobotExport, type LerobotFlags } from './export-lerobot.ts';

const FORMATS = [...EXPORT_FORMATS, 'lerobot'] as const;

interface ExportFlags extends LerobotFlags {
  from?: string;
  to?: string;
  format: ExportFormat | 'lerobot';
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

function wholeFps(value: string): number {
  const n = Number(value);
  if (!Number.isInteger(n) || n < 1 || n > 1000)
    throw new InvalidArgumentError(`--fps must be a whole number from 1 to 1000, got "${value}"`);
  return n;
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
    .description(
      "write an arm's stored history over a time range as MCAP (Foxglove), CSV or a LeRobot v3.0 dataset",
    )
    .requiredOption('--arm <id>', 'arm id')
    .option('--from <iso-time>', 'start of the range (included; mcap, csv: required)')
    .option('--to <iso-time>', 'end of the range (excluded; mcap, csv: required)')
    .addOption(new Option('--format <format>', 'file format').choices(FORMATS).default('mcap'))
    .requiredOption('--out <file>', 'file to write (lerobot: a new or empty folder)')
    .option(
      '--profile <name>',
      'the robot profile: for the 3D view (mcap; default: the one the arm announced, from its history or the broker); ' +
        'names the motors and their units (lerobot, required)',
    )
    .option(
      '--fps <n>',
      'lerobot: frames per second the history is resampled to',
      wholeFps,
      DEFAULT_FPS,
    )
    .option(
      '--episodes <list>',
      'lerobot: the marked episodes (all, or numbers 0,2 among the kept ones in --from/--to)',
    )
    .option(
      '--task <text>',
      "lerobot: the task, LeRobot's single_task (with --from/--to; overrides the marks' tasks)",
    )
    .option('--models <dir>', 'the folder of robot profiles (default public/models)')
    .option(
      '--cameras <dir>',
      "lerobot: the camera recordings' folder (the middleware's CAMERA_DIR; armtwin up: .armtwin/camera-recordings)",
    )
    .option(
      '--camera <names>',
      'lerobot: only these cameras, comma-separated (default: every one recorded over every episode)',
    )
    .addHelpText(
      'after',
      `
Reads InfluxDB with the middleware's settings: INFLUX_URL, INFLUX_TOKEN, INFLUX_ORG,
INFLUX_BUCKET (README, Configuration). The MCAP carries the robot description (meshes inline),
link transforms and joint states of the profile the arm announced: the one the middleware
stored with its history, else the arm's retained announcement on MQTT_URL. Open it in Foxglove
or Lichtblick with deploy/foxglove/armtwin-arm.json (docs/foxglove-mcap.md).

lerobot: the episodes marked through the HTTP API (POST /api/arms/<id>/episodes), or one
episode [--from, --to) with --task, resampled at --fps (the last stored sample at or before
each frame; docs/dataset.md). Every camera recorded over every episode (--cameras, default
CAMERA_DIR) becomes a video feature observation.images.<camera>: H.264 at --fps, cut from the
recorded segments (docs/cameras-recording.md).

Examples:
  INFLUX_URL=http://127.0.0.1:8086 armtwin export --format lerobot --arm so101 --profile so101 \\
    --episodes all --out ds/
  INFLUX_URL=http://127.0.0.1:8086 armtwin export --arm arm1 \\
    --from 2026-11-24T06:00:00Z --to 2026-11-24T06:10:00Z --out arm1.mcap`,
    )
    .action(async (flags: ExportFlags, cmd: Command) => {
      let startMs: number | undefined, stopMs: number | undefined;
      try {
        if (flags.from !== undefined) startMs = isoTime('from')(flags.from);
        if (flags.to !== undefined) stopMs = isoTime('to')(flags.to);
        if (startMs !== undefined && stopMs !== undefined && stopMs <= startMs)
          throw new Error('--to must be after --from');
      } catch (err) {
        return cmd.error((err as Error).message);
      }
      const config = loadConfig();
      if (!config.influxUrl) return cmd.error('INFLUX_URL is not set: nothing to read from');
      const reader = historyReader(influxSource(config, 120_000), config.influxQueryLanguage);
      if (flags.format === 'lerobot') {
        try {
          const cameras = flags.cameras ?? config.cameraDir;
          process.stderr.write(
            `${await runLerobotExport(reader, { ...flags, cameras }, { startMs, stopMs })}\n`,
          );
        } catch (err) {
          return cmd.error(`armtwin export: ${(err as Error).message}`);
        }
        return;
      }
      if (startMs === undefined || stopMs === undefined)
        return cmd.error(`--format ${flags.format} needs --from and --to`);
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
