/**
 * The JSON schemas of the MCAP export's own messages (`armtwin.*` stored points); the topics it
 * shares with the live Foxglove server take that server's (@armtwin/foxglove/topics).
 */
const number = { type: 'number' } as const;
const timestamp = {
  type: 'object',
  properties: { sec: { type: 'integer', minimum: 0 }, nsec: { type: 'integer', minimum: 0 } },
} as const;

export const SCHEMAS = {
  servo: {
    title: 'armtwin.ServoSample',
    description: 'One stored servo point (PROTOCOL.md §6): a position or health report',
    type: 'object',
    properties: {
      timestamp,
      id: { type: 'string' },
      pwm: { type: 'integer', description: 'pulse width, µs' },
      angle: { ...number, description: 'servo angle, degrees' },
      temp: { ...number, description: '°C' },
      volt: { ...number, description: 'supply, V' },
    },
  },
  command: {
    title: 'armtwin.Command',
    description: 'One stored command point (PROTOCOL.md §6): what a servo was asked',
    type: 'object',
    properties: {
      timestamp,
      id: { type: 'string' },
      pwm: { type: 'integer' },
      angle: number,
      ms: { type: 'integer' },
    },
  },
  ik: {
    title: 'armtwin.IkResult',
    description: 'One stored $KMS outcome (PROTOCOL.md §4, §6)',
    type: 'object',
    properties: {
      timestamp,
      code: { type: 'integer' },
      x: number,
      y: number,
      z: number,
      a: number,
    },
  },
} as const;
