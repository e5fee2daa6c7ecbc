/** What the link may publish, as ArmLink applies it (the role's side: ../auth/roles.ts). */
export interface LinkPermissions {
  /** Publish on `arm/{id}/control`: jog, Move, `$PNG` pings. */
  command: boolean;
  /** Publish `#255PDST!`. */
  stop: boolean;
  /** Hold `arm/{id}/operator` (retained `1`, last will `0`, short keep-alive). */
  deadman: boolean;
}

/** Before the role is known nothing publishes. */
export const NO_PERMISSIONS: LinkPermissions = { command: false, stop: false, deadman: false };
