/**
 * An arm's small live pose in the fleet list: one bar per joint, its servo angle marked within
 * its limits (from the arm's summary, docs/protocol.md § Fleets), redrawn when the summary
 * changes (2 Hz at most while the arm moves). Text for screen readers in the label.
 */
import type { SummaryJoint } from '@armtwin/protocol';

const W = 6;
const GAP = 3;
const H = 18;

/** Where `deg` sits between `min` and `max`, 0..1 (0.5 when the range is empty). */
export const jointFraction = (j: SummaryJoint): number =>
  j.max > j.min ? Math.min(1, Math.max(0, (j.deg - j.min) / (j.max - j.min))) : 0.5;

export function PoseBars({ joints, id }: { joints: readonly SummaryJoint[]; id: string }) {
  if (joints.length === 0) return <span className="fleet-pose dim">no pose yet</span>;
  const width = joints.length * (W + GAP) - GAP;
  const words = joints.map((j) => `servo ${String(j.id).padStart(3, '0')} ${j.deg}°`).join(', ');
  return (
    <svg
      className="fleet-pose"
      width={width}
      height={H}
      viewBox={`0 0 ${width} ${H}`}
      role="img"
      aria-label={`pose: ${words}`}
      data-testid={`fleet-pose-${id}`}
      data-degrees={joints.map((j) => j.deg).join(' ')}
    >
      {joints.map((j, i) => {
        const y = (1 - jointFraction(j)) * (H - 2);
        return (
          <g key={j.id} transform={`translate(${i * (W + GAP)},0)`}>
            <rect className="track" width={W} height={H} rx={1} />
            <rect className="mark" y={y} width={W} height={2} />
          </g>
        );
      })}
    </svg>
  );
}
