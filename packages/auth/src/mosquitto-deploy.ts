/**
 * `armtwin deploy-mosquitto`: reads the users file and writes the Mosquitto deployment
 * generated from it (./mosquitto-config.ts) into a folder, `passwd` readable by its owner only.
 */
import fs from 'node:fs';
import path from 'node:path';
import { mosquittoFiles, type MosquittoDeployOptions } from './mosquitto-config.ts';
import { loadUsers } from './users.ts';

export interface MosquittoDeployment {
  /** The folder written, absolute. */
  dir: string;
  /** How many users the files hold. */
  users: number;
}

/**
 * Writes mosquitto.conf, passwd and acl to `outDir` (created if missing). `confDir` defaults to
 * `outDir` made absolute, `source` to the users file's name.
 */
export function deployMosquitto(
  usersFile: string,
  outDir: string,
  options: Partial<MosquittoDeployOptions> = {},
): MosquittoDeployment {
  const users = loadUsers(usersFile);
  const dir = path.resolve(outDir);
  const files = mosquittoFiles(users.list, {
    ...options,
    confDir: options.confDir ?? dir,
    source: options.source ?? path.basename(usersFile),
  });
  fs.mkdirSync(dir, { recursive: true });
  for (const [name, text] of Object.entries(files)) {
    // passwd holds hashes: readable by its owner only (chown it to the mosquitto user).
    fs.writeFileSync(path.join(dir, name), text, { mode: name === 'passwd' ? 0o600 : 0o644 });
    if (name === 'passwd') fs.chmodSync(path.join(dir, name), 0o600);
  }
  return { dir, users: users.list.length };
}
