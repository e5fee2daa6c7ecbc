/**
 * The selected arm's leader arms (`armtwin gateway --leader-of`, docs/so101.md § 6): whose leader
 * it is and whether it drives the arm, or why it stopped (an e-stop, a lost lease: its user
 * publishes `1` on its enable topic to follow again). The ghost shows the newest leader's pose
 * (the Ghost panel's legend says so). Nothing shows while the arm has no leader.
 */
import { useLeaders } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';

export function LeaderSection() {
  const leaders = useLeaders();
  const list = useSampled(() => ({ version: leaders.version, list: leaders.list }));
  const rows = list.list.filter((l) => l.state !== null || !Number.isNaN(l.poseAt));
  if (rows.length === 0) return null;
  return (
    <ul className="leaders" aria-label="Leader arms" data-testid="leaders">
      {rows.map((l) => (
        <li
          key={l.user}
          data-testid={`leader-${l.user}`}
          data-following={l.state ? String(l.state.following) : 'unknown'}
          className={l.state && !l.state.following ? 'bad' : undefined}
        >
          {l.state === null
            ? `${l.user}'s leader arm: not yet said whether it drives the arm`
            : l.state.following
              ? `${l.user}'s leader arm drives the arm`
              : `${l.user}'s leader arm no longer drives the arm: ${l.state.reason || 'stopped'}`}
        </li>
      ))}
    </ul>
  );
}
