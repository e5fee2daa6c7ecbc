/**
 * A tiny, dependency-free field reader for validating parsed JSON: each read checks one field
 * and, when it is wrong, records a message naming the field's path (`servos[2].polarity`)
 * instead of throwing, so a profile with several mistakes reports all of them at once.
 */

export type Json = Record<string, unknown>;

export class Fields {
  readonly errors: string[] = [];

  /** Record an error at `path`. */
  fail(path: string, message: string): undefined {
    this.errors.push(`${path}: ${message}`);
    return undefined;
  }

  /** `v` as a plain object, or undefined (with an error). */
  object(path: string, v: unknown): Json | undefined {
    if (typeof v === 'object' && v !== null && !Array.isArray(v)) return v as Json;
    return this.fail(path, `must be an object, got ${describe(v)}`);
  }

  array(path: string, v: unknown): unknown[] | undefined {
    if (Array.isArray(v)) return v;
    return this.fail(path, `must be an array, got ${describe(v)}`);
  }

  /** A non-empty string, optionally matching `pattern` (described by `what`). */
  string(path: string, v: unknown, pattern?: RegExp, what?: string): string | undefined {
    if (typeof v !== 'string' || v.length === 0)
      return this.fail(path, `must be a non-empty string, got ${describe(v)}`);
    if (pattern && !pattern.test(v))
      return this.fail(path, `must be ${what}, got ${JSON.stringify(v)}`);
    return v;
  }

  /** A finite number (optionally > 0 or an integer), or `fallback` when absent and allowed. */
  number(
    path: string,
    v: unknown,
    opts: { positive?: boolean; integer?: boolean; fallback?: number } = {},
  ): number | undefined {
    if (v === undefined && opts.fallback !== undefined) return opts.fallback;
    if (typeof v !== 'number' || !Number.isFinite(v))
      return this.fail(path, `must be a finite number, got ${describe(v)}`);
    if (opts.integer && !Number.isInteger(v))
      return this.fail(path, `must be an integer, got ${v}`);
    if (opts.positive && !(v > 0)) return this.fail(path, `must be greater than 0, got ${v}`);
    return v;
  }

  /** One of `options`, or `fallback` when absent and given. */
  oneOf<T extends string | number>(
    path: string,
    v: unknown,
    options: readonly T[],
    fallback?: T,
  ): T | undefined {
    if (v === undefined && fallback !== undefined) return fallback;
    if ((options as readonly unknown[]).includes(v)) return v as T;
    return this.fail(
      path,
      `must be one of ${options.map((o) => JSON.stringify(o)).join(', ')}, got ${describe(v)}`,
    );
  }

  /** Report keys of `obj` not in `known` (keys starting with `$`, like `$comment`, are allowed). */
  noUnknownKeys(path: string, obj: Json, known: readonly string[]): void {
    for (const key of Object.keys(obj)) {
      if (!key.startsWith('$') && !known.includes(key))
        this.fail(
          path === '' ? key : `${path}.${key}`,
          `unknown field (expected one of ${known.join(', ')})`,
        );
    }
  }
}

/** A short description of a JSON value for error messages. */
export function describe(v: unknown): string {
  if (v === undefined) return 'nothing (the field is missing)';
  if (v === null) return 'null';
  if (Array.isArray(v)) return 'an array';
  if (typeof v === 'object') return 'an object';
  if (typeof v === 'string') return JSON.stringify(v.length > 40 ? `${v.slice(0, 40)}…` : v);
  return `${typeof v} ${String(v)}`;
}
