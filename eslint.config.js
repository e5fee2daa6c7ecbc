import js from '@eslint/js';
import tseslint from 'typescript-eslint';
import reactHooks from 'eslint-plugin-react-hooks';
import globals from 'globals';

export default tseslint.config(
  { ignores: ['**/node_modules/**', '**/dist/**', '.tools/**', 'test-results/**', 'playwright-report/**'] },
  js.configs.recommended,
  ...tseslint.configs.recommended,
  {
    files: ['**/*.{js,mjs}'],
    languageOptions: { globals: globals.node },
  },
  {
    files: ['apps/web/**/*.{ts,tsx}'],
    plugins: { 'react-hooks': reactHooks },
    rules: reactHooks.configs.recommended.rules,
  },
  // apps/web in layers (apps/web/README.md § Layers): core → scene → ui. An import may point
  // down or sideways, never up; core draws nothing (no React, no three.js), scene renders no HUD.
  {
    files: ['apps/web/src/core/**/*.{ts,tsx}'],
    rules: {
      'no-restricted-imports': [
        'error',
        {
          patterns: [
            {
              regex: '^\\.\\.?/(?:.*/)?(?:scene|ui)/',
              message:
                'apps/web/src/core imports neither scene/ nor ui/ (layers: core → scene → ui).',
            },
            {
              regex: '^(?:react|react-dom|three|urdf-loader|uplot)(?:/|$)',
              message: 'apps/web/src/core is plain logic: no React, three.js or charts.',
            },
          ],
        },
      ],
    },
  },
  {
    files: ['apps/web/src/scene/**/*.{ts,tsx}'],
    rules: {
      'no-restricted-imports': [
        'error',
        {
          patterns: [
            {
              regex: '^\\.\\.?/(?:.*/)?ui/',
              message: 'apps/web/src/scene does not import ui/ (layers: core → scene → ui).',
            },
            {
              regex: '^(?:react|react-dom)(?:/|$)',
              message: 'apps/web/src/scene draws the 3D view; React belongs in ui/.',
            },
          ],
        },
      ],
    },
  },
  {
    // Type-aware rules: each TypeScript file is checked with its own tsconfig (projectService).
    files: ['**/*.{ts,tsx,mts,cts}'],
    languageOptions: {
      parserOptions: {
        // The shipped models' mesh generators are in no tsconfig: checked with the defaults.
        projectService: { allowDefaultProject: ['public/models/*/*.ts'] },
        tsconfigRootDir: import.meta.dirname,
      },
    },
    rules: {
      '@typescript-eslint/no-floating-promises': 'error',
      // A switch over a union names every member: a default does not stand in for a new one.
      '@typescript-eslint/switch-exhaustiveness-check': 'error',
    },
  },
  {
    rules: {
      '@typescript-eslint/no-unused-vars': [
        'error',
        { argsIgnorePattern: '^_', varsIgnorePattern: '^_' },
      ],
    },
  },
);
