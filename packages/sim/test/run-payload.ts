/** Feeds a control payload (frames and groups) to a SimModel at time `t`; returns its replies. */
import { createReader, type Frame, type Group } from '@armtwin/protocol';
import type { SimModel } from '../src/model.ts';

export const T0 = 1_000_000;

export function runPayload(model: SimModel, payload: string, t: number): string[] {
  const out: string[] = [];
  const reader = createReader({
    onFrame: (f: Frame) => model.execute(f, t, out),
    onGroup: (g: Group) => model.executeGroup(g, t, out),
  });
  reader.feed(payload);
  return out;
}
