/**
 * The four endpoints: build the Flux, run it on the injected `QueryApi`, shape the answer.
 * The only I/O is `queryApi.collectRows`.
 */
import type { QueryApi } from '@influxdata/influxdb-client';
import type { AlarmsAnswer, PoseAnswer, SeriesAnswer, TrackingAnswer } from '@armtwin/api';
import { alarmEpisodes, sortEpisodes, type AlarmEpisode } from './alarms.ts';
import type { HistoryOptions } from './options.ts';
import type { HistoryParams } from './params.ts';
import {
  actualCountQuery,
  actualQuery,
  alarmsQuery,
  commandsQuery,
  poseQuery,
  seriesQuery,
} from './queries.ts';
import { rowTime, samplesBy, toPoseFrames, toSeries, type Row } from './shape.ts';
import { trackingStats, type Command, type TrackingStats } from './tracking.ts';
import { windowFor } from './window.ts';

export interface EndpointContext {
  queryApi: QueryApi;
  bucket: string;
  options: HistoryOptions;
}

const rows = (ctx: EndpointContext, q: Parameters<QueryApi['collectRows']>[0]): Promise<Row[]> =>
  ctx.queryApi.collectRows<Row>(q);

const range = (p: HistoryParams) => ({ arm: p.arm, start: p.startMs, stop: p.stopMs });

export async function series(ctx: EndpointContext, p: HistoryParams): Promise<SeriesAnswer> {
  const every = windowFor(p.startMs, p.stopMs, ctx.options.maxPoints);
  const result = toSeries(await rows(ctx, seriesQuery(ctx.bucket, p, every.text)));
  return { ...range(p), field: p.field, every: every.text, everyMs: every.ms, series: result };
}

export async function pose(ctx: EndpointContext, p: HistoryParams): Promise<PoseAnswer> {
  const every = windowFor(p.startMs, p.stopMs, ctx.options.maxPoints);
  const result = toSeries(await rows(ctx, poseQuery(ctx.bucket, p, every.text)));
  return { ...range(p), every: every.text, everyMs: every.ms, ...toPoseFrames(result) };
}

export async function alarms(ctx: EndpointContext, p: HistoryParams): Promise<AlarmsAnswer> {
  const max = ctx.options.maxAlarmRows;
  const result = await rows(ctx, alarmsQuery(ctx.bucket, p, max));
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
  const counts = await rows(ctx, actualCountQuery(ctx.bucket, p));
  const most = Math.max(0, ...counts.map((r) => Number(r._value)));
  const stride = Math.max(1, Math.ceil(most / maxTrackingSamples));
  const [cmdRows, actualRows] = await Promise.all([
    rows(ctx, commandsQuery(ctx.bucket, p, commandLookbackMs, maxCommands)),
    rows(ctx, actualQuery(ctx.bucket, p, stride)),
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
  return { ...range(p), unit: 'deg', stride, truncated, joints };
}
