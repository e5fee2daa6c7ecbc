/** The HUD's layout: panels as semi-transparent layers over the full-window 3D view. */
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

export function App() {
  return (
    <div className="hud">
      <div className="column left">
        <JogPanel />
        <CartesianPanel />
        <CommandPanel />
        <PlanPanel />
        <GhostPanel />
        <CalibrationPanel />
        <ImportPanel />
      </div>
      <div className="column center">
        <HistoryPanel />
      </div>
      <div className="column right">
        <EmergencyStopButton />
        <LoginPanel />
        <FleetPanel />
        <CameraPanel />
        <StatusPanel />
        <HealthPanel />
        <ConnectionPanel />
      </div>
    </div>
  );
}
