/** The Flux `HistoryReader`: the builders of queries.ts run through the official client's QueryApi. */
import { InfluxDB, type ParameterizedQuery, type QueryApi } from '@influxdata/influxdb-client';
import {
  actualCountQuery,
  actualQuery,
  alarmsQuery,
  auditQuery,
  commandsQuery,
  measurementQuery,
  poseQuery,
  seriesQuery,
} from './queries.ts';
import type { HistoryReader, InfluxSource } from './reader.ts';
import type { Row } from './shape.ts';

/** A reader over a QueryApi (`new InfluxDB({url, token}).getQueryApi(org)`) and a bucket. */
export function fluxReader(queryApi: QueryApi, bucket: string): HistoryReader {
  const rows = (q: ParameterizedQuery): Promise<Row[]> => queryApi.collectRows<Row>(q);
  return {
    language: 'flux',
    series: (p, every) => rows(seriesQuery(bucket, p, every)),
    pose: (p, every) => rows(poseQuery(bucket, p, every)),
    alarms: (p, max) => rows(alarmsQuery(bucket, p, max)),
    commands: (p, lookback, max) => rows(commandsQuery(bucket, p, lookback, max)),
    actualCount: (p) => rows(actualCountQuery(bucket, p)),
    actual: (p, every) => rows(actualQuery(bucket, p, every)),
    audit: (p, max) => rows(auditQuery(bucket, p, max)),
    measurement: (m, arm, a, b) => rows(measurementQuery(bucket, m, arm, a, b)),
  };
}

export function fluxReaderFor(src: InfluxSource): HistoryReader {
  const influx = new InfluxDB({
    url: src.url,
    token: src.token || undefined,
    timeout: src.timeoutMs,
  });
  return fluxReader(influx.getQueryApi(src.org), src.bucket);
}
