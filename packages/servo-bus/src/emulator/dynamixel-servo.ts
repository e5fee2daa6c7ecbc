/**
 * One emulated Dynamixel X-series servo behind Protocol 2.0, as the e-Manual describes it:
 * Status Return Level, EEPROM locked while torque is on, goal limits per operating mode
 * (position: Min/Max Position Limit; extended position: ±256 turns), whole-field writes,
 * REG_WRITE/ACTION, REBOOT, and Hardware Error Status with its alert bit and Shutdown.
 * It moves at Profile Velocity (Velocity Limit when 0); Profile Acceleration is not emulated.
 */
import { decodeField, fieldAt, type ServoModel } from '../control-table.ts';
import {
  DYNAMIXEL_EXTENDED_POSITION_LIMIT,
  DYNAMIXEL_OPERATING_MODES,
  DYNAMIXEL_VELOCITY_UNIT_RPM,
  DYNAMIXEL_VOLTAGE_UNIT_V,
  type XSeriesField,
} from '../dynamixel/control-table.ts';
import type { Instruction } from '../instructions.ts';
import type { StatusPacket } from '../packet.ts';
import {
  DYNAMIXEL_HARDWARE_ERRORS,
  dynamixelErrorByte,
  type DynamixelError,
} from '../status-errors.ts';
import { ServoBase } from './servo-base.ts';

const TICKS_PER_S_PER_UNIT = (DYNAMIXEL_VELOCITY_UNIT_RPM * 4096) / 60;

export class DynamixelServo extends ServoBase<XSeriesField> {
  readonly protocol = 'dynamixel' as const;
  private registered: { address: number; data: Uint8Array } | undefined;
  private clockMs = 0;

  constructor(model: ServoModel<XSeriesField>, id: number, position: number) {
    super(model, id, position);
    this.set('goalPosition', position);
    this.refresh();
  }

  get torque(): boolean {
    return this.get('torqueEnable') === 1;
  }
  get temperatureC(): number {
    return this.get('presentTemperature');
  }
  get voltageV(): number {
    return this.get('presentInputVoltage') * DYNAMIXEL_VOLTAGE_UNIT_V;
  }

  protected present(shaft: number): number {
    return Math.round(shaft) + this.get('homingOffset');
  }
  protected toShaft(present: number): number {
    return present - this.get('homingOffset');
  }
  protected targetShaft(): number {
    return this.toShaft(this.get('goalPosition'));
  }
  protected travelSpeed(): number {
    const limit = this.get('velocityLimit');
    const profile = this.get('profileVelocity');
    return (
      (profile > 0 && (limit === 0 || profile < limit) ? profile : limit) * TICKS_PER_S_PER_UNIT
    );
  }

  protected refresh(): void {
    this.set('presentPosition', this.present(this.shaft));
    this.set('presentVelocity', this.speedTicksPerS / TICKS_PER_S_PER_UNIT);
    this.set('moving', this.moving ? 1 : 0);
    this.set('movingStatus', this.torque && !this.moving ? 1 : 0);
    this.set('realtimeTick', this.clockMs % 32768);
  }

  override advance(dtMs: number): void {
    this.clockMs += Math.max(0, dtMs);
    super.advance(dtMs);
  }

  setVoltage(volts: number): void {
    this.set('presentInputVoltage', volts / DYNAMIXEL_VOLTAGE_UNIT_V);
    this.checkHealth();
  }

  /** Latches Hardware Error Status bits; torque goes off for those Shutdown names. */
  protected checkHealth(): void {
    let bits = this.get('hardwareErrorStatus');
    const v = this.get('presentInputVoltage');
    if (v < this.get('minVoltageLimit') || v > this.get('maxVoltageLimit'))
      bits |= DYNAMIXEL_HARDWARE_ERRORS['input-voltage'];
    if (this.get('presentTemperature') > this.get('temperatureLimit'))
      bits |= DYNAMIXEL_HARDWARE_ERRORS.overheating;
    this.set('hardwareErrorStatus', bits);
    if (bits & this.get('shutdown')) this.set('torqueEnable', 0);
    this.refresh();
  }

  private status(
    error: DynamixelError | null,
    params: Uint8Array = new Uint8Array(0),
  ): StatusPacket {
    return {
      type: 'status',
      id: this.id,
      error: dynamixelErrorByte(error, this.get('hardwareErrorStatus') !== 0),
      params,
    };
  }

  /** Status Return Level: 0 answers PING only, 1 also READ, 2 everything. */
  private reply(
    kind: 'ping' | 'read' | 'other',
    packet: StatusPacket,
    broadcast: boolean,
  ): StatusPacket | null {
    if (broadcast && kind !== 'ping') return null;
    const level = this.get('statusReturnLevel');
    if (kind === 'other' && level < 2) return null;
    if (kind === 'read' && level < 1) return null;
    return packet;
  }

  checksumError(): StatusPacket | null {
    return this.reply('other', this.status('crc'), false);
  }

