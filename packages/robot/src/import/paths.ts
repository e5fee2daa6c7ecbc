/**
 * POSIX path helpers for the importer's pure core (no `node:path`: `@armtwin/ik` also runs in
 * the browser). Paths are '/'-separated; `normalize` resolves `.` and `..` and never climbs
 * above the start of a relative path's root ('' = the tree root).
 */

/** `a/./b/../c` → `a/c`; a leading `/` is kept; `..` past the root is dropped. */
export function normalize(p: string): string {
  const abs = p.startsWith('/');
  const out: string[] = [];
  for (const part of p.split('/')) {
    if (part === '' || part === '.') continue;
    if (part === '..') out.pop();
    else out.push(part);
  }
  return (abs ? '/' : '') + out.join('/');
}

/** The folder of a path (`a/b/c.urdf` → `a/b`; `c.urdf` → ''). */
export function dirname(p: string): string {
  const i = p.lastIndexOf('/');
  return i < 0 ? '' : i === 0 ? '/' : p.slice(0, i);
}

export function basename(p: string): string {
  return p.slice(p.lastIndexOf('/') + 1);
}

export function join(...parts: string[]): string {
  return normalize(parts.filter((x) => x !== '').join('/'));
}

/** `dir` and each of its ancestors, nearest first, ending at the root ('' or '/'). */
export function ancestors(dir: string): string[] {
  const out = [normalize(dir)];
  while (out.at(-1) !== '' && out.at(-1) !== '/') out.push(dirname(out.at(-1)!));
  return out;
}

/** The longest common folder of some file paths. */
export function commonDir(files: readonly string[]): string {
  if (files.length === 0) return '';
  let common = dirname(files[0]!).split('/');
  for (const f of files.slice(1)) {
    const parts = dirname(f).split('/');
    let k = 0;
    while (k < common.length && k < parts.length && common[k] === parts[k]) k++;
    common = common.slice(0, k);
  }
  return common.join('/') || (files[0]!.startsWith('/') ? '/' : '');
}

/** `file` relative to `dir` (`file` must lie inside `dir`). */
export function inside(dir: string, file: string): string {
  if (dir === '' || dir === '/') return file.replace(/^\//, '');
  return file.slice(dir.length + 1);
}
