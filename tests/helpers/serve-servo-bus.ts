/**
 * Serves an emulated servo bus (`@armtwin/servo-bus`) on a serial port, for the SDK
 * integration test: bytes from the port go into the bus, its answers go back out, and the
 * shafts advance on the wall clock (every 5 ms, and before each chunk is handled, so a read
 * sees where the servo is now). Stands in for `armtwin sim --bus` until that exists.
 *
 *     node --import tsx tests/helpers/serve-servo-bus.ts --protocol dynamixel --port /dev/pts/7 \
 *       --baud 57600 --servos '[{"id":1},{"id":2,"model":"XL430-W250"}]'
 *
 * Prints one line `servo bus ready` once the port is open; exits on SIGTERM or SIGINT.
 */
import { parseArgs } from 'node:util';
import { SerialPort } from 'serialport';
import { createEmulatedBus, isBusProtocol, type EmulatedServoSpec } from '@armtwin/servo-bus';

const { values } = parseArgs({
  options: {
    protocol: { type: 'string' },
    port: { type: 'string' },
    baud: { type: 'string', default: '1000000' },
    servos: { type: 'string' },
  },
});
if (!values.protocol || !isBusProtocol(values.protocol) || !values.port || !values.servos) {
  console.error(
    'usage: serve-servo-bus.ts --protocol dynamixel|feetech --port PATH [--baud N] --servos JSON',
  );
  process.exit(2);
}

const bus = createEmulatedBus({
  protocol: values.protocol,
  servos: JSON.parse(values.servos) as EmulatedServoSpec[],
  startMs: Date.now(),
});
const port = new SerialPort({ path: values.port, baudRate: Number(values.baud), autoOpen: false });

port.on('data', (chunk: Buffer) => {
  bus.advance(Date.now());
  const answer = bus.feed(chunk);
  if (answer.length > 0) port.write(Buffer.from(answer));
});
port.on('error', (err) => console.error(`serial port: ${err.message}`));
const ticker = setInterval(() => bus.advance(Date.now()), 5);

function stop() {
  clearInterval(ticker);
  console.log(`counters ${JSON.stringify(bus.counters)}`);
  port.close(() => process.exit(0));
  setTimeout(() => process.exit(0), 1000).unref();
}
process.on('SIGTERM', stop);
process.on('SIGINT', stop);

port.open((err) => {
  if (err) {
    console.error(`cannot open ${values.port}: ${err.message}`);
    process.exit(1);
  }
  console.log('servo bus ready');
});
