/**
 * The users-and-roles file: one JSON document that drives the embedded broker's hooks and the
 * generated Mosquitto configuration (`armtwin deploy-mosquitto`). Parsing is pure; `loadUsers`
 * is the only function that touches the disk.
 *
 *   { "users": [
 *       { "name": "alice", "role": "operator", "password": "$7$10000$…$…" },
 *       { "name": "arm1",  "role": "device", "arm": "arm1", "password": "$7$…" } ] }
 */
import fs from 'node:fs';
import { z } from 'zod';
import { ARM_ID_PATTERN } from '@armtwin/protocol';
import { isPasswordHash, verifyPassword } from './password.ts';
import { ROLES, type Principal } from './roles.ts';

/** A user name Mosquitto's password and ACL files can hold: no `:`, no spaces. */
export const USER_NAME_PATTERN = /^[A-Za-z0-9._-]{1,64}$/;

const USER = z
  .object({
    name: z.string().regex(USER_NAME_PATTERN, 'must match [A-Za-z0-9._-]{1,64}'),
    role: z.enum(ROLES),
    arm: z.string().regex(ARM_ID_PATTERN, 'must match [a-z0-9-]{1,32}').optional(),
    password: z
      .string()
      .refine(isPasswordHash, 'must be a $7$ (or $6$) hash: see `armtwin passwd`'),
  })
  .strict()
  .refine((u) => (u.role === 'device') === (u.arm !== undefined), {
    message: 'a device user needs "arm" (its own arm id); other roles must not have one',
    path: ['arm'],
  });

const FILE = z
  .object({ users: z.array(USER).min(1) })
  .strict()
  .refine((f) => new Set(f.users.map((u) => u.name)).size === f.users.length, {
    message: 'user names must be unique',
    path: ['users'],
  });

export type UserEntry = z.infer<typeof USER>;

export interface Users {
  readonly list: readonly UserEntry[];
  /** The principal for these credentials, or null (unknown user or wrong password). */
  authenticate(name: string, password: string | Buffer): Principal | null;
}

export class UsersFileError extends Error {
  override name = 'UsersFileError';
}

/** Parses the file's text; throws a UsersFileError naming every problem. */
export function parseUsers(text: string, source = 'users file'): Users {
  let json: unknown;
  try {
    json = JSON.parse(text);
  } catch (err) {
    throw new UsersFileError(`${source}: not JSON: ${(err as Error).message}`, { cause: err });
  }
  const parsed = FILE.safeParse(json);
  if (!parsed.success) {
    const lines = parsed.error.issues.map((i) => `${i.path.join('.') || '(top)'}: ${i.message}`);
    throw new UsersFileError(`${source}:\n  ${lines.join('\n  ')}`);
  }
  const list = parsed.data.users;
  const byName = new Map(list.map((u) => [u.name, u]));
  return {
    list,
    authenticate(name, password) {
      const u = byName.get(name);
      if (!u || !verifyPassword(password, u.password)) return null;
      return { name: u.name, role: u.role, ...(u.arm ? { arm: u.arm } : {}) };
    },
  };
}

export function loadUsers(file: string): Users {
  let text: string;
  try {
    text = fs.readFileSync(file, 'utf8');
  } catch (err) {
    throw new UsersFileError(`cannot read users file ${file}: ${(err as Error).message}`, {
      cause: err,
    });
  }
  return parseUsers(text, file);
}
