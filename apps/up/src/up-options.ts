/**
 * What `armtwin up` is given (`UpOptions`) and what it hands back (`Up`): the settings of each
 * part and the running parts, for ./up.ts (which starts them) and ./run-up.ts (the command's
 * settings).
 */
import type { Users } from '@armtwin/auth';
import type { Broker, BrokerTls } from '@armtwin/broker';
import type { ArmtwinFoxglove } from '@armtwin/foxglove';
import type { MqttSim } from '@armtwin/sim';
import type { ModelCopies } from './model-copies.ts';
import type { StartedMiddleware } from './parts.ts';
import type { So101Part } from './so101-part.ts';

export interface UpOptions {
  /** The HTTP port: HUD, /mqtt, /api. 0 = any free port. */
  httpPort: number;
  /** The broker's MQTT/TCP port. */
  mqttPort: number;
  /** Fall back to a free MQTT port when `mqttPort` is taken (when it was not asked for explicitly). */
  mqttPortFallback: boolean;
  host: string;
  /** The simulated arm's id and state rate. */
  armId: string;
  rate: number;
  /**
   * The simulated arms and their profiles (`--arms arm1:armtwin5,arm2:track6`), all on this
   * broker; `sim` is the first. Unset or empty: one arm, `armId`, with the default profile.
   */
  arms?: { id: string; profile: string }[];
  /**
   * The second arm, a simulated SO-101 on an emulated Feetech bus behind the real bus gateway
   * (./so101-part.ts), on this arm id; unset: none. `armtwin up` starts it as `so101` unless
   * `--no-so101`. If it cannot start (no socat), `up` says why and runs without it.
   */
  so101?: string;
  /** INFLUX_URL ('' = local influxd if possible). */
  influxUrl: string;
  /** Build the HUD if it is missing. */
  buildWeb: boolean;
  /** Start the middleware. */
  middleware: boolean;
  /** The environment handed to the middleware's own config loader. */
  env: Record<string, string | undefined>;
  /** Users and roles (null = the anonymous local demo, loopback only). */
  users: Users | null;
  /** HTTPS/WSS and MQTTS with this certificate (null = plain). */
  tls: BrokerTls | null;
  /** API_TOKEN: a bearer token that reads /api's history and metrics ('' = none). */
  apiToken: string;
  /**
   * An extra folder of robot profiles (`--models DIR`): served at /models/ before
   * public/models, and searched first for the arms' profiles.
   */
  modelsDir?: string;
  /** The live Foxglove WebSocket server's port (`--foxglove [PORT]`; unset: none; 0: any free). */
  foxglovePort?: number;
  /** A demo camera of the first arm (`--camera testsrc`, a device, a URL; '' = none). */
  camera?: string;
  /**
   * Sources beyond this origin the HUD may connect to and show pictures from (other brokers,
   * camera servers), added to its Content-Security-Policy (./security-headers.ts).
   */
  cspSources?: string[];
  /**
   * A model copy (`/api/arms/{id}/model`, ./model-copies.ts) stops after this long with nothing
   * received on its topics, ms (unset: `DEFAULT_MODEL_COPIES_OPTIONS`, 10 minutes).
   */
  modelIdleMs?: number;
  /** Progress lines for the operator. */
  say: (msg: string) => void;
  onFirst: (kind: string, message: string) => void;
}

export interface Up {
  /** The URL to open. */
  url: string;
  broker: Broker;
  sim: MqttSim;
  /** Every simulated arm, in `arms` order. */
  sims: MqttSim[];
  /** The SO-101 on its emulated bus (`so101`), null when not asked for or when it failed to start. */
  so101: So101Part | null;
  /** The arms' model copies, started on demand (docs/protocol.md § Modes). */
  copies: ModelCopies;
  /** The live Foxglove server (`foxglovePort`), or null. */
  foxglove: ArmtwinFoxglove | null;
  /** Resolves when the middleware (if any) is up or has failed to start. */
  middlewareReady: Promise<StartedMiddleware | null>;
  stop(): Promise<void>;
}
