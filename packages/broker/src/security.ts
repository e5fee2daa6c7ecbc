/**
 * The broker's security settings from the files the config names: the users file
 * (ARMTWIN_USERS) and the TLS certificate (ARMTWIN_TLS_CERT / ARMTWIN_TLS_KEY), read from disk
 * once at start-up.
 */
import fs from 'node:fs';
import { loadUsers, type Users } from '@armtwin/auth';
import type { BrokerTls } from './broker.ts';

/** Where the security settings are: paths, '' = none. */
export interface BrokerSecurityFiles {
  usersFile: string;
  tlsCert: string;
  tlsKey: string;
}

export interface BrokerSecurity {
  users: Users | null;
  tls: BrokerTls | null;
}

function read(file: string, what: string): Buffer {
  try {
    return fs.readFileSync(file);
  } catch (err) {
    throw new Error(`cannot read ${what} ${file}: ${(err as Error).message}`, { cause: err });
  }
}

export function loadBrokerSecurity(c: BrokerSecurityFiles): BrokerSecurity {
  return {
    users: c.usersFile ? loadUsers(c.usersFile) : null,
    tls:
      c.tlsCert && c.tlsKey
        ? { cert: read(c.tlsCert, 'ARMTWIN_TLS_CERT'), key: read(c.tlsKey, 'ARMTWIN_TLS_KEY') }
        : null,
  };
}

/** One line for the operator: who may connect. */
export function describeSecurity(s: BrokerSecurity, host: string): string {
  const who = s.users
    ? `log-in required (${s.users.list.length} users, roles enforced)`
    : `ANONYMOUS local demo: anyone on this machine may move the arm (listening on ${host} only; set ARMTWIN_USERS for log-ins)`;
  return `${who}; ${s.tls ? 'TLS on (mqtts, https, wss)' : 'no TLS'}`;
}
