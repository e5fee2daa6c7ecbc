/**
 * Reads the recordings' folder (./segment-files.ts): each camera of an arm and its finished
 * segments by time, and the `.part` files a crash left. Shared by the recorder at start and by
 * the LeRobot export, which cuts its videos from these files.
 */
import fs from 'node:fs';
import path from 'node:path';
import { parseSegmentName, PART_EXT, type Segment } from './segment-files.ts';

export interface CameraFolder {
  armId: string;
  camId: string;
  /** Its folder. */
  dir: string;
  /** Finished segments, by time. */
  segments: Segment[];
  /** Names of unfinished (`.part`) files. */
  parts: string[];
}

const subfolders = (d: string): string[] =>
  fs.existsSync(d)
    ? fs
        .readdirSync(d, { withFileTypes: true })
        .filter((e) => e.isDirectory())
        .map((e) => e.name)
        .sort()
    : [];

/** One camera's folder `<dir>/<armId>/<camId>`. */
export function readCameraFolder(dir: string, armId: string, camId: string): CameraFolder {
  const folder = path.join(dir, armId, camId);
  const segments: Segment[] = [];
  const parts: string[] = [];
  for (const name of fs.existsSync(folder) ? fs.readdirSync(folder) : []) {
    if (name.endsWith(PART_EXT)) parts.push(name);
    const t = parseSegmentName(name);
    if (!t) continue;
    const { size } = fs.statSync(path.join(folder, name));
    segments.push({ armId, camId, name, ...t, bytes: size });
  }
  segments.sort((a, b) => a.startMs - b.startMs);
  return { armId, camId, dir: folder, segments, parts };
}

/** Every camera folder of one arm (null: of every arm). */
export function readCameraFolders(dir: string, armId: string | null = null): CameraFolder[] {
  const arms = armId === null ? subfolders(dir) : [armId];
  return arms.flatMap((arm) =>
    subfolders(path.join(dir, arm)).map((cam) => readCameraFolder(dir, arm, cam)),
  );
}
