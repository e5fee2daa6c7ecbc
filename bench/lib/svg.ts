/**
 * A tiny grouped-bar SVG writer (histograms are bars whose categories are bins). Written here
 * rather than taken from a chart library because the maintained ones (Chart.js, uPlot,
 * Observable Plot, Vega) need a DOM or a canvas to render, and this output is a few static
 * bars with axes: plain string building, no dependency, deterministic output for diffs.
 */

export interface BarSeries {
  name: string;
  values: number[];
  colour: string;
}

export interface BarChart {
  title: string;
  xLabel: string;
  yLabel: string;
  categories: string[];
  series: BarSeries[];
  /** Show every k-th category label (histograms with many bins). */
  labelEvery?: number;
  width?: number;
  height?: number;
}

const esc = (s: string) =>
  s.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;').replace(/"/g, '&quot;');

/** A "nice" upper bound for the y axis (1, 2 or 5 × 10ⁿ steps) and its tick step. */
function niceMax(max: number): { top: number; step: number } {
  if (!(max > 0)) return { top: 1, step: 0.25 };
  const raw = max / 4;
  const mag = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((m) => m * mag).find((s) => s >= raw) ?? 10 * mag;
  return { top: Math.ceil(max / step) * step, step };
}

export function barChartSvg(c: BarChart): string {
  const W = c.width ?? 720;
  const H = c.height ?? 360;
  const m = { l: 64, r: 16, t: 36, b: 64 };
  const pw = W - m.l - m.r;
  const ph = H - m.t - m.b;
  const all = c.series.flatMap((s) => s.values.filter(Number.isFinite));
  const { top, step } = niceMax(Math.max(0, ...all));
  const y = (v: number) => m.t + ph - (ph * v) / top;
  const slot = pw / Math.max(1, c.categories.length);
  const bw = (slot * 0.8) / Math.max(1, c.series.length);
  const out: string[] = [
    `<svg xmlns="http://www.w3.org/2000/svg" width="${W}" height="${H}" viewBox="0 0 ${W} ${H}" font-family="sans-serif" font-size="11">`,
    `<rect width="${W}" height="${H}" fill="white"/>`,
    `<text x="${W / 2}" y="20" text-anchor="middle" font-size="14">${esc(c.title)}</text>`,
  ];
  for (let v = 0; v <= top + step / 2; v += step) {
    const yy = y(v).toFixed(1);
    out.push(
      `<line x1="${m.l}" x2="${W - m.r}" y1="${yy}" y2="${yy}" stroke="#ddd"/>`,
      `<text x="${m.l - 6}" y="${yy}" text-anchor="end" dominant-baseline="middle">${+v.toPrecision(6)}</text>`,
    );
  }
  c.series.forEach((s, si) => {
    s.values.forEach((v, i) => {
      if (!(v > 0)) return;
      const x = m.l + i * slot + slot * 0.1 + si * bw;
      out.push(
        `<rect x="${x.toFixed(1)}" y="${y(v).toFixed(1)}" width="${bw.toFixed(1)}" height="${(m.t + ph - y(v)).toFixed(1)}" fill="${s.colour}"><title>${esc(`${s.name} ${c.categories[i]}: ${v}`)}</title></rect>`,
      );
    });
  });
  const every = c.labelEvery ?? 1;
  c.categories.forEach((cat, i) => {
    if (i % every) return;
    const x = m.l + (i + 0.5) * slot;
    out.push(
      `<text x="${x.toFixed(1)}" y="${m.t + ph + 14}" text-anchor="end" transform="rotate(-35 ${x.toFixed(1)} ${m.t + ph + 14})">${esc(cat)}</text>`,
    );
  });
  out.push(
    `<line x1="${m.l}" x2="${m.l}" y1="${m.t}" y2="${m.t + ph}" stroke="#333"/>`,
    `<line x1="${m.l}" x2="${W - m.r}" y1="${m.t + ph}" y2="${m.t + ph}" stroke="#333"/>`,
    `<text x="${m.l + pw / 2}" y="${H - 8}" text-anchor="middle">${esc(c.xLabel)}</text>`,
    `<text x="14" y="${m.t + ph / 2}" text-anchor="middle" transform="rotate(-90 14 ${m.t + ph / 2})">${esc(c.yLabel)}</text>`,
  );
  c.series.forEach((s, si) => {
    const x = W - m.r - 170;
    const yy = m.t + 4 + si * 16;
    out.push(
      `<rect x="${x}" y="${yy}" width="10" height="10" fill="${s.colour}"/>`,
      `<text x="${x + 14}" y="${yy + 9}">${esc(s.name)}</text>`,
    );
  });
  out.push('</svg>\n');
  return out.join('\n');
}
