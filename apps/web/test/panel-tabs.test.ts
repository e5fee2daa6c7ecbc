import { describe, expect, it } from 'vitest';
import { DEFAULT_SWIPE_OPTIONS, PANEL_TABS, swipeSheet, tapTab } from '../src/ui/hud/sheetTabs.ts';

describe('the phone layout tab bar', () => {
  it('has a distinct id and label per tab', () => {
    expect(new Set(PANEL_TABS.map((t) => t.id)).size).toBe(PANEL_TABS.length);
    expect(new Set(PANEL_TABS.map((t) => t.label)).size).toBe(PANEL_TABS.length);
  });

  it('a tap raises the sheet on that tab, switches from another, and lowers it when open', () => {
    expect(tapTab(null, 'jog')).toBe('jog');
    expect(tapTab('arm', 'jog')).toBe('jog');
    expect(tapTab('jog', 'jog')).toBeNull();
  });

  it('a swipe up raises the sheet on the last tab, down lowers it, a short move is a tap', () => {
    const d = DEFAULT_SWIPE_OPTIONS.minDistancePx;
    expect(swipeSheet(null, 'target', -d)).toBe('target');
    expect(swipeSheet('arm', 'target', -d - 50)).toBe('arm'); // already up: stays on its tab
    expect(swipeSheet('arm', 'arm', d)).toBeNull();
    expect(swipeSheet(null, 'jog', d + 100)).toBeNull();
    expect(swipeSheet('arm', 'arm', d - 1)).toBeUndefined();
    expect(swipeSheet(null, 'jog', -(d - 1))).toBeUndefined();
    expect(swipeSheet(null, 'jog', -10, { minDistancePx: 5 })).toBe('jog');
  });
});
