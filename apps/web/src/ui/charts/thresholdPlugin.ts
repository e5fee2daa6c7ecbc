import uPlot from 'uplot';

/** A horizontal line across a chart at `value` (a §5 threshold, say). */
export interface Threshold {
  value: number;
  colour: string;
}

/** A uPlot plugin that draws dashed threshold lines over the plot on every redraw. */
export function thresholdPlugin(lines: readonly Threshold[]): uPlot.Plugin {
  return {
    hooks: {
      draw: (u: uPlot) => {
        const { ctx } = u;
        const { left, width } = u.bbox;
        ctx.save();
        ctx.setLineDash([6, 4]);
        ctx.lineWidth = 1.5 * uPlot.pxRatio;
        for (const l of lines) {
          const y = Math.round(u.valToPos(l.value, 'y', true));
          ctx.strokeStyle = l.colour;
          ctx.beginPath();
          ctx.moveTo(left, y);
          ctx.lineTo(left + width, y);
          ctx.stroke();
        }
        ctx.restore();
      },
    },
  };
}
