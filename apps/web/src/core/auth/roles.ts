/**
 * Who this page is, and what that lets it do. The broker enforces the roles (SECURITY.md); the
 * page only mirrors them, so a viewer is never offered a control the broker would refuse —
 * and, on the embedded broker, never publishes at all (a refused publish closes the
 * connection). Pure: no I/O.
 */
import { ROLES, type Role } from '@armtwin/auth/roles';
import { CONTROL_USER_PATTERN } from '@armtwin/protocol';
import { guestName, type ControlIdentity } from '../link/ControlClaim.ts';
import type { LinkPermissions } from '../link/permissions.ts';

export { NO_PERMISSIONS, type LinkPermissions } from '../link/permissions.ts';

/**
 * Where the role came from: `server` = `/api/whoami` with our credentials; `demo` = the
 * anonymous local demo (whoami says so); `hint` = `?role=` because whoami could not answer;
 * `default` = nobody could say, so the page assumes the least: viewer.
 */
export type RoleSource = 'server' | 'demo' | 'hint' | 'default';

export interface Access {
  /** One of the users file's roles (`@armtwin/auth/roles`). */
  role: Role;
  source: RoleSource;
  /** The user name ('' = anonymous). */
  name: string;
}

export interface Permissions extends LinkPermissions {
  /** Stop is offered although nobody confirmed this account may publish. */
  stopUnconfirmed: boolean;
  /** Why the controls are off ('' when they are on), said on the page. */
  reason: string;
  /** The emergency stop button's text when `stop` is false. */
  stopRefusal: string;
}

export const VIEWER_REASON =
  'Signed in as viewer: controls are disabled. Ask for an operator account to move the arm.';
export const STOP_NEEDS_OPERATOR =
  'Emergency stop needs an operator account — use the physical stop';

export function permissionsFor(a: Access): Permissions {
  if (a.role === 'operator' || a.role === 'admin') {
    return {
      command: true,
      stop: true,
      deadman: true,
      stopUnconfirmed: false,
      reason: '',
      stopRefusal: '',
    };
  }
  const off = { command: false, deadman: false, stopRefusal: STOP_NEEDS_OPERATOR };
  if (a.role === 'viewer' && a.source === 'default') {
    // Nobody could say who we are. Moving is off (safety first); the stop stays on because it
    // can only make things safer: Mosquitto drops a refused publish, and the embedded broker
    // (whose whoami is always there) would at worst close and reopen the connection.
    return {
      ...off,
      stop: true,
      stopUnconfirmed: true,
      reason:
        'Role unknown (the server could not say): controls are disabled. If this account is an operator, open the page with ?role=operator.',
    };
  }
  return {
    ...off,
    stop: false,
    stopUnconfirmed: false,
    reason:
      a.role === 'viewer'
        ? VIEWER_REASON
        : `Signed in as ${a.role}: this page only watches. Log in with an operator account to move the arm.`,
  };
}

/**
 * The name this page claims arms under (docs/protocol.md § Control): the logged-in user, whom
 * the broker vouches for; in the anonymous demo a self-declared one (`?user=`, else a guest name).
 */
export function controlIdentity(a: Access, username: string): ControlIdentity {
  const enforced = a.source !== 'demo' && CONTROL_USER_PATTERN.test(a.name);
  const declared = CONTROL_USER_PATTERN.test(username) ? username : guestName();
  return { name: enforced ? a.name : declared, enforced, admin: a.role === 'admin' };
}

export const isRole = (v: unknown): v is Role =>
  typeof v === 'string' && (ROLES as readonly string[]).includes(v);
