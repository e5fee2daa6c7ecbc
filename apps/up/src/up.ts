/**
 * `armtwin up` (what `npm start` runs): the embedded broker, ONE HTTP(S) server (the HUD's
 * files, MQTT over WebSockets at /mqtt, and armtwin's one HTTP API under /api
 * (`@armtwin/http-api`: the middleware's history and metrics, robot writes, model copies), the
 * simulated arm (and the SO-101 on an emulated servo bus behind the bus gateway:
 * ./so101-part.ts), and the middleware with its storage, each as far as it exists. The arm and the middleware connect to
 * the broker in-process (no socket, no password) with the device and middleware roles.
 * `stop()` takes them down in order: the sim says offline, the middleware flushes, influxd
 * stops, the broker and server close.
 *
 * Security (SECURITY.md): without a users file this is the anonymous local demo and the broker
 * refuses any non-loopback host. With one, every MQTT client logs in, and /api (but /healthz)
 * needs a user's name and password (HTTP Basic) or, to read, the API token as a bearer token:
 * the API's one log-in step, on the broker's log-ins and throttle.
 */
import { randomBytes } from 'node:crypto';
import { startBroker } from '@armtwin/broker';
import { createApi } from '@armtwin/http-api';
import { MODELS_DIR } from '@armtwin/sim';
import type { ArmtwinFoxglove } from '@armtwin/foxglove';
import { createCameraPart } from './camera-part.ts';
import { startFoxglovePart } from './foxglove-part.ts';
import { createFront, listenFront } from './http-front.ts';
import { ensureWebBuild, startMiddlewarePart, WEB_DIST, type StartedMiddleware } from './parts.ts';
import { createModelPart } from './model-part.ts';
import { armSpecsOf, loadArmProfiles, profileDir, startSimArms } from './sim-arms.ts';
import { SO101_ARM, startSo101Part } from './so101-part.ts';
import { staticFiles } from './static-files.ts';
import type { Up, UpOptions } from './up-options.ts';

export type { Up, UpOptions } from './up-options.ts';

export async function startUp(o: UpOptions): Promise<Up> {
  const armSpecs = armSpecsOf(o);
  const modelDirs = o.modelsDir ? [o.modelsDir, MODELS_DIR] : [MODELS_DIR];
  const profiles = loadArmProfiles(armSpecs, modelDirs);
  const hasWeb = o.buildWeb ? ensureWebBuild(o.say) : false;
  const broker = await startBroker({
    host: o.host,
    port: o.mqttPort,
    fallbackToFreePort: o.mqttPortFallback,
    users: o.users,
    tls: o.tls,
    onDenied: (what, detail) =>
      o.onFirst(`denied:${what}`, `${what} refused ${JSON.stringify(detail)}`),
  });
  if (broker.fellBack)
    o.say(`broker: port ${o.mqttPort} is taken; MQTT/TCP on ${broker.port} instead`);

  let mw: StartedMiddleware | null = null;
  const files = staticFiles(
    WEB_DIST,
    'The HUD is not built: run `npm run build -w @armtwin/web`.\n',
  );
  const model = createModelPart({
    broker,
    simulated: new Map(
      armSpecs.map((a) => [
        a.id,
        { profile: a.profile, modelsDir: profileDir(modelDirs, a.profile) },
      ]),
    ),
    modelDirs,
    rate: o.rate,
    ...(o.modelIdleMs ? { idleMs: o.modelIdleMs } : {}),
    onFirst: o.onFirst,
    say: o.say,
  });
  const api = createApi({
    // Without a users file this is the local demo: the broker refuses any non-loopback host.
    auth: { logins: broker.logins, apiToken: o.apiToken, anonymous: 'anywhere' },
    service: () => mw?.middleware.service ?? null,
    modelDirs,
    modelCopies: model.copies,
    onFirst: o.onFirst,
  });
  // The in-process middleware has no password to send the camera server: a token of this run,
  // never stored, lets its recording watch the camera as the middleware role may.
  const recorderToken = randomBytes(32).toString('base64url');
  const camera = o.camera
    ? createCameraPart({
        source: o.camera,
        armId: armSpecs[0]!.id,
        broker,
        apiToken: o.apiToken,
        recorderToken,
        say: o.say,
        onFirst: o.onFirst,
      })
    : null;
  const server = createFront({
    broker,
    api,
    camera,
    files,
    tls: o.tls,
    cspSources: o.cspSources ?? [],
  });
  let url: string;
  try {
    url = await listenFront(server, o.httpPort, o.host, o.tls !== null);
  } catch (err) {
    await camera?.stop();
    await broker.close();
    throw err;
  }
  camera?.announce(url.slice(0, -1));
  let foxglove: ArmtwinFoxglove | null = null;
  if (o.foxglovePort !== undefined) {
    try {
      foxglove = await startFoxglovePart({
        broker,
        port: o.foxglovePort,
        host: o.host,
        tls: o.tls,
        modelDirs,
        onFirst: o.onFirst,
      });
      o.say(`foxglove: live at ${foxglove.url} (docs/foxglove.md)`);
    } catch (err) {
      await camera?.stop();
      await broker.close();
      server.close();
      throw err;
    }
  }

  const sims = startSimArms(broker, armSpecs, profiles, { ...o, modelDirs });
  const sim = sims[0]!;
  const so101 = o.so101
    ? await startSo101Part({
        broker,
        armId: o.so101,
        profile: SO101_ARM.profile,
        modelsDir: profileDir(modelDirs, SO101_ARM.profile),
        onFirst: o.onFirst,
      }).catch((err: unknown) => {
        o.say(
          `SO-101 "${o.so101}": not started: ${err instanceof Error ? err.message : String(err)}`,
        );
        return null;
      })
    : null;

  const middlewareReady = o.middleware
    ? startMiddlewarePart(
        {
          mqttUrl: broker.url,
          connect: (_url, opts) =>
            broker.connectInProcess({ name: 'middleware', role: 'middleware' }, opts),
          modelDirs,
          cameraAuthorization: `Bearer ${recorderToken}`,
          // its camera server's https/wss URLs carry the up's own (maybe self-signed) certificate
          cameraCa: o.tls?.cert ?? null,
        },
        o.influxUrl,
        o.env,
        o.say,
      ).then(
        (started) => {
          mw = started;
          o.say(`middleware: running; storage: ${started.storage}`);
          return started;
        },
        (err: unknown) => {
          o.say(`middleware: failed to start: ${err instanceof Error ? err.message : String(err)}`);
          return null;
        },
      )
    : Promise.resolve(null);
  if (!hasWeb && o.buildWeb) o.say('HUD: not available; the page at the URL says why');

  let stopping: Promise<void> | undefined;
  const stop = () =>
    (stopping ??= (async () => {
      await foxglove?.stop();
      await camera?.stop();
      await model.stop();
      await Promise.all([...sims.map((s) => s.stop()), so101?.stop()]);
      const started = await middlewareReady;
      if (started) {
        await started.middleware
          .stop()
          .catch((err: Error) => o.say(`middleware: stop failed: ${err.message}`));
        await started.influx
          ?.stop()
          .catch((err: Error) => o.say(`influxd: stop failed: ${err.message}`));
      }
      const closed = new Promise<void>((resolve) => server.close(() => resolve()));
      await broker.close();
      server.closeAllConnections();
      await closed;
    })());

  return { url, broker, sim, sims, so101, copies: model.copies, foxglove, middlewareReady, stop };
}
