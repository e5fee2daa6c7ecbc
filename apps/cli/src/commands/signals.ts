import type { Logger } from 'pino';

/** Resolves on the first SIGINT or SIGTERM (a second one exits at once, for a stuck shutdown). */
export function untilSignal(log?: Logger): Promise<NodeJS.Signals> {
  return new Promise((resolve) => {
    const on = (signal: NodeJS.Signals) => {
      process.removeListener('SIGINT', on);
      process.removeListener('SIGTERM', on);
      const again = () => process.exit(130);
      process.once('SIGINT', again);
      process.once('SIGTERM', again);
      log?.info({ signal }, 'stopping');
      resolve(signal);
    };
    process.once('SIGINT', on);
    process.once('SIGTERM', on);
  });
}
