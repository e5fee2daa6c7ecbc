/**
 * Environment variables of the arm-side commands (sim, gateway, broker, up), read here and
 * nowhere else. Flags override them; `DEFAULT_CLI_CONFIG` holds the defaults once.
 */
export interface CliConfig {
  /** MQTT_URL: broker the sim and gateway connect to. */
  mqttUrl: string;
  /** MQTT_USERNAME / MQTT_PASSWORD: broker credentials ('' = anonymous). */
  mqttUsername: string;
  mqttPassword: string;
  /** ARMTWIN_PORT: the one HTTP port of `armtwin up` (HUD, /mqtt WebSockets, /api). */
  httpPort: number;
  /** ARMTWIN_MQTT_PORT: the embedded broker's MQTT/TCP port. */
  mqttPort: number;
  /** ARMTWIN_HOST: interface `armtwin up` and `armtwin broker` listen on. */
  host: string;
  /** INFLUX_URL: InfluxDB for `armtwin up`'s middleware ('' = start a local influxd if possible). */
  influxUrl: string;
  /** LOG_LEVEL: pino level. */
  logLevel: string;
  /**
   * ARMTWIN_USERS: the users-and-roles file ('' = the anonymous local demo, loopback only).
   * With it the embedded broker authenticates and authorises every client (SECURITY.md).
   */
  usersFile: string;
  /** ARMTWIN_TLS_CERT / ARMTWIN_TLS_KEY: PEM files; both set = MQTTS and HTTPS/WSS. */
  tlsCert: string;
  tlsKey: string;
  /** API_TOKEN: bearer token of the middleware's HTTP API (/metrics, /history), passed through. */
  apiToken: string;
  /**
   * ARMTWIN_CSP_SOURCES: other brokers and camera servers the HUD of `armtwin up` may reach
   * (space-separated CSP sources, e.g. `wss://broker.lab https://cams.lab:8443`; '' = none).
   */
  cspSources: string;
}

export const DEFAULT_CLI_CONFIG: CliConfig = {
  mqttUrl: 'mqtt://127.0.0.1:1883',
  mqttUsername: '',
  mqttPassword: '',
  httpPort: 8080,
  mqttPort: 1883,
  host: '127.0.0.1',
  influxUrl: '',
  logLevel: 'info',
  usersFile: '',
  tlsCert: '',
  tlsKey: '',
  apiToken: '',
  cspSources: '',
};

const ENV: Record<keyof CliConfig, string> = {
  mqttUrl: 'MQTT_URL',
  mqttUsername: 'MQTT_USERNAME',
  mqttPassword: 'MQTT_PASSWORD',
  httpPort: 'ARMTWIN_PORT',
  mqttPort: 'ARMTWIN_MQTT_PORT',
  host: 'ARMTWIN_HOST',
  influxUrl: 'INFLUX_URL',
  logLevel: 'LOG_LEVEL',
  usersFile: 'ARMTWIN_USERS',
  tlsCert: 'ARMTWIN_TLS_CERT',
  tlsKey: 'ARMTWIN_TLS_KEY',
  apiToken: 'API_TOKEN',
  cspSources: 'ARMTWIN_CSP_SOURCES',
};

/** Throws unless the certificate and key are both set or both empty. */
function both(cert: string, key: string): void {
  if (Boolean(cert) !== Boolean(key))
    throw new Error('ARMTWIN_TLS_CERT and ARMTWIN_TLS_KEY go together: set both or neither');
}

function port(name: string, text: string): number {
  const n = Number(text);
  if (!Number.isInteger(n) || n < 0 || n > 65535)
    throw new Error(`${name}=${JSON.stringify(text)}: expected a port 0–65535`);
  return n;
}

/** The config from an environment (`process.env` by default); unset or empty → default. */
export function loadCliConfig(env: Record<string, string | undefined> = process.env): CliConfig {
  both(env[ENV.tlsCert]?.trim() ?? '', env[ENV.tlsKey]?.trim() ?? '');
  const get = (key: keyof CliConfig) => env[ENV[key]]?.trim() || String(DEFAULT_CLI_CONFIG[key]);
  return {
    mqttUrl: get('mqttUrl'),
    mqttUsername: env[ENV.mqttUsername] ?? '',
    mqttPassword: env[ENV.mqttPassword] ?? '',
    httpPort: port(ENV.httpPort, get('httpPort')),
    mqttPort: port(ENV.mqttPort, get('mqttPort')),
    host: get('host'),
    influxUrl: env[ENV.influxUrl]?.trim() ?? '',
    logLevel: get('logLevel'),
    usersFile: env[ENV.usersFile]?.trim() ?? '',
    tlsCert: env[ENV.tlsCert]?.trim() ?? '',
    tlsKey: env[ENV.tlsKey]?.trim() ?? '',
    apiToken: env[ENV.apiToken]?.trim() ?? '',
    cspSources: env[ENV.cspSources]?.trim() ?? '',
  };
}
