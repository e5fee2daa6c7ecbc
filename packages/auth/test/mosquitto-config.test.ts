/** The Mosquitto 2.0 configuration generated from the users file (`armtwin deploy-mosquitto`). */
import { describe, expect, test } from 'vitest';
import { hashPassword, parseUsers } from '@armtwin/auth';
import { mosquittoAcl, mosquittoConf, mosquittoPasswd } from '../src/mosquitto-config.ts';

describe('Mosquitto configuration', () => {
  const h = hashPassword('pw', { iterations: 10 });
  const users = parseUsers(
    JSON.stringify({
      users: [
        { name: 'op', role: 'operator', password: h },
        { name: 'arm9', role: 'device', arm: 'arm9', password: h },
      ],
    }),
  ).list;

  test('no anonymous access, password and ACL files, packet bound, TLS listeners', () => {
    const conf = mosquittoConf({
      confDir: '/etc/x',
      certfile: '/c.pem',
      keyfile: '/k.pem',
      cafile: '/ca.pem',
    });
    for (const line of [
      'per_listener_settings false',
      'allow_anonymous false',
      'password_file /etc/x/passwd',
      'acl_file /etc/x/acl',
      'max_packet_size 65536',
      'listener 1883 127.0.0.1',
      'listener 8883',
      'protocol websockets',
      'certfile /c.pem',
      'keyfile /k.pem',
      'cafile /ca.pem',
    ])
      expect(conf.split('\n')).toContain(line);
    expect(conf).not.toMatch(/allow_anonymous true/);
  });

  test('passwd holds name:hash; acl a user block per user with the role filled in', () => {
    expect(mosquittoPasswd(users)).toBe(`op:${h}\narm9:${h}\n`);
    const acl = mosquittoAcl(users);
    expect(acl).toContain('user op\ntopic read arm/+/status');
    expect(acl).toContain('topic readwrite arm/+/operator');
    expect(acl).toContain('topic write arm/+/control');
    expect(acl).toContain('user arm9\ntopic read arm/arm9/control');
    expect(acl).toContain('topic write arm/arm9/status');
    expect(acl).toContain('topic read arm/+/camera/+');
    expect(acl).toContain('topic write arm/arm9/camera/+');
    expect(acl).not.toMatch(/^pattern/m);
  });
});
