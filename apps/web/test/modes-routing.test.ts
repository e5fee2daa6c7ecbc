/**
 * Model / Shadow / Twin routing (docs/protocol.md § Modes): the pure mode → topic rules, and the
 * arm link that applies them to every command (a fake client records what it publishes).
 */
import { afterEach, beforeEach, describe, expect, it, vi } from 'vitest';
import { encodePosition } from '@armtwin/protocol';
import {
  commandArm,
  commandTopic,
  defaultMode,
  modelArmId,
  parseMode,
  stopArms,
} from '../src/core/link/modes.ts';
import { poseBody } from '../src/core/modes/modelCopy.ts';
import { queryWithMode } from '../src/core/modes/ModeSwitch.ts';
import { ArmStore } from '../src/core/store/ArmStore.ts';
import { ArmLink } from '../src/core/link/ArmLink.ts';
import { FakeMqttClient } from './support/FakeMqttClient.ts';
import { defaultSettings } from '../src/core/config/settings.ts';

describe('mode → topic (pure)', () => {
  it('Twin drives the arm, Model its copy, Shadow nothing', () => {
    expect(commandTopic('arm1', 'twin', null)).toBe('arm/arm1/control');
    expect(commandTopic('arm1', 'twin', 'alice')).toBe('arm/arm1/control/alice');
    expect(commandTopic('arm1', 'model', null)).toBe('arm/arm1-model/control');
    expect(commandTopic('arm1', 'model', 'alice')).toBe('arm/arm1-model/control/alice');
    expect(commandTopic('arm1', 'shadow', 'alice')).toBeNull();
    expect(commandArm('arm1', 'shadow')).toBeNull();
    expect(modelArmId('arm1')).toBe('arm1-model');
  });

  it('an arm that cannot have a copy (a copy, a long id) has no Model route', () => {
    expect(modelArmId('arm1-model')).toBeNull();
    expect(modelArmId('a'.repeat(27))).toBeNull();
    expect(commandTopic('arm1-model', 'model', null)).toBeNull();
    expect(stopArms('arm1-model', 'model')).toEqual(['arm1-model']);
  });

  it('the stop reaches the real arm in every mode, and the copy too in Model', () => {
    expect(stopArms('arm1', 'twin')).toEqual(['arm1']);
    expect(stopArms('arm1', 'shadow')).toEqual(['arm1']);
    expect(stopArms('arm1', 'model')).toEqual(['arm1-model', 'arm1']);
  });

  it('a role that may drive opens in Twin, a viewer in Shadow; ?mode= is read and written', () => {
    expect(defaultMode(true)).toBe('twin');
    expect(defaultMode(false)).toBe('shadow');
    expect(parseMode('model')).toBe('model');
    expect(parseMode('Model')).toBeNull();
    expect(parseMode(null)).toBeNull();
    expect(queryWithMode('?arm=arm2&mode=twin', 'model')).toBe('?arm=arm2&mode=model');
  });

  it('the copy starts at the pulses known, by servo id', () => {
    expect(poseBody([0, 1, 2], [1500, NaN, 1720.4])).toEqual({ '0': 1500, '2': 1720 });
    expect(poseBody([0, 1], [NaN, NaN])).toBeNull();
  });
});

function setup() {
  const store = new ArmStore();
  const copy = new ArmStore();
  const client = new FakeMqttClient();
  const link = new ArmLink(store, defaultSettings({ protocol: 'http:', host: 'h' }), () => client);
  link.start({ command: true, stop: true, deadman: true });
  client.emit('connect');
  const sent = () =>
    client.published
      .filter((p) => !p.payload.startsWith('$PNG') && !p.topic.endsWith('/operator'))
      .map((p) => `${p.topic} ${p.payload}`);
  return { store, copy, client, link, sent };
}

describe('ArmLink routes every command by mode', () => {
  beforeEach(() => vi.useFakeTimers());
  afterEach(() => vi.useRealTimers());

  it('Model: jogs, groups and $KMS go to the copy, reads its status, holds its deadman', () => {
    const { client, copy, link, store, sent } = setup();
    link.setMode('model', copy);
    expect(client.subscribed).toContain('arm/arm1-model/status');
    expect(client.published).toContainEqual(
      expect.objectContaining({
        topic: 'arm/arm1-model/operator',
        payload: '1',
        retain: true,
      }),
    );
    link.jog(2, 1600);
    link.sendGroup('{#000P1500T0100!}');
    link.moveTo(150, 0, 100, undefined, [1500, 1500, 1500, 1500]);
    link.holdMoves([[1, 1550]], 200);
    vi.advanceTimersByTime(2000); // the pings stay off the arm too
    expect(sent()).toEqual([
      'arm/arm1-model/control #002P1600T0100!',
      'arm/arm1-model/control {#000P1500T0100!}',
      expect.stringMatching(/^arm\/arm1-model\/control \$KMS:/),
      'arm/arm1-model/control #001P1550T0200!',
    ]);
    expect(client.published.some((p) => /^arm\/arm1\/control/.test(p.topic))).toBe(false);
    // The copy's status lands in the copy's store, not the arm's.
    client.emit(
      'message',
      'arm/arm1-model/status',
      new TextEncoder().encode(encodePosition(0, 1700)),
    );
    expect(copy.pwm[0]).toBe(1700);
    expect(store.pwm[0]).toBeNaN();
  });

  it('Model: the emergency stop goes to the copy and the real arm', () => {
    const { copy, link, sent } = setup();
    link.setMode('model', copy);
    expect(link.emergencyStop()).toBe(true);
    expect(sent()).toEqual(['arm/arm1-model/control #255PDST!', 'arm/arm1/control #255PDST!']);
  });

  it('Model is refused for an arm that cannot have a copy: commands stay on the arm', () => {
    const store = new ArmStore();
    const client = new FakeMqttClient();
    const settings = { ...defaultSettings({ protocol: 'http:', host: 'h' }), armId: 'arm1-model' };
    const link = new ArmLink(store, settings, () => client);
    link.start({ command: true, stop: true, deadman: false });
    client.emit('connect');
    link.setMode('model', new ArmStore());
    expect(link.mode).toBe('twin');
    link.sendGroup('{#000P1500T0100!}');
    expect(client.published.map((p) => p.topic)).toEqual(['arm/arm1-model/control']);
  });

  it('Shadow: nothing but the stop goes out, and the page may not move', () => {
    const { link, sent } = setup();
    link.setMode('shadow');
    expect(link.mayMove).toBe(false);
    link.jog(2, 1600);
    expect(link.sendGroup('{#000P1500T0100!}')).toBe(false);
    expect(link.holdMoves([[1, 1550]], 200)).toBe(false);
    expect(link.stopServos([1])).toBe(false);
    expect(link.setTorque(false)).toBe(false);
    vi.advanceTimersByTime(2000);
    expect(sent()).toEqual([]);
    expect(link.emergencyStop()).toBe(true);
    expect(sent()).toEqual(['arm/arm1/control #255PDST!']);
  });

  it('back to Twin: the arm again, the copy let go (deadman 0, topics unsubscribed)', () => {
    const { client, copy, link, sent } = setup();
    link.setMode('model', copy);
    link.setMode('twin');
    expect(client.published).toContainEqual(
      expect.objectContaining({
        topic: 'arm/arm1-model/operator',
        payload: '0',
        retain: true,
      }),
    );
    expect(client.unsubscribed).toContain('arm/arm1-model/status');
    link.sendGroup('{#000P1500T0100!}');
    expect(sent()).toEqual(['arm/arm1/control {#000P1500T0100!}']);
  });
});
