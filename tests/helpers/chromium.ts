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

/**
 * The same with hardware WebGL, for the benchmark's page sections on a machine with a GPU
 * (`npm run bench -- --gpu`): ANGLE on Vulkan gave an NVIDIA renderer in headless Chromium on an
 * H100 machine (BENCHMARKS.md § On a GPU); `--use-angle=gl-egl` also did, plain `--use-gl=egl`
 * did not.
 */
export const GPU_CHROMIUM_ARGS = [
  ...CHROMIUM_ARGS.filter((a) => a !== '--disable-gpu'),
  '--use-angle=vulkan',
  '--enable-features=Vulkan,VulkanFromANGLE,DefaultANGLEVulkan',
  '--disable-vulkan-surface',
  '--ignore-gpu-blocklist',
  '--enable-gpu',
];
