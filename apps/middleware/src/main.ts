/**
 * CLI entry (`npm run middleware`): config from the environment, start, and on SIGINT or
 * SIGTERM seal the open batch, write what can be written, exit. What is not written stays
 * in the spool for the next start.
 */
import { ConfigError, loadConfig, startMiddleware } from './index.ts';

/** A configuration problem (a bad variable, an unreadable users file): say it, exit 2. */
function configProblem(err: unknown): never {
  if (err instanceof ConfigError) {
    console.error(`armtwin middleware: ${err.message}`);
    process.exit(2);
  }
  throw err;
}

let config;
try {
  config = loadConfig();
} catch (err) {
  configProblem(err);
}

const mw = await startMiddleware(config).catch(configProblem);
let stopping = false;
for (const signal of ['SIGINT', 'SIGTERM'] as const) {
  process.on(signal, () => {
    if (stopping) process.exit(1);
    stopping = true;
    mw.stop().then(
      () => process.exit(0),
      (err: unknown) => {
        console.error(err);
        process.exit(1);
      },
    );
  });
}
