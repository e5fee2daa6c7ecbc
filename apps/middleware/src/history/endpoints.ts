/**
 * The four endpoints: ask the injected `HistoryReader` (Flux or InfluxQL), shape the answer.
 * The only I/O is the reader's.
 */
import type {
  AlarmsAnswer,
  AuditAnswer,
  AuditRecord,
  PoseAnswer,
  SeriesAnswer,
  TrackingAnswer,
} from '@armtwin/api';
import { alarmEpisodes, sortEpisodes, type AlarmEpisode } from './alarms.ts';
import { actualFromMs, type HistoryOptions } from './options.ts';
import type { HistoryParams } from './params.ts';
import type { HistoryReader } from './reader.ts';
import { rowTime, samplesBy, toPoseFrames, toSeries } from './shape.ts';
import { trackingStats, type Command, type TrackingStats } from './tracking.ts';
import { windowFor } from './window.ts';

export interface EndpointContext {
  reader: HistoryReader;
  options: HistoryOptions;
}

const range = (p: HistoryParams) => ({ arm: p.arm, start: p.startMs, stop: p.stopMs });

export async function series(ctx: EndpointContext, p: HistoryParams): Promise<SeriesAnswer> {
  const every = windowFor(p.startMs, p.stopMs, ctx.options.maxPoints);
  const result = toSeries(await ctx.reader.series(p, every.text));
  return { ...range(p), field: p.field, every: every.text, everyMs: every.ms, series: result };
}

export async function pose(ctx: EndpointContext, p: HistoryParams): Promise<PoseAnswer> {
  const every = windowFor(p.startMs, p.stopMs, ctx.options.maxPoints);
  const result = toSeries(await ctx.reader.pose(p, every.text));
  return { ...range(p), every: every.text, everyMs: every.ms, ...toPoseFrames(result) };
}

export async function alarms(ctx: EndpointContext, p: HistoryParams): Promise<AlarmsAnswer> {
  const max = ctx.options.maxAlarmRows;
  const result = await ctx.reader.alarms(p, max);
  const byKey = samplesBy(
    result.map((r) => ({ ...r, key: `${String(r._field)}/${String(r.id)}` })),
    'key',
  );
  const episodes: AlarmEpisode[] = [];
  let truncated = false;
  for (const [key, samples] of byKey) {
    const [field, id] = key.split('/') as ['temp' | 'volt', string];
    if (samples.length > max) {
      truncated = true;
      samples.length = max;
    }
    episodes.push(...alarmEpisodes(p.arm, id, field, samples));
  }
  return { ...range(p), truncated, episodes: sortEpisodes(episodes) };
}

export async function tracking(ctx: EndpointContext, p: HistoryParams): Promise<TrackingAnswer> {
  const { maxTrackingSamples, commandLookbackMs, maxCommands } = ctx.options;
  const counts = await ctx.reader.actualCount(p);
  const most = Math.max(0, ...counts.map((r) => Number(r._value)));
  // Denser than the bound: the first sample of each window, windows sized as for series.
  const thin =
    most > maxTrackingSamples
      ? windowFor(actualFromMs(p.startMs), p.stopMs, maxTrackingSamples)
      : null;
  const [cmdRows, actualRows] = await Promise.all([
    ctx.reader.commands(p, commandLookbackMs, maxCommands),
    ctx.reader.actual(p, thin?.text ?? null),
  ]);
  const commands = new Map<string, Command[]>();
  for (const r of cmdRows) {
    if (typeof r.angle !== 'number') continue;
    const id = String(r.id);
    if (!commands.has(id)) commands.set(id, []);
    commands
      .get(id)!
      .push({ t: rowTime(r), angle: r.angle, ms: typeof r.ms === 'number' ? r.ms : 0 });
  }
  let truncated = false;
  for (const list of commands.values()) {
    list.sort((a, b) => a.t - b.t);
    if (list.length > maxCommands) truncated = true;
  }
  const actual = samplesBy(actualRows);
  const ids = [...new Set([...commands.keys(), ...actual.keys()])].sort();
  const joints: TrackingStats[] = ids.map((id) =>
    trackingStats(id, commands.get(id) ?? [], actual.get(id) ?? [], p.startMs, p.stopMs),
  );
  return { ...range(p), unit: 'deg', thinnedEveryMs: thin?.ms ?? null, truncated, joints };
}

export async function audit(ctx: EndpointContext, p: HistoryParams): Promise<AuditAnswer> {
  const max = ctx.options.maxAuditRows;
  const events: AuditRecord[] = (await ctx.reader.audit(p, max))
    .map((r) => ({
      at: rowTime(r),
      by: typeof r.by === 'string' ? r.by : '',
      kind: String(r.kind ?? ''),
      detail: typeof r.detail === 'string' ? r.detail : '',
    }))
    .sort((a, b) => a.at - b.at);
  const truncated = events.length > max;
  if (truncated) events.length = max;
  return { ...range(p), truncated, events };
}
