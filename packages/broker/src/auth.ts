/**
 * The embedded broker's policy: authentication from the users file (through the log-in
 * throttle), authorisation from ROLE_RULES (@armtwin/auth), the packet-size bound, and
 * in-process clients. Without a users file (the local demo) every client is anonymous and may
 * do anything but publish to `$SYS/`, and the broker must then listen on loopback only
 * (enforced by the caller).
 */
import { Duplex } from 'node:stream';
import type { Aedes, Client, Connection } from 'aedes';
import { canPublish, canSubscribe, type LoginThrottle, type Principal } from '@armtwin/auth';

export interface BrokerPolicy {
  /** Gives an in-process connection (no socket, no password) the rights of `principal`. */
  trust(conn: Connection, principal: Principal): void;
  /** Where a connection comes from (its IP), for the log-in throttle. */
  from(conn: Connection, address: string): void;
}

/** What the broker counts, for its log. */
export interface AuthCounters {
  refusedLogins: number;
  /** Log-ins refused unchecked because their address is locked out (@armtwin/auth's LoginThrottle). */
  lockedOutLogins: number;
  deniedPublish: number;
  deniedSubscribe: number;
  oversizePackets: number;
}

const SYS = '$SYS/';

/** CONNACK 0x05 "not authorised" (aedes' default return code for a failed authenticate). */
function notAuthorised(): Error & { returnCode: number } {
  return Object.assign(new Error('bad user name or password'), { returnCode: 5 });
}

export function installPolicy(
  aedes: Aedes,
  logins: LoginThrottle | null,
  counters: AuthCounters,
  onDenied: (what: string, detail: Record<string, unknown>) => void,
): BrokerPolicy {
  const trusted = new WeakMap<object, Principal>();
  const principals = new WeakMap<Client, Principal>();
  const sources = new WeakMap<object, string>();

  aedes.authenticate = (client, username, password, done) => {
    const inProcess = trusted.get(client.conn);
    if (inProcess) {
      principals.set(client, inProcess);
      return done(null, true);
    }
    if (!logins) return done(null, true);
    if (!username) return refuse(client, '(anonymous)', done);
    logins
      .login(sources.get(client.conn) ?? 'unknown', username, password ?? Buffer.alloc(0))
      .then((r) => {
        if (!r.ok) return refuse(client, username, done, r.lockedMs);
        principals.set(client, r.principal);
        done(null, true);
      })
      .catch((err: unknown) => done(err as never, false));
  };
  const refuse = (
    client: Client,
    user: string,
    done: (err: never, ok: boolean) => void,
    lockedMs = 0,
  ) => {
    counters.refusedLogins++;
    if (lockedMs > 0) counters.lockedOutLogins++;
    onDenied(lockedMs > 0 ? 'login-locked-out' : 'login', {
      user,
      client: client.id,
      ...(lockedMs > 0 ? { lockedForS: Math.ceil(lockedMs / 1000) } : {}),
    });
    done(notAuthorised() as never, false);
  };

  aedes.authorizePublish = (client, packet, done) => {
    if (packet.topic.startsWith(SYS)) return done(new Error(`${SYS} is reserved`));
    if (!logins) return done(null);
    // client is null only for a will left by a client of an earlier broker process: an
    // in-memory broker has none, so refuse what cannot be attributed.
    const p = client ? principals.get(client) : undefined;
    if (p && canPublish(p, packet.topic)) return done(null);
    counters.deniedPublish++;
    onDenied('publish', { user: p?.name, topic: packet.topic.slice(0, 120) });
    done(new Error(`not authorised to publish to ${packet.topic.slice(0, 120)}`));
  };

  aedes.authorizeSubscribe = (client, sub, done) => {
    if (!logins) return done(null, sub);
    const p = principals.get(client);
    if (p && canSubscribe(p, sub.topic)) return done(null, sub);
    counters.deniedSubscribe++;
    onDenied('subscribe', { user: p?.name, topic: sub.topic.slice(0, 120) });
    done(null, null); // SUBACK 0x80 for this filter; the connection stays (as Mosquitto does)
  };

  return {
    trust: (conn, principal) => void trusted.set(conn, principal),
    from: (conn, address) => void sources.set(conn, address),
  };
}

interface PacketParser {
  packet: { length: number };
  _parseLength(): boolean;
  _emitError(err: Error): void;
}

/**
 * Refuses any MQTT packet whose declared remaining length exceeds `maxBytes`, as soon as its
 * fixed header is read (before its body is buffered), and closes the connection, as Mosquitto's
 * `max_packet_size` does. Aedes has no such option, so this wraps the length step of the
 * client's mqtt-packet parser (aedes 1.x keeps it as `client._parser`); the broker's tests
 * fail if a new aedes changes that.
 */
export function limitPacketSize(client: Client, maxBytes: number, onOversize: () => void): void {
  const parser = (client as unknown as { _parser?: PacketParser })._parser;
  if (!parser || typeof parser._parseLength !== 'function')
    throw new Error('aedes internals changed: cannot bound the packet size (client._parser)');
  const parseLength = parser._parseLength;
  parser._parseLength = function (this: PacketParser) {
    const ok = parseLength.call(this);
    if (ok && this.packet.length > maxBytes) {
      onOversize();
      this._emitError(new Error(`packet of ${this.packet.length} bytes > ${maxBytes}`));
      return false;
    }
    return ok;
  };
}

/** Two connected in-memory streams: what one writes, the other reads. */
export function duplexPair(): [Duplex, Duplex] {
  const sides: Duplex[] = [];
  const make = (other: () => Duplex) =>
    new Duplex({
      read() {},
      write(chunk, _encoding, cb) {
        if (!other().destroyed) other().push(chunk);
        cb();
      },
      final(cb) {
        if (!other().destroyed) other().push(null);
        cb();
      },
      destroy(err, cb) {
        if (!other().destroyed) other().destroy();
        cb(err);
      },
    });
  sides.push(
    make(() => sides[1]!),
    make(() => sides[0]!),
  );
  return [sides[0]!, sides[1]!];
}
