/** Processes by pid, as a test checks that a child (an ffmpeg, say) is running or gone. */
import fs from 'node:fs';

/** Whether a process `pid` exists (signal 0). */
export function alive(pid: number): boolean {
  try {
    process.kill(pid, 0);
    return true;
  } catch {
    return false;
  }
}

/** The first child process of `pid` (Linux: /proc/<pid>/task/<pid>/children). */
export function firstChildPid(pid: number): number {
  return Number(fs.readFileSync(`/proc/${pid}/task/${pid}/children`, 'utf8').trim().split(' ')[0]);
}
