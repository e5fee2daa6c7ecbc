/**
 * Real services for integration and end-to-end tests: a throwaway Mosquitto and a throwaway
 * influxd on free ports of 127.0.0.1, each in its own temp dir.
 *
 * In a Vitest file, use the hooks from `./use-services.ts` (kept apart because it imports
 * `vitest`, which must not be loaded by Playwright):
 *
 *     const broker = useMosquitto();      // started in beforeAll, disposed in afterAll
 *     const influx = useInflux();
 *     test('…', async () => { mqtt.connect(broker().url); … influx().url … });
 *
 * Anywhere else (Playwright globalSetup, scripts), call `startMosquitto()` / `startInflux()`
 * and finally `await svc.dispose({ keepLogs: failed })`.
 *
 * Logs: each service writes `<dir>/<name>.log` (its stdout and stderr). `dispose({ keepLogs:
 * true })` copies the logs and config to `test-results/services/<name>-<timestamp>-<pid>/`
 * before removing the temp dir; `useMosquitto`/`useInflux` pass `keepLogs: true` when any
 * test, hook or suite in their scope failed. A service that fails to start always keeps its
 * logs and names the folder in the error.
 *
 * Lifecycle: `stop()` (SIGTERM), `kill()` (SIGKILL), `start()` and `restart()` act on the
 * process only, on the same dir and ports, for outage and persistence tests. Processes are
 * killed when the test process exits or gets SIGINT/SIGTERM/SIGHUP, and (via
 * `setpriv --pdeathsig`) even when it is SIGKILLed.
 */
export {
  startMosquitto,
  mosquittoBinary,
  deployedMosquittoSpec,
  DEFAULT_MOSQUITTO_OPTIONS,
} from './mosquitto.ts';
export type { MosquittoOptions, MosquittoService } from './mosquitto.ts';
export { startInflux, influxQuery, INFLUXD, DEFAULT_INFLUX_OPTIONS } from './influx.ts';
export type { InfluxOptions, InfluxService } from './influx.ts';
export { freePort, freePorts, canConnect, LOOPBACK } from './ports.ts';
export { REPO_ROOT, KEPT_LOGS_DIR, keepLogs } from './files.ts';
