/** The doctor's line to an emulated bus (tests, the simulator): the host's baud rate is told to
 * the bus, so a servo set to another rate hears nothing, as on a wire. */
import type { EmulatedBus } from '../emulator/emulated-bus.ts';
import type { DoctorLink } from './scan.ts';

export const emulatedDoctorLink = (bus: EmulatedBus): DoctorLink => ({
  setBaud: (baud) => Promise.resolve(bus.setLineBaud(baud)),
  exchange: (bytes) => Promise.resolve(bus.feed(bytes)),
});
