/**
 * The page's Content-Security-Policy forbids `eval` (`script-src 'self'`, SECURITY.md § The page
 * itself). Zod (the camera announcements' parser) probes `new Function('')` once to decide whether
 * to compile its object parsers; under the policy that probe is blocked and reported as a
 * violation. Telling Zod up front that the page is jitless skips the probe. Imported first by
 * ./main.tsx, before anything parses.
 */
import { config } from 'zod';

config({ jitless: true });
