/**
 * What the robot and model-copy routes share: a JSON answer counted by outcome (`written`,
 * `refused:<why>`, …), every refusal or failure told to `onFirst` under `<label>:<kind>`; and
 * who may call them (`May`, from the one log-in step, ./authorize.ts).
 */
import type http from 'node:http';
import type { Refusal } from './authorize.ts';
import { sendJson } from './send-json.ts';

export type RouteCounters = Record<string, number>;

/** Why the request's caller may not use a route (null: it may). */
export type May = (req: http.IncomingMessage) => Promise<Refusal | null>;

export type Answer = (
  res: http.ServerResponse,
  status: number,
  body: unknown,
  kind: string,
) => void;

export function countedAnswer(
  label: string,
  counters: RouteCounters,
  onFirst: (kind: string, message: string) => void,
): Answer {
  return (res, status, body, kind) => {
    counters[kind] = (counters[kind] ?? 0) + 1;
    if (status >= 400) onFirst(`${label}:${kind}`, `${label} ${kind}: ${JSON.stringify(body)}`);
    sendJson(res, status, body);
  };
}

/** Checks the caller; false once it has answered why not (`refused:role`, `{ok:false, errors}`). */
export async function callerMay(
  may: May,
  req: http.IncomingMessage,
  res: http.ServerResponse,
  answer: Answer,
): Promise<boolean> {
  const why = await may(req);
  if (why) answer(res, why.status, { ok: false, errors: [why.error] }, 'refused:role');
  return !why;
}

/** `405` with the methods a route takes, unless the request uses one of them (true). */
export function methodIn(
  req: http.IncomingMessage,
  res: http.ServerResponse,
  methods: readonly string[],
): boolean {
  if (methods.includes(req.method ?? '')) return true;
  res.writeHead(405, { allow: methods.join(', ') }).end();
  return false;
}
