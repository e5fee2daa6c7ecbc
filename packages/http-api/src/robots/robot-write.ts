/**
 * What the robot-write routes (calibration, keep-out) share: the checks before a write and
 * reading the profile file.
 */
import fs from 'node:fs';
import type http from 'node:http';
import path from 'node:path';
import { PROFILE_NAME } from '@armtwin/motion/robot-folder';
import { callerMay, methodIn, type Answer, type May } from '../counted-answer.ts';
import { readBody } from '../read-body.ts';

/** What a robot-write route is told. */
export interface RobotWriteOptions {
  /** Models folders, searched in order. */
  dirs: readonly string[];
  /** Who may write (operators; ./authorize.ts). */
  may: May;
  /** Told once per kind of refusal or failure. */
  onFirst(kind: string, message: string): void;
}

/**
 * The start every robot write shares: PUT only, the caller's role, the robot's profile.json (the
 * first models folder holding it), a JSON body of at most `maxBytes`. What the write needs, or
 * null once it has answered why not.
 */
export async function readRobotWrite(
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
