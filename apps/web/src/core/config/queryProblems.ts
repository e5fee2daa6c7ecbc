/**
 * What is wrong with the page's URL query, said before anything connects. Today: an arm id
 * that is not `[a-z0-9-]{1,32}` (it would become an MQTT topic) — the page shows the error and
 * subscribes to nothing, rather than quietly watching another arm.
 */
import { isValidArmId } from '@armtwin/protocol';

export function armQueryProblem(search: string): string | null {
  const arm = new URLSearchParams(search).get('arm');
  if (arm === null || isValidArmId(arm)) return null;
  const shown = arm.length > 40 ? `${arm.slice(0, 40)}…` : arm;
  return `Invalid arm id in the address: "${shown}". An arm id is 1–32 of a–z, 0–9 and -. Not connected.`;
}
