/**
 * Waiting for a condition in a test: polls until it holds, and fails naming what it waited for.
 * Only a generous limit, never a timing assertion.
 */

/** Polls `probe` (sync or async) until it gives a truthy value, which it returns; fails naming `what` after `ms`. */
export async function until<T>(
  probe: () => T | Promise<T>,
  ms: number,
  what: string,
  everyMs = 50,
): Promise<NonNullable<T>> {
  const end = Date.now() + ms;
  for (;;) {
    const v = await probe();
    if (v) return v as NonNullable<T>;
    if (Date.now() > end) throw new Error(`timed out waiting for ${what}`);
    await new Promise((r) => setTimeout(r, everyMs));
  }
}
