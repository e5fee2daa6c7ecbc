/**
 * The page's log-in: for each link (the first one, and each one the Connection or Login panel
 * makes) it asks `/api/whoami` who the credentials are, starts the link with that role's
 * permissions, and follows the broker's answer (connected, or refused → the log-in form).
 * A plain object; panels sample `state`. whoami is injected, so a test needs no server.
 */
import type { ArmLink } from '../link/ArmLink.ts';
import type { HudSettings } from '../config/settings.ts';
import { INITIAL_LOGIN, loginReducer, type LoginEvent, type LoginState } from './loginMachine.ts';
import { controlIdentity, permissionsFor, type Permissions } from './roles.ts';
import { resolveAccess, type Whoami } from './whoami.ts';

export interface SessionDeps {
  whoami(settings: HudSettings): Promise<Whoami>;
  /** What is wrong with the URL (checked before the first connection), or null. */
  queryProblem: string | null;
}

export class Session {
  state: LoginState = INITIAL_LOGIN;
  /** The permissions of the current link's role (none until known). */
  permissions: Permissions | null = null;
  /** The last failure to start a link ('' = none), shown by the Login panel. */
  error = '';
  private generation = 0;
  private started = false;

  constructor(private readonly deps: SessionDeps) {}

  dispatch(event: LoginEvent): void {
    this.state = loginReducer(this.state, event);
  }

  /** Starts `link` once its role is known. A newer call supersedes an older one. */
  async start(link: ArmLink): Promise<void> {
    const gen = ++this.generation;
    const s = link.settings;
    if (!this.started) {
      this.started = true;
      if (this.deps.queryProblem) {
        this.dispatch({ type: 'invalid', error: this.deps.queryProblem });
        return;
      }
    }
    this.permissions = null;
    this.dispatch({ type: 'start', username: s.username });
    const who = await this.deps.whoami(s);
    if (gen !== this.generation) return;
    if (who.kind === 'locked') {
      // Connecting now would only be refused: say why, and let the user try again later.
      this.dispatch({
        type: 'refused',
        message: `too many failed log-ins from this address; try again in ${who.retryS} s`,
      });
      return;
    }
    const access = resolveAccess(who, s.roleHint, s.username);
    this.permissions = permissionsFor(access);
    this.dispatch({ type: 'role', access });
    try {
      link.start(
        this.permissions,
        {
          connected: () => gen === this.generation && this.dispatch({ type: 'connected' }),
          authRefused: (message) => {
            if (gen !== this.generation) return;
            this.permissions = null; // not connected: no role, nothing to offer
            this.dispatch({ type: 'refused', message });
          },
        },
        controlIdentity(access, s.username),
      );
      this.error = '';
    } catch (err) {
      this.error = `Could not connect: ${err instanceof Error ? err.message : String(err)}`;
    }
  }
}
