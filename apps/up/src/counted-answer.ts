/**
 * A JSON answer of the robot-write routes (calibration, keep-out), counted by outcome
 * (`written`, `refused:<why>`); every refusal or failure is told to `onFirst` under `<label>:<kind>`.
 */
import type http from 'node:http';

export type RouteCounters = Record<string, number>;

export function countedAnswer(
  label: string,
  counters: RouteCounters,
  onFirst: (kind: string, message: string) => void,
) {
  return (res: http.ServerResponse, status: number, body: unknown, kind: string): void => {
    counters[kind] = (counters[kind] ?? 0) + 1;
    if (status !== 200) onFirst(`${label}:${kind}`, `${label} ${kind}: ${JSON.stringify(body)}`);
    res
      .writeHead(status, { 'content-type': 'application/json', 'cache-control': 'no-store' })
      .end(JSON.stringify(body));
  };
}
