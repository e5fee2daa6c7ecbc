/**
 * The middleware's episode marks (./marks.ts) in InfluxDB: read through the history's reader,
 * written through the storage (spool, then InfluxDB) and flushed before the answer, so the next
 * read sees them. Actions of one middleware run one at a time.
 */
import type { EpisodeAnswer, EpisodeService } from '@armtwin/http-api';
import type { HistoryReader } from '../history/reader.ts';
import { decide, marksOf, parseEpisodeAction, type EpisodeMark } from './marks.ts';

/** Reads every mark of an arm in [fromMs, toMs) (default: all). */
export async function readMarks(
  reader: HistoryReader,
  arm: string,
  fromMs = 0,
  toMs = Date.now() + 86_400_000,
): Promise<EpisodeMark[]> {
  return marksOf(await reader.measurement('episode', arm, fromMs, toMs));
}

export function episodeStore(o: {
  reader: HistoryReader;
  storage: { add(lines: readonly string[]): void; flush(timeoutMs: number): Promise<boolean> };
  now(): number;
}): EpisodeService {
  let queue: Promise<unknown> = Promise.resolve();
  const act = async (arm: string, body: unknown, by: string): Promise<EpisodeAnswer> => {
    const action = parseEpisodeAction(body);
    if ('error' in action) return { status: 400, body: { ok: false, errors: [action.error] } };
    const d = decide(arm, await readMarks(o.reader, arm), action, o.now(), by);
    if (d.lines.length === 0) return d;
    o.storage.add(d.lines);
    if (!(await o.storage.flush(10_000)))
      return { status: 202, body: { ...d.body, note: 'spooled: InfluxDB has not taken it yet' } };
    return d;
  };
  return {
    list: (arm, fromMs, toMs) => readMarks(o.reader, arm, fromMs, toMs),
    act(arm, body, by = '') {
      const next = queue.then(() => act(arm, body, by));
      queue = next.catch(() => {});
      return next;
    },
  };
}
