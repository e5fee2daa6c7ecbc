/**
 * The Foxglove layout deploy/foxglove/armtwin-arm.json as the tests read it: its panels and every
 * topic it reads, so a recording (export-foxglove.test.ts) and a live server
 * (foxglove-camera-plan.test.ts) can each be checked to carry them.
 */
import fs from 'node:fs';
import path from 'node:path';
import { REPO_ROOT } from './files.ts';

export interface Layout {
  configById: Record<string, unknown>;
}
export interface ThreeD {
  topics: Record<string, { visible?: boolean }>;
  layers: Record<
    string,
    { layerId: string; sourceType?: string; topic?: string; framePrefix?: string }
  >;
}
export interface Plot {
  paths: { value: string }[];
}

export const readLayout = (): Layout =>
  JSON.parse(
    fs.readFileSync(path.join(REPO_ROOT, 'deploy/foxglove/armtwin-arm.json'), 'utf8'),
  ) as Layout;

/** The layout's panels by kind (the part of the panel id before `!`). */
export function layoutPanels(layout: Layout) {
  const panels = Object.entries(layout.configById);
  const find = <T>(kind: string) => panels.find(([id]) => id.startsWith(`${kind}!`))?.[1] as T;
  return {
    threeD: find<ThreeD>('3D'),
    plot: find<Plot>('Plot'),
    log: find<{ topicToRender: string }>('RosOut'),
    image: find<{ imageMode: { imageTopic: string } }>('Image'),
  };
}

/** Every topic the layout reads. */
export function layoutTopics(layout: Layout): string[] {
  const { threeD, plot, log, image } = layoutPanels(layout);
  return [
    ...Object.keys(threeD.topics),
    ...Object.values(threeD.layers).flatMap((l) => (l.topic ? [l.topic] : [])),
    ...plot.paths.map((p) => p.value.slice(0, p.value.indexOf('.'))),
    log.topicToRender,
    image.imageMode.imageTopic,
  ];
}

/** Topics only the live server has (a recording holds no cameras, plans or servo health). */
export const liveOnly = (topic: string): boolean =>
  /^\/[a-z0-9-]+\/(health|plan|plan_tf|camera\/[a-z0-9-]+)$/.test(topic);
