/**
 * What the robot-write routes (calibration, keep-out) share: a change to a robot's profile.json,
 * checked before and after it is applied, written with a backup of the old file; answered and
 * counted by outcome (`written`, `refused:<why>`, `failed:read`).
 */
import fs from 'node:fs';
import type http from 'node:http';
import path from 'node:path';
import { PROFILE_NAME } from '@armtwin/motion/robot-folder';
import {
  callerMay,
  countedAnswer,
  methodIn,
  type Answer,
  type May,
  type RouteCounters,
} from '../counted-answer.ts';
import { readBody } from '../read-body.ts';
import { replaceProfileFile } from './profile-file.ts';

/** What a robot-write route is told. */
export interface RobotWriteOptions {
  /** Models folders, searched in order. */
  dirs: readonly string[];
  /** Who may write (operators; ./authorize.ts). */
  may: May;
  /** Told once per kind of refusal or failure. */
  onFirst(kind: string, message: string): void;
}

type Checked<T> = { ok: true; value: T } | { ok: false; errors: string[] };

/** One kind of change to a robot's profile.json. */
export interface ProfileChange<R> {
  /** Counts and `onFirst` kinds are named `<label>:<outcome>`. */
  label: string;
  /** The largest request body. */
  maxBytes: number;
  /** The request's JSON checked before the profile is read (refused as `refused:request`). */
  request(json: unknown): Checked<R>;
  /**
   * The profile (as on disk) with the change, and what the answer tells of it beside `ok` and
   * `backup`; or why not (refused as `refused:<refusedAs>`).
   */
  apply(raw: unknown, request: R): Checked<{ raw: unknown; told: Record<string, unknown> }>;
  refusedAs: string;
}

/** A `PUT /robots/{name}/…` route making `change` (answers: see ./calibration.ts, ./keep-out.ts). */
export function profileWriteRoute<R>(o: RobotWriteOptions, change: ProfileChange<R>) {
  const counters: RouteCounters = {};
  const answer = countedAnswer(change.label, counters, o.onFirst);
  const handle = async (req: http.IncomingMessage, res: http.ServerResponse, name: string) => {
    const write = await readRobotWrite(req, res, o, name, change.maxBytes, answer);
    if (!write) return;
    const request = change.request(write.json);
    if (!request.ok)
      return answer(res, 400, { ok: false, errors: request.errors }, 'refused:request');
    const profile = readProfileFile(res, write.file, answer);
    if (!profile) return;
    const applied = change.apply(profile.raw, request.value);
    if (!applied.ok)
      return answer(res, 400, { ok: false, errors: applied.errors }, `refused:${change.refusedAs}`);
    const backup = replaceProfileFile(write.file, applied.value.raw);
    answer(res, 200, { ok: true, ...applied.value.told, backup }, 'written');
  };
  return { counters, handle };
}

/**
 * The start every robot write shares: PUT only, the caller's role, the robot's profile.json (the
 * first models folder holding it), a JSON body of at most `maxBytes`. What the write needs, or
 * null once it has answered why not.
 */
async function readRobotWrite(
  req: http.IncomingMessage,
  res: http.ServerResponse,
  o: RobotWriteOptions,
  name: string,
  maxBytes: number,
  answer: Answer,
): Promise<{ name: string; file: string; json: unknown } | null> {
  if (!methodIn(req, res, ['PUT'])) return null;
  if (!(await callerMay(o.may, req, res, answer))) return null;
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
function readProfileFile(
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
