/**
 * A view of the History panel once its load has answered: the data, or the text to show in
 * its place. (The answers themselves are `@armtwin/api`'s, the types the middleware writes.)
 */
export type Loaded<T> = { ok: true; data: T } | { ok: false; error: string };
