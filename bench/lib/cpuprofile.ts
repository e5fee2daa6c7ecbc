/**
 * A V8 `.cpuprofile` (node --cpu-prof) summed by function: self time (the samples whose top
 * frame it is) as a share of all samples. Pure: the parsed JSON in, rows out.
 */
export interface CpuProfile {
  nodes: {
    id: number;
    callFrame: { functionName: string; url: string; lineNumber: number };
  }[];
  samples: number[];
  timeDeltas: number[];
}

export interface SelfTimeRow {
  /** `name (file:line)`, the file relative to the repository or a package. */
  fn: string;
  selfMs: number;
  share: number;
}

/** `/…/node_modules/mqtt/build/lib/client.js` → `mqtt/build/lib/client.js`; repo paths relative. */
export function shortUrl(url: string, repo: string): string {
  const u = url.replace(/^file:\/\//, '');
  const nm = u.lastIndexOf('node_modules/');
  if (nm >= 0) return u.slice(nm + 'node_modules/'.length);
  return u.startsWith(repo) ? u.slice(repo.length + 1) : u;
}

/** Functions by self time, largest first; `(idle)` and `(program)` stay in as V8 names them. */
export function selfTimes(p: CpuProfile, repo: string): { totalMs: number; rows: SelfTimeRow[] } {
  const byId = new Map(p.nodes.map((n) => [n.id, n]));
  const us = new Map<string, number>();
  let total = 0;
  for (let i = 0; i < p.samples.length; i++) {
    const n = byId.get(p.samples[i]!);
    const dt = p.timeDeltas[i] ?? 0;
    if (!n || dt < 0) continue;
    const f = n.callFrame;
    const where = f.url ? ` (${shortUrl(f.url, repo)}:${f.lineNumber + 1})` : '';
    const key = `${f.functionName || '(anonymous)'}${where}`;
    us.set(key, (us.get(key) ?? 0) + dt);
    total += dt;
  }
  const rows = [...us]
    .map(([fn, t]) => ({ fn, selfMs: t / 1000, share: total ? t / total : 0 }))
    .sort((a, b) => b.selfMs - a.selfMs);
  return { totalMs: total / 1000, rows };
}
