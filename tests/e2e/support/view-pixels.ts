/// <reference lib="dom" />
/**
 * What the 3D view and a camera's picture show, read in the page (no screenshots to decode):
 * `snapView` copies the 3D view's canvas right after the Viewer renders (a render hook, so the
 * WebGL drawing buffer is still there) into a fixed-size 2D canvas kept in the page by name;
 * the comparisons run in the page over those snapshots and return a few numbers.
 */
import type { Locator, Page } from '@playwright/test';

/** Snapshot size: the same whatever the view's resolution (the governor may change it). */
export const SNAP_W = 480;
export const SNAP_H = 270;

interface SnapWindow {
  __armtwin: {
    viewer: {
      canvas: HTMLCanvasElement;
      renderHooks: Set<(now: number) => void>;
      invalidate(): void;
      liveRobot: { visible: boolean } | null;
    };
  };
  __snaps?: Record<string, Uint8ClampedArray>;
}

/** Takes the next rendered frame of the 3D view as snapshot `name`. */
export function snapView(page: Page, name: string): Promise<void> {
  return page.evaluate(
    async ({ name, w, h }) => {
      const win = window as unknown as SnapWindow;
      const v = win.__armtwin.viewer;
      const out = document.createElement('canvas');
      out.width = w;
      out.height = h;
      const ctx = out.getContext('2d')!;
      await new Promise<void>((resolve) => {
        const hook = () => {
          ctx.drawImage(v.canvas, 0, 0, w, h);
          v.renderHooks.delete(hook);
          resolve();
        };
        v.renderHooks.add(hook);
        v.invalidate();
      });
      (win.__snaps ??= {})[name] = ctx.getImageData(0, 0, w, h).data;
    },
    { name, w: SNAP_W, h: SNAP_H },
  );
}

/** Shows or hides the live twin (to see the picture alone behind it). */
export function showTwin(page: Page, visible: boolean): Promise<void> {
  return page.evaluate((visible) => {
    const v = (window as unknown as SnapWindow).__armtwin.viewer;
    v.liveRobot!.visible = visible;
    v.invalidate();
  }, visible);
}

export interface SnapDiff {
  /** Pixels whose |ΔR|+|ΔG|+|ΔB| is over 40. */
  changed: number;
  /** Over those pixels, the correlation of the two snapshots' luma (1: one shows through the other). */
  correlation: number;
}

/** Where snapshots `a` and `b` differ. */
export function diffSnaps(page: Page, a: string, b: string): Promise<SnapDiff> {
  return page.evaluate(
    ({ a, b }) => {
      const s = (window as unknown as SnapWindow).__snaps!;
      const A = s[a]!;
      const B = s[b]!;
      const la: number[] = [];
      const lb: number[] = [];
      for (let i = 0; i < A.length; i += 4) {
        const d =
          Math.abs(A[i]! - B[i]!) +
          Math.abs(A[i + 1]! - B[i + 1]!) +
          Math.abs(A[i + 2]! - B[i + 2]!);
        if (d <= 40) continue;
        la.push(A[i]! * 0.3 + A[i + 1]! * 0.59 + A[i + 2]! * 0.11);
        lb.push(B[i]! * 0.3 + B[i + 1]! * 0.59 + B[i + 2]! * 0.11);
      }
      const n = la.length;
      const mean = (v: number[]) => v.reduce((x, y) => x + y, 0) / Math.max(1, v.length);
      const ma = mean(la);
      const mb = mean(lb);
      let sab = 0;
      let saa = 0;
      let sbb = 0;
      for (let i = 0; i < n; i++) {
        sab += (la[i]! - ma) * (lb[i]! - mb);
        saa += (la[i]! - ma) ** 2;
        sbb += (lb[i]! - mb) ** 2;
      }
      return { changed: n, correlation: saa && sbb ? sab / Math.sqrt(saa * sbb) : 0 };
    },
    { a, b },
  );
}

/** Mean RGB of a square patch of snapshot `name`, centred at fractions (fx, fy) of it. */
export function snapPatch(page: Page, name: string, fx: number, fy: number, half = 8) {
  return page.evaluate(
    ({ name, fx, fy, half, w, h }) => {
      const d = (window as unknown as SnapWindow).__snaps![name]!;
      const cx = Math.round(fx * w);
      const cy = Math.round(fy * h);
      const sum = [0, 0, 0];
      let n = 0;
      for (let y = cy - half; y < cy + half; y++)
        for (let x = cx - half; x < cx + half; x++) {
          const i = (y * w + x) * 4;
          for (let c = 0; c < 3; c++) sum[c]! += d[i + c]!;
          n++;
        }
      return sum.map((v) => v / n);
    },
    { name, fx, fy, half, w: SNAP_W, h: SNAP_H },
  );
}

/** Mean RGB of a patch of a camera view's canvas, centred at fractions of the picture. */
export function picturePatch(view: Locator, fx: number, fy: number, halfFraction: number) {
  return view.locator('canvas').evaluate(
    (c: HTMLCanvasElement, { fx, fy, halfFraction }) => {
      const half = Math.max(1, Math.round(halfFraction * c.height));
      const x0 = Math.round(fx * c.width) - half;
      const y0 = Math.round(fy * c.height) - half;
      const d = c.getContext('2d')!.getImageData(x0, y0, 2 * half, 2 * half).data;
      const sum = [0, 0, 0];
      for (let i = 0; i < d.length; i += 4) for (let k = 0; k < 3; k++) sum[k]! += d[i + k]!;
      return sum.map((v) => v / (d.length / 4));
    },
    { fx, fy, halfFraction },
  );
}

/** The 3D view's width / height. */
export function viewAspect(page: Page): Promise<number> {
  return page.evaluate(() => {
    const c = (window as unknown as SnapWindow).__armtwin.viewer.canvas;
    return c.clientWidth / c.clientHeight;
  });
}
