/**
 * Who may watch a camera server (`@armtwin/camera`) that has a users file, against real ffmpeg
 * (Debian's test source): an anonymous viewer gets 401 on both kinds of stream and on the
 * metrics, a viewer's or operator's log-in is let in, a device may watch only its own arm's
 * camera. (The streams themselves: camera-server.test.ts.)
 */
import path from 'node:path';
import { beforeAll, describe, expect, test } from 'vitest';
import { LoginThrottle, loadUsers } from '@armtwin/auth';
import type { ServedCameras } from '@armtwin/camera';
import { openH264, openMjpeg } from '../helpers/camera-viewers.ts';
import { REPO_ROOT } from '../helpers/files.ts';
import { until } from '../helpers/until.ts';
import { useCameraServers } from '../helpers/use-camera-servers.ts';

const start = useCameraServers();
const USERS_FILE = path.join(REPO_ROOT, 'deploy', 'users.example.json');
const basic = (user: string) => `Basic ${Buffer.from(`${user}:${user}-demo`).toString('base64')}`;

describe('camera server with a users file', () => {
  let cam: ServedCameras;
  beforeAll(async () => {
    cam = await start({ access: { logins: new LoginThrottle(loadUsers(USERS_FILE)), token: '' } });
  });

  test('an anonymous viewer gets 401, a viewer’s log-in gets the stream, a device of another arm 403', async () => {
    const url = `${cam.url}/camera/front.mjpeg`;
    const anonymous = await fetch(url);
    expect(anonymous.status).toBe(401);
    expect(anonymous.headers.get('www-authenticate')).toBe('Basic realm="armtwin"');
    expect((await fetch(`${cam.url}/camera/metrics`)).status).toBe(401);
    expect((await fetch(url, { headers: { authorization: basic('arm2') } })).status).toBe(403);

    const viewer = await openMjpeg(url, basic('viewer'));
    expect(viewer.res.status).toBe(200);
    await until(() => viewer.parts.length >= 2, 15_000, 'a JPEG for the viewer');
    await viewer.stop();

    const wsUrl = `${cam.url.replace('http', 'ws')}/camera/front.h264`;
    const refused = await openH264(wsUrl);
    expect(refused.opened).toBe(401);
    refused.close();
    const auth = encodeURIComponent(Buffer.from('operator:operator-demo').toString('base64'));
    const operator = await openH264(`${wsUrl}?auth=${auth}`);
    expect(operator.opened).toBe(101);
    await until(() => operator.messages.length >= 1, 15_000, 'an access unit for the operator');
    expect(operator.messages[0]!.key).toBe(true);
    operator.close();
    const arm1 = await openH264(
      `${wsUrl}?auth=${encodeURIComponent(Buffer.from('arm1:arm1-demo').toString('base64'))}`,
    );
    expect(arm1.opened).toBe(101); // a device may watch its own arm's camera
    arm1.close();
  });
});
