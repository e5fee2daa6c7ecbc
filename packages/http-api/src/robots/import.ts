/**
 * `POST /api/robots/import[?name=NAME][&urdf=FILE][&replace=1]` (an operator's right; anyone in the
 * anonymous local demo): a robot dropped on the HUD, as a .zip (a dropped folder is zipped by the
 * page), imported with `armtwin robot import`'s core (`planImport`, `zipSource`,
 * `writeRobotFolder`) into the first models folder, where `/models/NAME/` serves it at once.
 *
 * Answers JSON: 200 `{ok, name, files, warnings, notes}`; 400 `{ok:false, errors}` for a body
 * that is not a zip, holds no (or several) .urdf, or a robot the import refuses (every reason);
 * 401/403 for a missing or non-operator log-in; 409 when that robot exists and `replace` is not
 * set; 413 for a body over `MAX_IMPORT_BYTES`.
 */
import type http from 'node:http';
import { IMPORT_NAME, MAX_IMPORT_BYTES, planImport } from '@armtwin/robot';
import { RobotExistsError, writeRobotFolder, zipSource } from '@armtwin/robot/import-node';
import {
  callerMay,
  countedAnswer,
  methodIn,
  type May,
  type RouteCounters,
} from '../counted-answer.ts';
import { readBody } from '../read-body.ts';

export interface ImportRouteOptions {
  /** Where imported robots are written (the first models folder). */
  modelsDir: string;
  /** Who may import (operators; ../authorize.ts). */
  may: May;
  onFirst(kind: string, message: string): void;
}

export function importRoute(o: ImportRouteOptions) {
  const counters: RouteCounters = {};
  const answer = countedAnswer('import', counters, o.onFirst);
  const refuse = (res: http.ServerResponse, status: number, errors: string[], kind: string) =>
    answer(res, status, { ok: false, errors }, `refused:${kind}`);
  const handle = async (req: http.IncomingMessage, res: http.ServerResponse) => {
    if (!methodIn(req, res, ['POST'])) return;
    if (!(await callerMay(o.may, req, res, answer))) return;
    const query = new URL(req.url ?? '', 'http://x').searchParams;
    const name = query.get('name') || undefined;
    if (name !== undefined && !IMPORT_NAME.test(name))
      return refuse(
        res,
        400,
        [`name must be [a-z0-9_-]{1,32}, got ${JSON.stringify(name)}`],
        'name',
      );
    const body = await readBody(req, MAX_IMPORT_BYTES);
    if (body === null)
      return refuse(res, 413, [`too big: at most ${MAX_IMPORT_BYTES / 1048576} MB`], 'size');
    if (body.length < 4 || body.readUInt32LE(0) !== 0x04034b50)
      return refuse(
        res,
        400,
        ['not a .zip (give a robot folder, or a .zip holding a .urdf)'],
        'zip',
      );
    let result;
    try {
      const source = zipSource(body, 'the dropped files', query.get('urdf') || undefined);
      result = planImport(source, name ? { name } : {});
    } catch (err) {
      return refuse(res, 400, [(err as Error).message], 'zip');
    }
    if (!result.ok) return refuse(res, 400, result.errors, 'robot');
    const { plan } = result;
    try {
      writeRobotFolder(plan, o.modelsDir, query.get('replace') === '1');
    } catch (err) {
      if (!(err instanceof RobotExistsError)) throw err;
      return refuse(
        res,
        409,
        [`a robot named ${plan.name} exists already: give another name, or replace it`],
        'exists',
      );
    }
    answer(
      res,
      200,
      {
        ok: true,
        name: plan.name,
        files: plan.files.length,
        warnings: plan.warnings,
        notes: plan.profile.notes,
      },
      'written',
    );
  };
  return { counters, handle };
}
