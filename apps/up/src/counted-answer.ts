/**
 * What the robot-write routes (calibration, keep-out) share: a JSON answer counted by outcome
 * (`written`, `refused:<why>`), every refusal or failure told to `onFirst` under
 * `<label>:<kind>`; the checks before a write; reading the profile file.
 */
import fs from 'node:fs';
import type http from 'node:http';
import path from 'node:path';
import { PROFILE_NAME } from '@armtwin/motion/robot-folder';
import type { Authorize } from './calibration-route.ts';
import { readBody } from './read-body.ts';

export type RouteCounters = Record<string, number>;

export function countedAnswer(
  label: string,
  counters: RouteCounters,
  onFirst: (kind: string, message: string) => void,
) {
  return (res: http.ServerResponse, status: number, body: unknown, kind: string): void => {
    counters[kind] = (counters[kind] ?? 0) + 1;
    if (status >= 400) onFirst(`${label}:${kind}`, `${label} ${kind}: ${JSON.stringify(body)}`);
    res
      .writeHead(status, { 'content-type': 'application/json', 'cache-control': 'no-store' })
      .end(JSON.stringify(body));
  };
}

type Answer = ReturnType<typeof countedAnswer>;

/**
 * The start every robot write shares: PUT only, the caller's role, the robot's profile.json (the
 * first models folder holding it), a JSON body of at most `maxBytes`. What the write needs, or
 * null once it has answered why not.
 */
export async function readRobotWrite(
  req: http.IncomingMessage,
  res: http.ServerResponse,
  o: { dirs: readonly string[]; authorize: Authorize },
  route: RegExp,
  maxBytes: number,
  answer: Answer,
): Promise<{ name: string; file: string; json: unknown } | null> {
  if (req.method !== 'PUT') {
    res.writeHead(405, { allow: 'PUT' }).end();
    return null;
  }
  const name = decodeURIComponent(route.exec(req.url ?? '')![1]!);
  const who = await o.authorize(req);
  if (!who.ok) {
    answer(res, who.status, { ok: false, errors: [who.error] }, 'refused:role');
    return null;
  }
  const file = PROFILE_NAME.test(name)
    ? o.dirs.map((d) => path.join(d, name, 'profile.json')).find((f) => fs.existsSync(f))
    : undefined;
  if (!file) {
    answer(res, 404, { ok: false, errors: [`no robot "${name}"`] }, 'refused:robot');
    return null;
  }
  const body = await readBody(req, maxBytes);
  if (body === null) {
    answer(res, 413, { ok: false, errors: [`request over ${maxBytes} bytes`] }, 'refused:size');
    return null;
  }
  try {
    return { name, file, json: JSON.parse(body.toString('utf8')) };
  } catch {
    answer(res, 400, { ok: false, errors: ['the request is not JSON'] }, 'refused:json');
    return null;
  }
}

/** The robot's profile.json as it is on disk, or null once it has answered (500) that it does not read. */
export function readProfileFile(
  res: http.ServerResponse,
  file: string,
  answer: Answer,
): { raw: unknown } | null {
  try {
    return { raw: JSON.parse(fs.readFileSync(file, 'utf8')) };
  } catch (err) {
    const error = `${file} does not read: ${(err as Error).message}`;
    answer(res, 500, { ok: false, errors: [error] }, 'failed:read');
    return null;
  }
}
