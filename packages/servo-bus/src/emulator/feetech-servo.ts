/**
 * One emulated Feetech STS servo (STS3215): answers PING, READ, WRITE, REG_WRITE/ACTION as
 * the STS memory table says, replies only to PING and READ when Response Status Level is 0,
 * clamps goals to the angle limits (none when both limits are 0: multi-turn), makes the present
 * position read 2048 on Torque Enable = 128, and sets the status error flags from its health
 * (voltage outside its limits, temperature over its limit), dropping torque for those named in
 * Unloading Condition. It moves at Goal Speed (steps/s; full speed when 0); Acceleration and
 * Goal Time are not emulated. Writes to read-only fields and the EEPROM lock are ignored.
 */
import { decodeField, fieldAt, fieldRange, type ServoModel } from '../control-table.ts';
import {
  FEETECH_TORQUE_CALIBRATE_MIDDLE,
  FEETECH_VOLTAGE_UNIT_V,
  type StsField,
} from '../feetech/control-table.ts';
import type { Instruction } from '../instructions.ts';
import type { StatusPacket } from '../packet.ts';
import { FEETECH_ERROR_BITS } from '../status-errors.ts';
import { ServoBase } from './servo-base.ts';

export class FeetechServo extends ServoBase<StsField> {
  readonly protocol = 'feetech' as const;
  private registered: { address: number; data: Uint8Array } | undefined;

  constructor(model: ServoModel<StsField>, id: number, position: number) {
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
    return this.get('presentVoltage') * FEETECH_VOLTAGE_UNIT_V;
  }

  protected present(shaft: number): number {
    return Math.round(shaft) - this.get('homingOffset');
  }
  protected toShaft(present: number): number {
    return present + this.get('homingOffset');
  }
  protected targetShaft(): number {
    return this.toShaft(this.get('goalPosition'));
  }
  protected travelSpeed(): number {
    const speed = Math.abs(this.get('goalSpeed'));
    return speed > 0 ? speed : this.model.fullSpeedTicksPerS;
  }

  protected refresh(): void {
    this.set('presentPosition', this.present(this.shaft));
    this.set('presentSpeed', this.speedTicksPerS);
    this.set('moving', this.moving ? 1 : 0);
  }

  setVoltage(volts: number): void {
    this.set('presentVoltage', volts / FEETECH_VOLTAGE_UNIT_V);
    this.checkHealth();
  }

  /** The error flags the servo's state raises now (and any held in its Status field). */
  private errorFlags(): number {
    let flags = this.get('status');
    const v = this.get('presentVoltage');
    if (v < this.get('minVoltageLimit') || v > this.get('maxVoltageLimit'))
      flags |= FEETECH_ERROR_BITS.voltage;
    if (this.get('presentTemperature') > this.get('maxTemperatureLimit'))
      flags |= FEETECH_ERROR_BITS.overheat;
    return flags;
  }

  protected checkHealth(): void {
    if (this.errorFlags() & this.get('unloadingCondition')) this.set('torqueEnable', 0);
    this.refresh();
  }

  private status(params: Uint8Array = new Uint8Array(0)): StatusPacket {
    return { type: 'status', id: this.id, error: this.errorFlags(), params };
  }

  /** Response Status Level 0: only PING and READ answer; broadcasts answer only PING. */
  private reply(
    kind: 'ping' | 'read' | 'other',
    broadcast: boolean,
    params?: Uint8Array,
  ): StatusPacket | null {
    if (broadcast && kind !== 'ping') return null;
    if (kind === 'other' && this.get('responseStatusLevel') === 0) return null;
    return this.status(params);
  }

  checksumError(): StatusPacket | null {
    return null;
  }

  handle(ins: Instruction, broadcast: boolean): StatusPacket | null {
    switch (ins.op) {
      case 'ping':
        return this.reply('ping', broadcast);
      case 'read':
        return this.reply(
          'read',
          broadcast,
          this.readMemory(
            ins.address,
            Math.max(0, Math.min(ins.length, this.model.tableSize - ins.address)),
          ),
        );
      case 'write':
        this.write(ins.address, ins.data);
        return this.reply('other', broadcast);
      case 'reg-write':
        this.registered = { address: ins.address, data: ins.data };
        return this.reply('other', broadcast);
      case 'action':
        if (this.registered) this.write(this.registered.address, this.registered.data);
        this.registered = undefined;
        return this.reply('other', broadcast);
      case 'reboot':
      case 'sync-read':
      case 'sync-write':
        throw new Error(`${ins.op} is not a Feetech servo's to handle`);
      default: {
        const never: never = ins;
        throw new Error(`unhandled instruction ${String(never)}`);
      }
    }
  }

  private write(address: number, data: Uint8Array): void {
    const table = this.model.table;
    const torqueBefore = this.get('torqueEnable');
    const end = Math.min(address + data.length, this.model.tableSize);
    for (let a = address; a < end; a++) {
      const name = fieldAt(table, a);
      if (name && table[name].access === 'rw') this.mem[a] = data[a - address]!;
    }
    if (this.get('torqueEnable') === FEETECH_TORQUE_CALIBRATE_MIDDLE) {
      const { max } = fieldRange(table.homingOffset);
      this.set('homingOffset', Math.max(-max, Math.min(max, Math.round(this.shaft) - 2048)));
      this.set('torqueEnable', torqueBefore);
      this.set('goalPosition', this.present(this.shaft));
    }
    const goal = decodeField(table.goalPosition, this.mem, table.goalPosition.address);
    const min = this.get('minPositionLimit');
    const max = this.get('maxPositionLimit');
    if ((min !== 0 || max !== 0) && this.get('operatingMode') === 0)
      this.set('goalPosition', Math.min(max, Math.max(min, goal)));
    this.checkHealth();
  }
}
