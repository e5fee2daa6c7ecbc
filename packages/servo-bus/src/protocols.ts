/** The servo buses this package speaks, declared once. */
export const BUS_PROTOCOLS = ['dynamixel', 'feetech'] as const;
export type BusProtocol = (typeof BUS_PROTOCOLS)[number];

/** The id every servo on the bus listens to (both vendors). */
export const BROADCAST_ID = 0xfe;
/** Highest id a single servo may have: 252 on Dynamixel 2.0, 253 on Feetech. */
export const MAX_SERVO_ID: Record<BusProtocol, number> = { dynamixel: 0xfc, feetech: 0xfd };

export const isBusProtocol = (value: string): value is BusProtocol =>
  (BUS_PROTOCOLS as readonly string[]).includes(value);
