import { describe, expect, test } from 'vitest';
import { EMERGENCY_STOP, perishesWithConnection } from '../src/index.ts';

describe('perishesWithConnection: what is sent on its own connection or never', () => {
  test.each([
    ['arm/arm1/claim/alice', 'take'],
    ['arm/arm1/claim/alice', 'beat'],
    ['arm/arm1/claim/alice', 'release'],
    ['arm/arm1-model/claim/bob', 'take'],
    ['arm/arm1/override/root', 'take'],
    ['arm/arm1/control', '#000P1500T0500!'],
    ['arm/arm1/control/alice', '$KMS:100,0,150,500!'],
    ['arm/arm1/control/alice', '#000PDST!#001P1500T0100!'],
    ['arm/arm1/request/alice', '{"id":"r1","to":{"x":1}}'],
  ])('%s %s perishes', (topic, payload) => {
    expect(perishesWithConnection(topic, payload)).toBe(true);
    expect(perishesWithConnection(topic, new TextEncoder().encode(payload))).toBe(true);
  });

  test.each([
    ['arm/arm1/control/alice', EMERGENCY_STOP],
    ['arm/arm1/control', EMERGENCY_STOP],
    ['arm/arm1/control/alice', '#000PDST!#001PDST!'],
    ['arm/arm1/status', '$TIM:1!'],
    ['arm/arm1/operator', '1'],
    ['arm/arm1/torque', '0'],
    ['arm/bad id/claim/alice', 'take'],
    ['something/else', 'take'],
  ])('%s %s is kept (sent on the next connection)', (topic, payload) => {
    expect(perishesWithConnection(topic, payload)).toBe(false);
    expect(perishesWithConnection(topic, new TextEncoder().encode(payload))).toBe(false);
  });
});
