#!/usr/bin/env node
// The `armtwin` command. Sources are TypeScript, loaded through tsx: no build step.
import { register } from 'tsx/esm/api';

register();
const { main } = await import('../src/main.ts');
await main(process.argv);
