/**
 * Ghost: a translucent second arm showing the previewed target pose or the pose this HUD
 * commanded, beside the live arm. A switch hides it; the legend says what it shows now. A
 * refused target shows its offending link red. With nothing of this page's to show, the ghost is
 * a leader arm's pose (where it asks the arm to go), the leaders and whether they drive the arm
 * listed below (./LeaderSection.tsx). The live arm's links can be painted by tracking
 * error (./TrackingLegend.tsx); the folded Keep-out zones section lists and edits the zones
 * (../Zones/ZonesSection.tsx).
 */
import { useState } from 'react';
import { useLeaders, useTarget, useSceneFigures } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';
import { ZonesSection } from '../Zones/ZonesSection.tsx';
import { TrackingLegend } from './TrackingLegend.tsx';
import { LeaderSection } from './LeaderSection.tsx';

const WORDS = {
  preview: 'showing the previewed target pose',
  commanded: 'showing the commanded pose (the arm is not there yet)',
  nothing: 'hidden: nothing to show apart from the live arm',
  plan: 'previewing the plan (Plan panel)',
  refused: 'showing the refused jog: the link in red would collide',
} as const;

export function GhostPanel() {
  const target = useTarget();
  const view = useSceneFigures();
  const [enabled, setEnabled] = useState(target.ghostEnabled);
  const leaders = useLeaders();
  const shows = useSampled(() => view.reports.ghostShows);
  // The plan's place on the ghost, taken by a leader's pose when the page previews nothing.
  const leader = useSampled(() => leaders.onGhost);
  const words =
    shows === 'plan' && leader
      ? `showing ${leader}'s leader arm: where it asks the arm to go`
      : WORDS[shows];
  return (
    <section className="panel ghost" aria-labelledby="ghost-title">
      <h2 id="ghost-title">Ghost</h2>
      <label className="check">
        <input
          type="checkbox"
          checked={enabled}
          onChange={(e) => {
            target.setGhostEnabled(e.currentTarget.checked);
            setEnabled(e.currentTarget.checked);
          }}
        />
        Show ghost arm
      </label>
      <p className="dim" data-testid="ghost-shows">
        <span className="ghost-swatch" aria-hidden="true" /> {enabled ? words : 'off'}
      </p>
      <LeaderSection />
      <TrackingLegend />
      <ZonesSection />
    </section>
  );
}
