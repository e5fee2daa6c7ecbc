/**
 * `armtwin up` from settings as the command has them (file paths, not loaded files): reads the
 * users file and the TLS certificate, says who may connect, starts the twin (./up.ts) and says
 * where the broker and each simulated arm are. The caller prints the URL and decides when to stop.
 */
import {
  describeSecurity,
  loadBrokerSecurity,
  type BrokerSecurity,
  type BrokerSecurityFiles,
} from '@armtwin/broker';
import { DEFAULT_PROFILE } from '@armtwin/sim';
import { SO101_ARM } from './so101-part.ts';
import { startUp, type Up, type UpOptions } from './up.ts';

export type RunUpOptions = Omit<UpOptions, keyof BrokerSecurity> & BrokerSecurityFiles;

export async function runUp(o: RunUpOptions): Promise<Up> {
  const { usersFile, tlsCert, tlsKey, ...options } = o;
  const security = loadBrokerSecurity({ usersFile, tlsCert, tlsKey });
  o.say(`security: ${describeSecurity(security, o.host)}`);
  const up = await startUp({ ...options, ...security });
  o.say(
    `broker: MQTT on ${up.broker.url}, MQTT over WebSockets on ${up.url.replace(/^http/, 'ws')}mqtt`,
  );
  const arms = o.arms?.length ? o.arms : [{ id: o.armId, profile: DEFAULT_PROFILE }];
  for (const a of arms)
    o.say(`simulated arm "${a.id}" (profile ${a.profile}) streaming at ${o.rate} Hz`);
  if (up.so101)
    o.say(
      `SO-101 "${o.so101}" (profile ${SO101_ARM.profile}) on an emulated Feetech bus, driven by the bus gateway over a pty pair in ${up.so101.ptyDir} (--no-so101 leaves it out)`,
    );
  return up;
}
