/**
 * Writing an import plan as `<models>/<name>/` (Node only), for `armtwin robot import` and for a
 * robot dropped on the HUD (`armtwin up`). An existing folder is kept unless `force`.
 */
import fs from 'node:fs';
import path from 'node:path';
import type { ImportPlan } from '../import/plan-import.ts';

/** The robot's folder is there already (the message names it). */
export class RobotExistsError extends Error {}

/** Writes the plan's files; returns the folder. Throws `RobotExistsError` if it exists. */
export function writeRobotFolder(plan: ImportPlan, modelsDir: string, force: boolean): string {
  const dir = path.join(path.resolve(modelsDir), plan.name);
  if (fs.existsSync(dir) && !force) throw new RobotExistsError(`${dir} exists`);
  fs.rmSync(dir, { recursive: true, force: true });
  for (const f of plan.files) {
    const file = path.join(dir, ...f.path.split('/'));
    fs.mkdirSync(path.dirname(file), { recursive: true });
    fs.writeFileSync(file, f.data);
  }
  return dir;
}
