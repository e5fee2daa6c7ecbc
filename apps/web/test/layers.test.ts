/**
 * apps/web is in layers, core → scene → ui (README § Layers), and `npm run lint` enforces it:
 * the repository's own ESLint config, run on a file placed in each layer.
 */
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { ESLint } from 'eslint';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../..');
// The probes are not files on disk, so the type-aware rules (which need the file in a tsconfig
// project) are off for them; the layer rules under test are the repository's own.
const eslint = new ESLint({
  cwd: root,
  overrideConfig: {
    files: ['**/*.{ts,tsx}'],
    languageOptions: { parserOptions: { projectService: false } },
    rules: {
      '@typescript-eslint/no-floating-promises': 'off',
      '@typescript-eslint/switch-exhaustiveness-check': 'off',
    },
  },
});

async function restricted(file: string, code: string): Promise<string[]> {
  const [result] = await eslint.lintText(code, { filePath: path.join(root, 'apps/web/src', file) });
  return result!.messages.filter((m) => m.ruleId === 'no-restricted-imports').map((m) => m.message);
}

// The first lint loads the TypeScript parser: seconds on a busy machine.
describe('apps/web layers', { timeout: 60_000 }, () => {
  it('core imports neither scene/, ui/, React nor three.js', async () => {
    const found = await restricted(
      'core/store/Probe.ts',
      [
        "import type { SceneView } from '../../scene/SceneView.ts';",
        "import type { HudParts } from '../../ui/hud/HudParts.ts';",
        "import { useState } from 'react';",
        "import * as THREE from 'three';",
        'export type P = [SceneView, HudParts, typeof useState, typeof THREE];',
      ].join('\n'),
    );
    expect(found).toHaveLength(4);
    expect(found[0]).toContain('core imports neither scene/ nor ui/');
  });

  it('scene imports neither ui/ nor React', async () => {
    const found = await restricted(
      'scene/render/Probe.ts',
      [
        "import type { HudParts } from '../../ui/hud/HudParts.ts';",
        "import { useState } from 'react';",
        'export type P = [HudParts, typeof useState];',
      ].join('\n'),
    );
    expect(found).toHaveLength(2);
    expect(found[0]).toContain('scene does not import ui/');
  });

  it('downward imports pass', async () => {
    expect(
      await restricted(
        'scene/Probe.ts',
        "import type { ArmStore } from '../core/store/ArmStore.ts';\nexport type P = ArmStore;",
      ),
    ).toEqual([]);
    expect(
      await restricted(
        'ui/hud/Probe.ts',
        "import type { SceneView } from '../../scene/SceneView.ts';\nimport { useState } from 'react';\nexport type P = [SceneView, typeof useState];",
      ),
    ).toEqual([]);
  });
});
