/**
 * Hands each of the page's parts down in its own context (./HudParts.ts). Rendered again by
 * main.tsx whenever a part is replaced (a reconnect's new link and settings, the render
 * fallback's choice), so the panels that use that part see the new one.
 */
import type { Context, ReactNode } from 'react';
import { HUD_CONTEXTS, type HudParts } from './HudParts.ts';

export function HudProvider({ parts, children }: { parts: HudParts; children: ReactNode }) {
  const keys = Object.keys(HUD_CONTEXTS) as (keyof HudParts)[];
  return keys.reduceRight<ReactNode>((inner, key) => provide(key, parts[key], inner), children);
}

function provide<K extends keyof HudParts>(key: K, value: HudParts[K], inner: ReactNode) {
  const Part: Context<HudParts[K] | null> = HUD_CONTEXTS[key];
  return <Part value={value}>{inner}</Part>;
}
