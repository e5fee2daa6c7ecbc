/**
 * Boot: settings → store → MQTT link → 3D view (first frame after the meshes load) → panels.
 * `window.__armtwin` is a read-only debug hook for the end-to-end tests and the console.
 */
import { StrictMode } from 'react';
import { createRoot } from 'react-dom/client';
import mqtt from 'mqtt';
import { ArmStore } from './store/ArmStore.ts';
import { TargetPreview } from './store/TargetPreview.ts';
import { ArmLink, type MqttConnect } from './mqtt/ArmLink.ts';
import { loadSettings, type HudSettings } from './config/settings.ts';
import { Viewer } from './scene/Viewer.ts';
import { MODEL_URL } from './model/armModel.ts';
import { HudContext, type Hud } from './hud/HudContext.ts';
import { App } from './hud/App.tsx';
import { ReplayPlayer } from './replay/ReplayPlayer.ts';
import { historyProbe } from './panels/History/probe.ts';
import 'uplot/dist/uPlot.min.css';
import './styles.css';

const connect: MqttConnect = (url, opts) => mqtt.connect(url, opts);

const settings = loadSettings();
const store = new ArmStore({ interpolationAlpha: settings.interpolationAlpha });
const target = new TargetPreview();

const viewEl = document.getElementById('view')!;
const hudEl = document.getElementById('hud')!;
const messageEl = document.getElementById('message')!;

const replay = new ReplayPlayer(store.opts.arm.servos.map((s) => s.polarity));
const viewer = new Viewer(viewEl, store, target, replay);
const hud: Hud = {
  store,
  target,
  replay,
  settings,
  link: new ArmLink(store, settings, connect),
  reconnect(next: HudSettings) {
    hud.link.stop();
    store.resetArm();
    store.setInterpolationAlpha(next.interpolationAlpha);
    hud.settings = next;
    hud.link = new ArmLink(store, next, connect);
    hud.link.start();
    render();
  },
};

declare global {
  interface Window {
    __armtwin?: {
      store: ArmStore;
      target: TargetPreview;
      viewer: Viewer;
      readonly link: ArmLink;
      ready: boolean;
      replay: ReplayPlayer;
      history: typeof historyProbe;
    };
  }
}
window.__armtwin = {
  store,
  target,
  viewer,
  get link() {
    return hud.link;
  },
  ready: false,
  replay,
  history: historyProbe,
};

const root = createRoot(hudEl);
function render() {
  root.render(
    <StrictMode>
      <HudContext value={{ ...hud }}>
        <App />
      </HudContext>
    </StrictMode>,
  );
}

hud.link.start();
render();
messageEl.textContent = 'Loading the arm model…';
viewer
  .load(new URL(MODEL_URL, document.baseURI).href)
  .then(() => {
    messageEl.hidden = true;
    viewer.start();
    window.__armtwin!.ready = true;
    render();
  })
  .catch((err: unknown) => {
    messageEl.classList.add('error');
    messageEl.setAttribute('role', 'alert');
    messageEl.textContent = `The arm model failed to load: ${err instanceof Error ? err.message : String(err)}`;
    render(); // the panels still work without the 3D view
  });
