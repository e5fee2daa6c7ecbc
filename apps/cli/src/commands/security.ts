/**
 * `armtwin passwd` (a password → a `$7$` hash for the users file, Mosquitto-compatible) and
 * `armtwin deploy-mosquitto` (the users file → mosquitto.conf, passwd, acl).
 */
import path from 'node:path';
import { InvalidArgumentError, Option, type Command } from 'commander';
import {
  DEFAULT_HASH_OPTIONS,
  DEFAULT_MOSQUITTO_DEPLOY_OPTIONS,
  deployMosquitto,
  hashPassword,
  ROLES,
  USER_NAME_PATTERN,
} from '@armtwin/auth';
import { armId, number } from './options.ts';

async function readStdin(): Promise<string> {
  const chunks: Buffer[] = [];
  for await (const c of process.stdin) chunks.push(c as Buffer);
  return Buffer.concat(chunks).toString('utf8');
}

interface PasswdFlags {
  iterations: number;
  name?: string;
  role?: string;
  arm?: string;
}

function userName(v: string): string {
  if (!USER_NAME_PATTERN.test(v)) throw new InvalidArgumentError('must match [A-Za-z0-9._-]{1,64}');
  return v;
}

export function registerPasswd(program: Command): void {
  program
    .command('passwd')
    .description('hash a password (first line of stdin) for the users file: Mosquitto $7$ format')
    .option(
      '--iterations <n>',
      `PBKDF2-SHA512 iterations (default ${DEFAULT_HASH_OPTIONS.iterations})`,
      number('iterations', 1, 10_000_000, true),
      DEFAULT_HASH_OPTIONS.iterations,
    )
    .option('--name <user>', 'print a whole users-file entry for this user', userName)
    .addOption(new Option('--role <role>', 'its role').choices([...ROLES]))
    .option('--arm <id>', "a device's own arm id", armId)
    .addHelpText(
      'after',
      `
Example: printf '%s' "$PASSWORD" | npx armtwin passwd --name alice --role operator
The password is read from stdin so it stays out of the shell history and the process list.`,
    )
    .action(async (flags: PasswdFlags) => {
      const password = (await readStdin()).split(/\r?\n/)[0] ?? '';
      if (!password) throw new Error('no password on stdin');
      const hash = hashPassword(password, { iterations: flags.iterations });
      if (!flags.name) return void process.stdout.write(`${hash}\n`);
      if (!flags.role) throw new Error('--name needs --role');
      if ((flags.role === 'device') !== (flags.arm !== undefined))
        throw new Error('a device needs --arm; other roles take none');
      const entry = {
        name: flags.name,
        role: flags.role,
        ...(flags.arm ? { arm: flags.arm } : {}),
        password: hash,
      };
      process.stdout.write(`${JSON.stringify(entry)}\n`);
    });
}

interface DeployFlags {
  users: string;
  out: string;
  confDir?: string;
  persistenceDir: string;
  port: number;
  bind?: string;
  mqttsPort: number;
  wssPort: number;
  certfile: string;
  keyfile: string;
  cafile: string;
  maxPacketSize: number;
}

export function registerDeployMosquitto(program: Command): void {
  const d = DEFAULT_MOSQUITTO_DEPLOY_OPTIONS;
  const port = number('port', 0, 65535, true);
  program
    .command('deploy-mosquitto')
    .description(
      'write a Mosquitto 2.0 configuration (mosquitto.conf, passwd, acl) from the users file',
    )
    .requiredOption(
      '--users <file>',
      'users-and-roles file (deploy/users.example.json shows the format)',
    )
    .requiredOption('--out <dir>', 'where to write the three files')
    .option(
      '--conf-dir <dir>',
      'absolute directory of passwd and acl on the broker host (default: --out, absolute)',
    )
    .option('--persistence-dir <dir>', 'Mosquitto persistence_location', d.persistenceDir)
    .option('--port <port>', 'plain MQTT on 127.0.0.1 only (0 = none)', port, d.localPort)
    .option('--bind <addr>', 'address of the TLS listeners (default: every interface)')
    .option('--mqtts-port <port>', 'MQTT over TLS (0 = none)', port, d.mqttsPort)
    .option(
      '--wss-port <port>',
      'MQTT over secure WebSockets, for the HUD (0 = none)',
      port,
      d.wssPort,
    )
    .option('--certfile <pem>', 'server certificate chain', d.certfile)
    .option('--keyfile <pem>', 'server private key', d.keyfile)
    .option('--cafile <pem>', 'CA certificate(s)', d.cafile)
    .option(
      '--max-packet-size <bytes>',
      'max_packet_size',
      number('bytes', 20, 268_435_455, true),
      d.maxPacketBytes,
    )
    .action((flags: DeployFlags) => {
      const { dir, users } = deployMosquitto(flags.users, flags.out, {
        confDir: flags.confDir,
        persistenceDir: flags.persistenceDir,
        localPort: flags.port,
        publicHost: flags.bind ?? '',
        mqttsPort: flags.mqttsPort,
        wssPort: flags.wssPort,
        certfile: flags.certfile,
        keyfile: flags.keyfile,
        cafile: flags.cafile,
        maxPacketBytes: flags.maxPacketSize,
      });
      process.stderr.write(
        `armtwin: wrote mosquitto.conf, passwd, acl to ${dir} for ${users} users\n` +
          `  run: mosquitto -c ${path.join(dir, 'mosquitto.conf')}\n`,
      );
    });
}
