import { describe, expect, test } from 'vitest';
import { ConfigError, DEFAULT_MIDDLEWARE_CONFIG, loadConfig } from '../src/config.ts';

describe('loadConfig', () => {
  test('an empty environment gives the defaults of the seed (Table 5) and of §6', () => {
    const c = loadConfig({});
    expect(c).toEqual(DEFAULT_MIDDLEWARE_CONFIG);
    expect(c).toMatchObject({
      batchSize: 1000,
      flushIntervalMs: 5000,
      maxRetryDelayMs: 15000,
      mqttKeepaliveS: 60,
      mqttReconnectMs: 1000,
      mqttQos: 1,
      influxBucket: 'armtwin/autogen',
      mqttClientId: 'armtwin-middleware',
    });
  });

  test('variables override, numbers are parsed, empty means default', () => {
    const c = loadConfig({
      MQTT_URL: 'mqtt://broker:1884',
      MQTT_QOS: '0',
      BATCH_SIZE: '50',
      FLUSH_INTERVAL_MS: '',
      WRITE_MODE: 'sync',
      MQTT_SHARE_GROUP: 'armtwin',
      INFLUX_URL: 'http://localhost:8086',
      INFLUX_CREATE_BUCKET: 'false',
    });
    expect(c.mqttUrl).toBe('mqtt://broker:1884');
    expect(c.mqttQos).toBe(0);
    expect(c.batchSize).toBe(50);
    expect(c.flushIntervalMs).toBe(5000);
    expect(c.writeMode).toBe('sync');
    expect(c.mqttShareGroup).toBe('armtwin');
    expect(c.influxCreateBucket).toBe(false);
  });

  test.each([
    ['MQTT_QOS', '2'],
    ['BATCH_SIZE', 'lots'],
    ['BATCH_SIZE', '0'],
    ['FLUSH_INTERVAL_MS', '1.5'],
    ['INFLUX_URL', 'localhost:8086'],
    ['MQTT_URL', 'http://x'],
    ['WRITE_MODE', 'async'],
    ['MQTT_SHARE_GROUP', 'a/b'],
    ['NATS_URL', 'mqtt://n1:1883'],
    ['NATS_URL', 'nats://n1:4222,'],
    ['NATS_CONSUMER', 'a.b'],
    ['NATS_ACK_WAIT_MS', '10'],
    ['PORT', '70000'],
    ['LOG_LEVEL', 'loud'],
    ['FOXGLOVE_PORT', 'yes'],
    ['FOXGLOVE_PORT', '65536'],
  ])('%s=%s stops start-up with a message naming the variable', (name, value) => {
    expect(() => loadConfig({ [name]: value })).toThrow(ConfigError);
    expect(() => loadConfig({ [name]: value })).toThrow(new RegExp(`${name}=`));
  });

  test('FOXGLOVE_PORT: unset is no Foxglove server; a port (0: any free one) starts one', () => {
    expect(loadConfig({}).foxglovePort).toBe('off');
    expect(loadConfig({ FOXGLOVE_PORT: '8765' }).foxglovePort).toBe(8765);
    expect(loadConfig({ FOXGLOVE_PORT: '0' }).foxglovePort).toBe(0);
  });

  test('NATS_URL takes a list of NATS servers, kept in order', () => {
    const c = loadConfig({ NATS_URL: 'nats://n1:4222, nats://n2:4222,tls://n3:4222' });
    expect(c.natsUrl).toBe('nats://n1:4222,nats://n2:4222,tls://n3:4222');
    expect(c.natsConsumer).toBe('armtwin-middleware');
    expect(loadConfig({}).natsUrl).toBe(''); // MQTT intake
  });

  test('several bad variables are all named', () => {
    expect(() => loadConfig({ MQTT_QOS: '5', PORT: '-1' })).toThrow(/MQTT_QOS=[\s\S]*PORT=/);
  });
});
