/**
 * Mounts the HUD: the page's objects come from ./ui/app/createHud.ts (the one composition root);
 * React draws the panels over the 3D view, re-mounting them when the robot changes.
 */
import './noEval.ts';
import { StrictMode } from 'react';
import { createRoot } from 'react-dom/client';
import { createHud } from './ui/app/createHud.ts';
import { HudContext, type Hud } from './ui/hud/HudContext.ts';
import { App } from './ui/app/App.tsx';
import 'uplot/dist/uPlot.min.css';
import './ui/styles.css';

const root = createRoot(document.getElementById('hud')!);

function render(hud: Hud): void {
  root.render(
    <StrictMode>
      <HudContext value={{ ...hud }}>
        <App key={hud.robots.active.spec.name} />
      </HudContext>
    </StrictMode>,
  );
}

createHud(
  { view: document.getElementById('view')!, message: document.getElementById('message')! },
  render,
).start();
