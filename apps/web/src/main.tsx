/**
 * Boot: settings → store → MQTT link → 3D view (first frame after the meshes load) → panels.
 * `window.__armtwin` is a read-only debug hook for the end-to-end tests and the console.
 */
import { StrictMode } from 'react';
import { createRoot } from 'react-dom/client';
import mqtt from 'mqtt';
import {
  clearInterval as clearWorkerInterval,
  setInterval as setWorkerInterval,
} from 'worker-timers';
import { ArmStore } from './store/ArmStore.ts';
import { TargetPreview } from './store/TargetPreview.ts';
import { ArmLink, type IntervalTimers, type MqttConnect } from './mqtt/ArmLink.ts';
import { loadSettings, type HudSettings } from './config/settings.ts';
import { Viewer } from './scene/Viewer.ts';
import { HudContext, type Hud } from './hud/HudContext.ts';
import { App } from './hud/App.tsx';
import { ReplayPlayer } from './replay/ReplayPlayer.ts';
import { historyProbe } from './panels/History/probe.ts';
import { Session } from './auth/Session.ts';
import { fetchWhoami } from './auth/whoami.ts';
import { armQueryProblem } from './config/queryProblems.ts';
import { RobotsHub } from './robots/RobotsHub.ts';
import { settingsForArm } from './robots/selectArm.ts';
import 'uplot/dist/uPlot.min.css';
import './styles.css';

const connect: MqttConnect = (url, opts) => mqtt.connect(url, opts);
/** The deadman's beat keeps time in a worker: a hidden tab is not throttled into a stop. */
const workerIntervals: IntervalTimers = {
  setInterval: (fn, ms) => setWorkerInterval(fn, ms),
  clearInterval: (id) => clearWorkerInterval(id),
};

const settings = loadSettings();
const store = new ArmStore({ interpolationAlpha: settings.interpolationAlpha });
const target = new TargetPreview();

const viewEl = document.getElementById('view')!;
const hudEl = document.getElementById('hud')!;
const messageEl = document.getElementById('message')!;

const replay = new ReplayPlayer(store.opts.arm.servos.map((s) => s.polarity));
const viewer = new Viewer(viewEl, store, target, replay);
const session = new Session({
  whoami: (s) => fetchWhoami(s.apiBase, s),
  queryProblem: armQueryProblem(window.location.search),
});
// Issue 9: the fleet, the selected arm's robot profile and model, planning (src/robots).
const robots = new RobotsHub(
  store,
  viewer,
  (url, opts) => mqtt.connect(url, opts),
  settings,
  () => render(),
);
const hud: Hud = {
  robots,
  selectArm(armId: string) {
    const next = settingsForArm(hud.settings, armId);
    if (next) hud.reconnect(next);
  },
  session,
  store,
  target,
  replay,
  settings,
  link: new ArmLink(store, settings, connect, workerIntervals),
  reconnect(next: HudSettings) {
    hud.link.stop();
    store.resetArm();
    store.setInterpolationAlpha(next.interpolationAlpha);
    const prev = hud.settings;
    hud.settings = next;
    hud.link = new ArmLink(store, next, connect, workerIntervals);
    robots.switched(prev, next);
    void session.start(hud.link);
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
      session: Session;
      robots: RobotsHub;
      /** The live arm's URDF joint values as drawn (rad, or m for a prismatic joint). */
      joints(which?: 'robot' | 'ghost'): number[];
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
  session,
  robots,
  joints: (which) => viewer.jointValues(which),
};

const root = createRoot(hudEl);
function render() {
  root.render(
    <StrictMode>
      <HudContext value={{ ...hud }}>
        <App key={robots.active.spec.name} />
      </HudContext>
    </StrictMode>,
  );
}

void session.start(hud.link);
// Let go of the arm when the page goes away (the deadman's `0` at once, not after the will).
window.addEventListener('pagehide', () => hud.link.release());
window.addEventListener('pageshow', (e) => e.persisted && hud.reconnect(hud.settings));
render();
messageEl.textContent = 'Loading the arm model…';
robots.start(settings.armId);
robots.active.firstLoad
  .then(() => {
    messageEl.hidden = true;
    viewer.start();
    robots.viewerStarted();
    window.__armtwin!.ready = true;
    render();
  })
  .catch((err: unknown) => {
    messageEl.classList.add('error');
    messageEl.setAttribute('role', 'alert');
    messageEl.textContent = `The arm model failed to load: ${err instanceof Error ? err.message : String(err)}`;
    render(); // the panels still work without the 3D view
  });
