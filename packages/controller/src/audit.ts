/**
 * One operator at a time, in front of the core: the `ControlArbiter` (./arbiter.ts) decides
 * whose control payloads reach the controller; this puts the core's keep-out refusals into its
 * audit record with their sender (`refused-keep-out`), for every driver alike.
 */
import type { ControlArbiter } from './arbiter.ts';
import type { ControllerCore } from './core.ts';

/**
 * Wraps the arbiter's `forward`: a payload that the core refuses by a keep-out rule is recorded
 * as `refused-keep-out` with who sent it. `control` is read late (the arbiter is built with this).
 */
export function auditKeepOut(
  core: () => ControllerCore,
  control: () => ControlArbiter,
  forward: (payload: Uint8Array | string) => void,
): (payload: Uint8Array | string) => void {
  return (payload) => {
    const r = core().counters.rejected;
    const before = r.zone + r.floor;
    forward(payload);
    if (r.zone + r.floor === before) return;
    const by = control().author;
    const who = by || 'a client on a plain topic';
    control().record(by, 'refused-keep-out', `${who}: ${core().lastKeepOutRefusal}`);
  };
}
