import uPlot from 'uplot';

/** A moment marked across a chart: a vertical dashed line at `at` (epoch ms) and a short label. */
export interface Marker {
  at: number;
  colour: string;
  label: string;
}

/**
 * A uPlot plugin that draws markers (early warnings, say) over the plot on every redraw; a
 * function is read at each redraw (a moving marker: the History replay's instant).
 */
export function markerPlugin(markers: readonly Marker[] | (() => readonly Marker[])): uPlot.Plugin {
  return {
    hooks: {
      draw: (u: uPlot) => {
        const list = typeof markers === 'function' ? markers() : markers;
        const { ctx } = u;
        const { left, top, width, height } = u.bbox;
        ctx.save();
        ctx.setLineDash([3, 3]);
        ctx.lineWidth = 1.5 * uPlot.pxRatio;
        ctx.font = `${10 * uPlot.pxRatio}px system-ui`;
        ctx.textBaseline = 'top';
        for (const m of list) {
          const x = Math.round(u.valToPos(m.at / 1000, 'x', true));
          if (x < left || x > left + width) continue;
          ctx.strokeStyle = ctx.fillStyle = m.colour;
          ctx.beginPath();
          ctx.moveTo(x, top);
          ctx.lineTo(x, top + height);
          ctx.stroke();
          // The label on the side with room: right of the line, left of it near the right edge.
          const right = x < left + width / 2;
          ctx.textAlign = right ? 'left' : 'right';
          const pad = 3 * uPlot.pxRatio;
          ctx.fillText(m.label, right ? x + pad : x - pad, top + 2 * uPlot.pxRatio);
        }
        ctx.restore();
      },
    },
  };
}