  handle(ins: Instruction, broadcast: boolean): StatusPacket | null {
    switch (ins.op) {
      case 'ping': {
        const p = new Uint8Array(3);
        p[0] = this.get('modelNumber') & 0xff;
        p[1] = this.get('modelNumber') >> 8;
        p[2] = this.get('firmwareVersion');
        return this.reply('ping', this.status(null, p), broadcast);
      }
      case 'read': {
        if (ins.address + ins.length > this.model.tableSize || ins.length === 0)
          return this.reply('read', this.status('access'), broadcast);
        return this.reply(
          'read',
          this.status(null, this.readMemory(ins.address, ins.length)),
          broadcast,
        );
      }
      case 'write':
        return this.reply('other', this.status(this.write(ins.address, ins.data)), broadcast);
      case 'reg-write': {
        const error = this.check(ins.address, ins.data);
        if (!error) {
          this.registered = { address: ins.address, data: ins.data };
          this.mem[this.model.table.registeredInstruction.address] = 1;
        }
        return this.reply('other', this.status(error), broadcast);
      }
      case 'action': {
        const reg = this.registered;
        this.registered = undefined;
        this.mem[this.model.table.registeredInstruction.address] = 0;
        const error = reg ? this.write(reg.address, reg.data) : null;
        return this.reply('other', this.status(error), broadcast);
      }
      case 'reboot': {
        const reply = this.reply('other', this.status(null), broadcast);
        this.reboot();
        return reply;
      }
      case 'sync-read':
      case 'sync-write':
        throw new Error(`${ins.op} is dispatched by the bus`);
      default: {
        const never: never = ins;
        throw new Error(`unhandled instruction ${String(never)}`);
      }
    }
  }

  /** Checks then writes; nothing is written when the check fails. */
  private write(address: number, data: Uint8Array): DynamixelError | null {
    const error = this.check(address, data);
    if (error) return error;
    const modeBefore = this.get('operatingMode');
    this.mem.set(data, address);
    if (
      this.get('operatingMode') !== modeBefore &&
      this.get('operatingMode') === DYNAMIXEL_OPERATING_MODES.position
    ) {
      // Back to single-turn: the position wraps into one turn.
      this.shaft = this.toShaft(((this.present(this.shaft) % 4096) + 4096) % 4096);
      this.set('goalPosition', this.present(this.shaft));
    }
    this.refresh();
    return null;
  }

  /** Why this write would be refused, as the e-Manual's error numbers, or null. */
  private check(address: number, data: Uint8Array): DynamixelError | null {
    const table = this.model.table;
    if (data.length === 0 || address + data.length > this.model.tableSize) return 'access';
    const after = new Uint8Array(this.mem);
    after.set(data, address);
    for (let a = address; a < address + data.length;) {
      const name = fieldAt(table, a);
      if (!name) return 'access';
      const f = table[name];
      if (f.address < address || f.address + f.size > address + data.length) return 'data-length';
      if (f.access === 'r') return 'access';
      if (f.area === 'eeprom' && this.torque) return 'access';
      const value = decodeField(f, after, f.address);
      const error = this.checkValue(name, value, after);
      if (error) return error;
      a = f.address + f.size;
    }
    return null;
  }

  private checkValue(name: XSeriesField, value: number, after: Uint8Array): DynamixelError | null {
    const t = this.model.table;
    const v = (n: XSeriesField) => decodeField(t[n], after, t[n].address);
    // eslint-disable-next-line @typescript-eslint/switch-exhaustiveness-check -- only these fields have rules; every other is plain memory
    switch (name) {
      case 'torqueEnable':
        if (value > 1) return 'data-range';
        return value === 1 && this.get('hardwareErrorStatus') & this.get('shutdown')
          ? 'result-fail'
          : null;
      case 'operatingMode':
        return Object.values(DYNAMIXEL_OPERATING_MODES).includes(value as 3 | 4)
          ? null
          : 'data-range';
      case 'id':
        return value > 252 ? 'data-range' : null;
      case 'goalPosition':
        if (v('operatingMode') === DYNAMIXEL_OPERATING_MODES.extendedPosition)
          return Math.abs(value) > DYNAMIXEL_EXTENDED_POSITION_LIMIT ? 'data-limit' : null;
        return value < v('minPositionLimit') || value > v('maxPositionLimit') ? 'data-limit' : null;
      case 'profileVelocity':
        return value > 32767 ? 'data-range' : null;
      default:
        return null;
    }
  }

  /** REBOOT: RAM back to its power-on values, torque off, errors cleared unless still true. */
  private reboot(): void {
    for (const name of Object.keys(this.model.table) as XSeriesField[]) {
      const f = this.model.table[name];
      if (f.area !== 'ram' || f.access === 'r' || name === 'goalPosition') continue;
      this.set(name, this.model.defaults[name] ?? 0);
    }
    this.set('hardwareErrorStatus', 0);
    this.registered = undefined;
    this.speedTicksPerS = 0;
    this.set('goalPosition', this.present(this.shaft));
    this.checkHealth();
  }
}
