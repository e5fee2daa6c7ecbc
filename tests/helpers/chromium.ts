/**
 * Debian's Chromium and the flags armtwin runs it with, headless, as root, on a machine with
 * no network beyond loopback: used by playwright.config.ts and by the browser benchmark.
 */
export const CHROMIUM_PATH = '/usr/bin/chromium';

export const CHROMIUM_ARGS = [
  '--headless',
  '--no-sandbox',
  '--disable-gpu',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--no-first-run',
];
