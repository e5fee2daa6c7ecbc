/**
 * What both emulated servos share: a memory laid out as the model's control table, a shaft
 * that turns toward the goal at a speed when torque is on and time advances, and setters the
 * simulator drives (temperature, voltage, a shaft moved by hand or by physics).
 */
import {
  decodeField,
  encodeField,
  fieldRange,
  initialMemory,
  type ServoModel,
} from '../control-table.ts';
import type { Instruction } from '../instructions.ts';
import type { StatusPacket } from '../packet.ts';
import type { BusProtocol } from '../protocols.ts';

/** How one emulated servo looks from outside the bus. */
export interface EmulatedServo {
  /** Its id now (a WRITE to the ID field changes it). */
  readonly id: number;
  readonly model: ServoModel;
  readonly protocol: BusProtocol;
  /** Present position as the servo reports it, ticks. */
  readonly position: number;
  /** Goal position as written, ticks. */
  readonly goal: number;
  readonly torque: boolean;
  readonly moving: boolean;
  readonly temperatureC: number;
  readonly voltageV: number;
  /** The value of a field of the control table, by name. */
  field(name: string): number;
  /** Sets the temperature the servo reads (°C), with the protections that follow from it. */
  setTemperature(celsius: number): void;
  /** Sets the input voltage the servo reads (V), with the protections that follow from it. */
  setVoltage(volts: number): void;
  /** Puts the shaft at a present position (ticks): moved by hand, or by the simulator's physics. */
  setPosition(ticks: number): void;
  /**
   * Sets a control-table field as the servo's own memory holds it (read-only ones too: a
   * firmware version, a model number, Feetech's Status error bits), for faults a test or the
   * simulator injects; the protections that follow from it apply.
   */
  setField(name: string, value: number): void;
}

/** The bus's side of a servo: instructions in, a status packet (or none) out, time passing. */
export interface BusServo extends EmulatedServo {
  /** The reply to an instruction for this servo; `broadcast` when it came to id 254. */
  handle(ins: Instruction, broadcast: boolean): StatusPacket | null;
  /** The reply to an instruction that arrived with a bad checksum, if the bus replies to one. */
  checksumError(): StatusPacket | null;
  /** Turns toward the goal for `dtMs` milliseconds. */
  advance(dtMs: number): void;
}

export abstract class ServoBase<F extends string> implements BusServo {
  protected readonly mem: Uint8Array;
  /** The shaft, in encoder ticks (fractional: it moves a little each advance). */
  protected shaft: number;
  /** Signed speed during the last advance, ticks/s. */
  protected speedTicksPerS = 0;

  constructor(
    readonly model: ServoModel<F>,
    id: number,
    position: number,
  ) {
    this.mem = initialMemory(model);
    this.shaft = position;
    this.set('id' as F, id);
  }

  abstract readonly protocol: BusProtocol;
  abstract handle(ins: Instruction, broadcast: boolean): StatusPacket | null;
  abstract checksumError(): StatusPacket | null;
  /** Where the shaft is heading, encoder ticks. */
  protected abstract targetShaft(): number;
  /** How fast it turns there, ticks/s. */
  protected abstract travelSpeed(): number;
  /** Writes the present-state fields (position, speed, moving…) from the shaft. */
  protected abstract refresh(): void;
  /** Shaft ticks → reported present position (homing offset applied). */
  protected abstract present(shaft: number): number;
  /** Reported present position → shaft ticks. */
  protected abstract toShaft(present: number): number;
  protected abstract checkHealth(): void;
  abstract readonly torque: boolean;

  get id(): number {
    return this.get('id' as F);
  }
  get position(): number {
    return this.get('presentPosition' as F);
  }
  get goal(): number {
    return this.get('goalPosition' as F);
  }
  get moving(): boolean {
    return this.torque && Math.abs(this.targetShaft() - this.shaft) > 1e-9;
  }
  abstract readonly temperatureC: number;
  abstract readonly voltageV: number;

  field(name: string): number {
    if (!(name in this.model.table)) throw new Error(`${this.model.name} has no field ${name}`);
    this.refresh();
    return this.get(name as F);
  }

  protected get(name: F): number {
    return decodeField(this.model.table[name], this.mem, this.model.table[name].address);
  }

  /** Stores a value, clamped to what the field can hold. */
  protected set(name: F, value: number): void {
    const f = this.model.table[name];
    const { min, max } = fieldRange(f);
    this.mem.set(encodeField(f, Math.min(max, Math.max(min, Math.round(value))), name), f.address);
  }

  /** Memory as a READ returns it, present state refreshed first. */
  protected readMemory(address: number, length: number): Uint8Array {
    this.refresh();
    return this.mem.slice(address, address + length);
  }

  advance(dtMs: number): void {
    const dt = Math.max(0, dtMs) / 1000;
    const target = this.targetShaft();
    const diff = target - this.shaft;
    if (!this.torque || diff === 0 || dt === 0) {
      this.speedTicksPerS = 0;
    } else {
      const speed = this.travelSpeed();
      const step = speed * dt;
      if (Math.abs(diff) <= step) {
        this.shaft = target;
        this.speedTicksPerS = 0;
      } else {
        this.shaft += Math.sign(diff) * step;
        this.speedTicksPerS = Math.sign(diff) * speed;
      }
    }
    this.refresh();
  }

  setTemperature(celsius: number): void {
    this.set('presentTemperature' as F, celsius);
    this.checkHealth();
  }

  setPosition(ticks: number): void {
    this.shaft = this.toShaft(ticks);
    this.refresh();
  }

  setField(name: string, value: number): void {
    if (!(name in this.model.table)) throw new Error(`${this.model.name} has no field ${name}`);
    this.set(name as F, value);
    this.checkHealth();
  }

  abstract setVoltage(volts: number): void;
}
