/**
 * The HUD's layout: panels as semi-transparent layers over the full-window 3D view, in landmarks
 * (the stop in the header, the panels in asides, the phone's tab bar in a nav). On a wide screen
 * the panels stand in three columns; on a phone or a narrow tablet (./layout.css) the 3D view keeps
 * the top of the screen, the stop stays on it, and the panels fold into a bottom sheet raised one
 * tab at a time from the tab bar (../hud/sheetTabs.ts).
 */
import { useEffect, useState, type ReactNode } from 'react';
import { JogPanel } from '../panels/Jog/JogPanel.tsx';
import { EmergencyStopButton } from '../panels/EmergencyStop/EmergencyStopButton.tsx';
import { StatusPanel } from '../panels/Status/StatusPanel.tsx';
import { ConnectionPanel } from '../panels/Connection/ConnectionPanel.tsx';
import { HealthPanel } from '../panels/Health/HealthPanel.tsx';
import { CartesianPanel } from '../panels/Cartesian/CartesianPanel.tsx';
import { GhostPanel } from '../panels/Ghost/GhostPanel.tsx';
import { HistoryPanel } from '../panels/History/HistoryPanel.tsx';
import { LoginPanel } from '../panels/Login/LoginPanel.tsx';
import { FleetPanel } from '../panels/Fleet/FleetPanel.tsx';
import { CommandPanel } from '../panels/Command/CommandPanel.tsx';
import { PlanPanel } from '../panels/Plan/PlanPanel.tsx';
import { CameraPanel } from '../panels/Camera/CameraPanel.tsx';
import { CalibrationPanel } from '../panels/Calibration/CalibrationPanel.tsx';
import { ImportPanel } from '../panels/Import/ImportPanel.tsx';
import { PanelTabs } from '../hud/PanelTabs.tsx';
import { SheetHandle } from '../hud/SheetHandle.tsx';
import type { PanelTab } from '../hud/sheetTabs.ts';
import { ModeBar } from '../modes/ModeBar.tsx';
import { SHADOW_REASON } from '../../core/link/modes.ts';
import { useModes } from '../hud/HudParts.ts';
import { useSampled } from '../hud/useSampled.ts';
import './layout.css';

const SHEET_ID = 'hud-sheet';

export function App() {
  // The bottom sheet's tab (null: lowered) and the last one raised; only the phone layout shows it.
  const [open, setOpen] = useState<PanelTab | null>(null);
  const [last, setLast] = useState<PanelTab>('jog');
  // Shadow mode: every panel's controls off (a disabled fieldset; the stop and the mode switch
  // stand outside the panels, and the panels still fold).
  const modes = useModes();
  const shadow = useSampled(() => modes.mode === 'shadow');
  const show = (tab: PanelTab | null) => {
    setOpen(tab);
    if (tab) setLast(tab);
  };
  // Raising or lowering the sheet resizes the 3D view's box (./layout.css); the view re-sizes its
  // canvas on the window's `resize`.
  useEffect(() => {
    window.dispatchEvent(new Event('resize'));
  }, [open]);

  // `modeFree`: who this page is, which broker it reads (Log-in, Connection) and the record of
  // what the arm did (History: load, replay, export, all on this page) act on no arm, so Shadow
  // leaves them on (a viewer opens in Shadow and must still log in and read the history).
  const slot = (tab: PanelTab, panel: ReactNode, modeFree = false) => (
    <div
      className={open === tab ? 'slot open' : 'slot'}
      data-tab={tab}
      data-mode-free={modeFree || undefined}
    >
      <fieldset
        className="mode-fieldset"
        disabled={shadow && !modeFree}
        title={shadow && !modeFree ? SHADOW_REASON : undefined}
      >
        {panel}
      </fieldset>
    </div>
  );
  return (
    <div className={open ? 'hud sheet-open' : 'hud'}>
      <header className="hud-bar">
        <h1 className="visually-hidden">armtwin HUD</h1>
        <ModeBar />
        <EmergencyStopButton />
      </header>
      <div className="hud-sheet" id={SHEET_ID}>
        <SheetHandle open={open} sheetId={SHEET_ID} onOpen={show} />
        <aside className="column left" aria-label="Moving the arm">
          {slot('jog', <JogPanel />)}
          {slot('target', <CartesianPanel />)}
          {slot('target', <CommandPanel />)}
          {slot('target', <PlanPanel />)}
          {slot('view', <GhostPanel />)}
          {slot('setup', <CalibrationPanel />)}
          {slot('setup', <ImportPanel />)}
        </aside>
        <aside className="column center" aria-label="History">
          {slot('view', <HistoryPanel />, true)}
        </aside>
        <aside className="column right" aria-label="The arm and its connection">
          {slot('setup', <LoginPanel />, true)}
          {slot('arm', <FleetPanel />)}
          {slot('view', <CameraPanel />)}
          {slot('arm', <StatusPanel />)}
          {slot('arm', <HealthPanel />)}
          {slot('setup', <ConnectionPanel />, true)}
        </aside>
      </div>
      <PanelTabs open={open} last={last} sheetId={SHEET_ID} onOpen={show} />
    </div>
  );
}
