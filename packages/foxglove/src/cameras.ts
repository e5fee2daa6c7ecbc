/**
 * Each arm's cameras as Foxglove image channels: every camera announced on
 * `arm/{arm}/camera/{cam}` (PROTOCOL.md §7) with an MJPEG stream (its main one or an alternate)
 * is advertised as `/{arm}/camera/{cam}`, `foxglove.CompressedImage` (JSON, `format` `jpeg`,
 * `frame_id` `{arm}/camera/{cam}`); an empty announcement removes it, a repeated one
 * keeps it. Each subscription reads
 * the stream itself (./camera-stream.ts) with its client's own log-in, so the camera server's
 * access rules apply to each Foxglove user as to the HUD; nothing is read while nobody watches.
 */
import type { MqttClient } from 'mqtt';
import type { WebSocket } from 'ws';
import { StatusLevel } from '@foxglove/ws-protocol';
import { CompressedImage } from '@foxglove/schemas/jsonschema';
import { CLEAN_SESSION_SUBSCRIBE_QOS } from '@armtwin/protocol';
import { cameraStreams, parseCameraMessage, parseCameraTopic } from '@armtwin/camera/announcement';
import type { FoxgloveServer } from './ws-protocol.ts';
import { cameraChannelTopic } from './topics.ts';
import { messageData } from './latched.ts';
import { stampOf } from './channels.ts';
import { readMjpeg, type MjpegReader } from './camera-stream.ts';

export interface Camera {
  armId: string;
  camId: string;
  /** The MJPEG stream's URL. */
  url: string;
}

export interface CameraCounts {
  /** Announcements that were not a camera (bad topic, bad payload), or had no MJPEG stream. */
  unusable: number;
  /** Frames sent to subscriptions, and those dropped for a client that is behind. */
  frames: number;
  dropped: number;
  /** Streams that failed or ended (told to the client as a status). */
  streamErrors: number;
}

/** A client this far behind (bytes queued on its socket) is sent no frame until it catches up. */
export const MAX_BUFFERED_BYTES = 8 * 1024 * 1024;

const SPEC = {
  encoding: 'json',
  schemaName: CompressedImage.title,
  schema: JSON.stringify(CompressedImage),
  schemaEncoding: 'jsonschema',
} as const;

export class CameraChannels {
  readonly counts: CameraCounts = { unusable: 0, frames: 0, dropped: 0, streamErrors: 0 };
  /** Cameras by channel id. */
  readonly byChannel = new Map<number, Camera>();
  private readonly byTopic = new Map<string, number>();

  constructor(
    private readonly fox: FoxgloveServer,
    mqtt: MqttClient,
  ) {
    mqtt.on('message', (t, payload) => {
      if (parseCameraTopic(t)) this.onAnnouncement(t, payload);
    });
    const subscribe = () => mqtt.subscribe('arm/+/camera/+', { qos: CLEAN_SESSION_SUBSCRIBE_QOS });
    mqtt.on('connect', subscribe);
    if (mqtt.connected) subscribe();
  }

  private onAnnouncement(t: string, payload: Buffer): void {
    const m = parseCameraMessage(t, payload);
    const mjpeg = m.type === 'camera' && cameraStreams(m.camera).find((s) => s.kind === 'mjpeg');
    const known = this.byTopic.get(t);
    // the same camera again (a repeated retained message), or a new URL: the channel stays, so
    // a client subscribing meanwhile keeps it; a new subscription reads the new URL
    if (known !== undefined && mjpeg) return void (this.byChannel.get(known)!.url = mjpeg.url);
    if (known !== undefined) {
      this.fox.removeChannel(known);
      this.byChannel.delete(known);
      this.byTopic.delete(t);
    }
    if (m.type === 'removed') return;
    if (m.type !== 'camera' || !mjpeg) return void this.counts.unusable++;
    const id = this.fox.addChannel({ topic: cameraChannelTopic(m.armId, m.camId), ...SPEC });
    this.byChannel.set(id, { armId: m.armId, camId: m.camId, url: mjpeg.url });
    this.byTopic.set(t, id);
  }

  /**
   * Streams a camera to each of `ws`'s subscriptions to one, read with `authorization` (the
   * client's own log-in; null: none, the anonymous demo). Returns what to call as it goes.
   */
  client(ws: WebSocket, authorization: string | null) {
    const readers = new Map<number, MjpegReader>();
    const tell = (message: string) =>
      this.fox.sendStatus({ level: StatusLevel.WARNING, message }, ws);
    return {
      subscribe: (subId: number, channelId: number) => {
        const cam = this.byChannel.get(channelId);
        if (!cam) return;
        const frameId = `${cam.armId}/camera/${cam.camId}`;
        readers.set(
          subId,
          readMjpeg(cam.url, authorization, {
            onFrame: (jpeg, ms) => {
              if (ws.bufferedAmount > MAX_BUFFERED_BYTES) return void this.counts.dropped++;
              const { ns, time } = stampOf(ms);
              const body = JSON.stringify({
                timestamp: time,
                frame_id: frameId,
                format: 'jpeg',
                data: Buffer.from(jpeg).toString('base64'),
              });
              ws.send(messageData(subId, ns, Buffer.from(body)));
              this.counts.frames++;
            },
            onEnd: (why) => {
              this.counts.streamErrors++;
              tell(`/${frameId}: ${why}`);
            },
          }),
        );
      },
      unsubscribe: (subId: number) => {
        readers.get(subId)?.stop();
        readers.delete(subId);
      },
      close: () => {
        for (const r of readers.values()) r.stop();
        readers.clear();
      },
    };
  }
}
