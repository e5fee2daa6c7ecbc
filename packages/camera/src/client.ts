/**
 * What a viewer needs, browser-safe (no `node:` imports): the §7 announcement, the `h264-ws`
 * message header, the NAL-unit helpers for WebCodecs, the multipart reader for an MJPEG stream
 * read with `fetch`, the time-stripe reader for latency measurements, and a camera's calibration
 * (its retained pose and fov, and the four-point solver).
 * `import … from '@armtwin/camera/client'`.
 */
export * from './announcement.ts';
export * from './wire.ts';
export * from './nal.ts';
export * from './multipart-parser.ts';
export * from './time-stripe.ts';
export * from './calibration.ts';
export * from './camera-solve.ts';
