/**
 * Mounts the HUD: the page's objects come from ./ui/app/createHud.ts (the one composition root);
 * React draws the panels over the 3D view, re-mounting them when the robot changes.
 */
import './noEval.ts';
import { StrictMode } from 'react';
import { createRoot } from 'react-dom/client';
import { createHud } from './ui/app/createHud.ts';
import { HudProvider } from './ui/hud/HudProvider.tsx';
import type { HudParts } from './ui/hud/HudParts.ts';
import { App } from './ui/app/App.tsx';
import 'uplot/dist/uPlot.min.css';
import './ui/styles.css';

const root = createRoot(document.getElementById('hud')!);

function render(parts: HudParts): void {
  root.render(
    <StrictMode>
      <HudProvider parts={parts}>
        <App key={parts.robots.active.spec.name} />
      </HudProvider>
    </StrictMode>,
  );
}

createHud(
  { view: document.getElementById('view')!, message: document.getElementById('message')! },
  render,
).start();
