/// <reference lib="dom" />
/**
 * What the robots, fleet and plan specs (../robots-*.spec.ts) read of the page's debug hook
 * `window.__armtwin` (the URDF joint values as drawn, the active robot, the plan runner, the
 * waypoints) and do on the page (waypoints typed into the Plan panel).
 */
import type { Page } from '@playwright/test';

export interface RobotsWindow {
  __armtwin?: {
    joints(which?: 'robot' | 'ghost'): number[];
    robots: {
      active: { spec: { name: string }; motion: unknown; source: string };
      runner: { state: string; replans: number; pauses: number; sent: number };
      waypoints: { list: { x: number; y: number; z: number }[] };
      editor: { screenPoint(i: number): { x: number; y: number } | null } | null;
    };
  };
}

/** The live arm's (or the ghost's) URDF joint values as drawn. */
export const joints = (page: Page, which: 'robot' | 'ghost' = 'robot') =>
  page.evaluate((w) => (window as unknown as RobotsWindow).__armtwin!.joints(w), which);

/** The plan runner's state and counters. */
export const runner = (page: Page) =>
  page.evaluate(() => {
    const r = (window as unknown as RobotsWindow).__armtwin!.robots.runner;
    return { state: r.state, replans: r.replans, pauses: r.pauses, sent: r.sent };
  });

/** Adds one waypoint per point with the Plan panel's button, then types each one's x, y, z (mm). */
export async function addWaypoints(
  page: Page,
  points: readonly { x: number; y: number; z: number }[],
): Promise<void> {
  const add = page.getByRole('button', { name: 'Add waypoint at tip' });
  for (let i = 0; i < points.length; i++) await add.click();
  for (const [i, p] of points.entries()) {
    await page.getByLabel(`Waypoint ${i + 1} X`).fill(String(p.x));
    await page.getByLabel(`Waypoint ${i + 1} Y`).fill(String(p.y));
    await page.getByLabel(`Waypoint ${i + 1} Z`).fill(String(p.z));
  }
}
