import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { defineConfig } from 'vite';
import react from '@vitejs/plugin-react';

const here = path.dirname(fileURLToPath(import.meta.url));

// The HUD is a static bundle: `npm start` serves apps/web/dist, `vite preview` serves it in
// the e2e tests. `base: './'` makes every URL relative, so it works under any path.
// The repo's public/ (public/models/…) is copied to the build's root: /models/armtwin5/….
export default defineConfig({
  root: here,
  base: './',
  publicDir: path.resolve(here, '../../public'),
  plugins: [react()],
  build: {
    outDir: path.resolve(here, 'dist'),
    emptyOutDir: true,
    chunkSizeWarningLimit: 1500,
  },
  server: { host: '127.0.0.1' },
  preview: { host: '127.0.0.1' },
});
