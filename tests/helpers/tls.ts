/**
 * A throwaway certificate authority and a server certificate it signed, made with `openssl` in
 * a temp dir, for TLS tests: the server certificate is for `localhost` and 127.0.0.1. A client
 * that trusts `ca` connects; one that does not is refused ("self-signed certificate in chain").
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

export interface TestCa {
  dir: string;
  /** File paths. */
  caFile: string;
  certFile: string;
  keyFile: string;
  /** PEM contents. */
  ca: Buffer;
  cert: Buffer;
  key: Buffer;
  dispose(): void;
}

export function makeTestCa(): TestCa {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-ca-'));
  const p = (name: string) => path.join(dir, name);
  const openssl = (...args: string[]) => execFileSync('openssl', args, { cwd: dir, stdio: 'pipe' });
  openssl(
    'req',
    '-x509',
    '-newkey',
    'rsa:2048',
    '-nodes',
    '-days',
    '2',
    '-subj',
    '/CN=armtwin test CA',
    '-keyout',
    p('ca.key'),
    '-out',
    p('ca.crt'),
    '-addext',
    'basicConstraints=critical,CA:TRUE',
    '-addext',
    'keyUsage=critical,keyCertSign,cRLSign',
  );
  openssl(
    'req',
    '-newkey',
    'rsa:2048',
    '-nodes',
    '-subj',
    '/CN=localhost',
    '-keyout',
    p('server.key'),
    '-out',
    p('server.csr'),
  );
  fs.writeFileSync(
    p('server.ext'),
    'subjectAltName=DNS:localhost,IP:127.0.0.1\nextendedKeyUsage=serverAuth\nbasicConstraints=CA:FALSE\n',
  );
  openssl(
    'x509',
    '-req',
    '-in',
    p('server.csr'),
    '-CA',
    p('ca.crt'),
    '-CAkey',
    p('ca.key'),
    '-CAcreateserial',
    '-days',
    '2',
    '-extfile',
    p('server.ext'),
    '-out',
    p('server.crt'),
  );
  // Mosquitto may drop to another user; let it read the key in this throwaway dir.
  fs.chmodSync(p('server.key'), 0o644);
  return {
    dir,
    caFile: p('ca.crt'),
    certFile: p('server.crt'),
    keyFile: p('server.key'),
    ca: fs.readFileSync(p('ca.crt')),
    cert: fs.readFileSync(p('server.crt')),
    key: fs.readFileSync(p('server.key')),
    dispose: () => fs.rmSync(dir, { recursive: true, force: true }),
  };
}
