/** What the Login panel says about the session, in words. Pure. */
import type { LoginState } from '../../../core/auth/loginMachine.ts';
import type { Permissions } from '../../../core/auth/roles.ts';

const SOURCE_WORDS = {
  server: '',
  demo: ' (local demo, no log-in)',
  hint: ' (from ?role=; the server could not confirm it)',
  default: ' (role unknown)',
} as const;

export function sessionWords(
  s: LoginState,
  p: Permissions | null,
): { who: string; reason: string } {
  switch (s.phase) {
    case 'invalid':
      return { who: 'Not connected.', reason: '' };
    case 'checking':
      return { who: 'Checking who you are…', reason: '' };
    case 'needs-login':
      return { who: 'Not signed in: log in to see the arm.', reason: '' };
    case 'connecting':
    case 'signed-in': {
      const a = s.access;
      const name = a.name ? `${a.name}, ${a.role}` : a.role;
      const verb = s.phase === 'connecting' ? 'Connecting as' : 'Signed in as';
      return { who: `${verb} ${name}${SOURCE_WORDS[a.source]}.`, reason: p?.reason ?? '' };
    }
  }
}
