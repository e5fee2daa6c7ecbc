/**
 * `GET …/whoami` (served by `armtwin up` and by the middleware with a users file): the body of
 * its 200 answer. 401 and 429 answer `{error}`; a 429 carries `Retry-After` in seconds.
 */
import type { ErrorAnswer } from './history.ts';

export interface WhoamiUser {
  /** The user name; '' in the anonymous local demo. */
  name: string;
  /** One of the users file's roles (`@armtwin/auth/roles`). */
  role: string;
  /** The device user's own arm id. */
  arm?: string;
  /** true in the anonymous local demo (no users file): everyone is an operator. */
  anonymous?: true;
}

export type WhoamiBody = WhoamiUser | ErrorAnswer;
