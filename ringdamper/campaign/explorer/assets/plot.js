// Minimal SVG charts: axes with ticks and labels (linear or log), lines, bands, points, vertical
// markers and a legend. Series values that are null or not finite (or <= 0 on a log axis) are skipped.
"use strict";

function niceTicks(lo, hi, count) {
  const span = hi - lo, step0 = span / Math.max(count, 1);
  const mag = Math.pow(10, Math.floor(Math.log10(step0)));
  const step = [1, 2, 2.5, 5, 10].map((f) => f * mag).find((s) => span / s <= count) || 10 * mag;
  const ticks = [];
  for (let t = Math.ceil(lo / step - 1e-9) * step; t <= hi + step * 1e-9; t += step) ticks.push(Math.abs(t) < step * 1e-9 ? 0 : t);
  return ticks;
}

function logTicks(lo, hi) {
  const ticks = [], factors = Math.log10(hi / lo) > 3 ? [1] : [1, 2, 5];  // decades only over a wide range
  for (let e = Math.floor(Math.log10(lo)); e <= Math.ceil(Math.log10(hi)); e++) {
    for (const f of factors) { const t = f * Math.pow(10, e); if (t >= lo * (1 - 1e-9) && t <= hi * (1 + 1e-9)) ticks.push(t); }
  }
  return ticks;
}

function fmt(v) {
  if (v === 0) return "0";
  const a = Math.abs(v);
  if (a >= 1e4 || a < 1e-3) return v.toExponential(0).replace("e+", "e");
  return String(Number(v.toPrecision(4)));
}

function esc(s) { return String(s).replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;"); }

class Chart {
  // opts: {title, xlabel, ylabel, xlog, ylog, width, height}
  constructor(el, opts) {
    this.el = el;
    this.o = Object.assign({ width: 420, height: 280, xlog: false, ylog: false }, opts);
  }

  ok(v, log) { return v !== null && Number.isFinite(v) && (!log || v > 0); }

  extent(series, key, log) {
    let lo = Infinity, hi = -Infinity;
    for (const s of series) {
      for (const k of key === "x" ? ["x"] : ["y", "y2"]) {
        for (const v of s[k] || []) if (this.ok(v, log)) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
      }
      if (key === "x" && s.type === "vline" && this.ok(s.at, log)) { lo = Math.min(lo, s.at); hi = Math.max(hi, s.at); }
    }
    if (!Number.isFinite(lo)) return log ? [1, 10] : [0, 1];
    if (log) { if (hi / lo < 1.5) { lo /= 1.25; hi *= 1.25; } return [lo, hi]; }
    if (hi - lo <= 1e-12 * Math.max(Math.abs(hi), 1e-300)) { const d = Math.abs(hi) * 0.05 || 1; return [lo - d, hi + d]; }
    const pad = 0.04 * (hi - lo);
    return [lo - pad, hi + pad];
  }

  // series: [{type: "line"|"band"|"points"|"vline", x, y, y2, at, cls, label, id, names}]
  draw(series, limits) {
    const o = this.o, W = o.width, H = o.height, m = { l: 62, r: 10, t: 22, b: 40 };
    const [x0, x1] = (limits && limits.x) || this.extent(series, "x", o.xlog);
    const [y0, y1] = (limits && limits.y) || this.extent(series, "y", o.ylog);
    const sx = o.xlog ? (v) => m.l + (Math.log(v / x0) / Math.log(x1 / x0)) * (W - m.l - m.r)
      : (v) => m.l + ((v - x0) / (x1 - x0)) * (W - m.l - m.r);
    const sy = o.ylog ? (v) => H - m.b - (Math.log(v / y0) / Math.log(y1 / y0)) * (H - m.t - m.b)
      : (v) => H - m.b - ((v - y0) / (y1 - y0)) * (H - m.t - m.b);
    const legendRows = Math.ceil(series.filter((s) => s.label).length / 2), HT = H + 13 * legendRows + (legendRows ? 4 : 0);
    const out = [`<svg viewBox="0 0 ${W} ${HT}" width="${W}" height="${HT}" class="chart">`];
    out.push(`<text class="title" x="${m.l}" y="14">${esc(o.title || "")}</text>`);
    const xt = o.xlog ? logTicks(x0, x1) : niceTicks(x0, x1, 6), yt = o.ylog ? logTicks(y0, y1) : niceTicks(y0, y1, 5);
    for (const t of xt) {
      const X = sx(t).toFixed(1);
      out.push(`<line class="grid" x1="${X}" x2="${X}" y1="${m.t}" y2="${H - m.b}"/><text class="tick" x="${X}" y="${H - m.b + 13}" text-anchor="middle">${fmt(t)}</text>`);
    }
    for (const t of yt) {
      const Y = sy(t).toFixed(1);
      out.push(`<line class="grid" x1="${m.l}" x2="${W - m.r}" y1="${Y}" y2="${Y}"/><text class="tick" x="${m.l - 4}" y="${Y}" dy="3" text-anchor="end">${fmt(t)}</text>`);
    }
    out.push(`<rect class="frame" x="${m.l}" y="${m.t}" width="${W - m.l - m.r}" height="${H - m.t - m.b}"/>`);
    out.push(`<text class="label" x="${(m.l + W - m.r) / 2}" y="${H - 6}" text-anchor="middle">${esc(o.xlabel)}</text>`);
    out.push(`<text class="label" transform="translate(13 ${(m.t + H - m.b) / 2}) rotate(-90)" text-anchor="middle">${esc(o.ylabel)}</text>`);
    out.push(`<clipPath id="clip-${this.el.id}"><rect x="${m.l}" y="${m.t}" width="${W - m.l - m.r}" height="${H - m.t - m.b}"/></clipPath><g clip-path="url(#clip-${this.el.id})">`);
    const legend = [];
    for (const s of series) {
      const id = s.id ? ` id="${s.id}"` : "";
      if (s.type === "vline") {
        if (this.ok(s.at, o.xlog)) out.push(`<line${id} class="${s.cls}" x1="${sx(s.at).toFixed(1)}" x2="${sx(s.at).toFixed(1)}" y1="${m.t}" y2="${H - m.b}"/>`);
      } else if (s.type === "points") {
        s.x.forEach((x, i) => {
          const y = s.y[i];
          if (this.ok(x, o.xlog) && this.ok(y, o.ylog)) out.push(`<circle class="${s.cls}"${s.fill ? ` style="fill:${s.fill[i]}"` : ""} cx="${sx(x).toFixed(1)}" cy="${sy(y).toFixed(1)}" r="${s.r || 3}"><title>${esc((s.names && s.names[i]) || s.label || "")}</title></circle>`);
        });
      } else {
        const runs = [[]];  // unbroken runs of finite points
        s.x.forEach((x, i) => {
          const y = s.y[i], y2 = s.type === "band" ? s.y2[i] : y;
          if (this.ok(x, o.xlog) && this.ok(y, o.ylog) && this.ok(y2, o.ylog)) runs[runs.length - 1].push([sx(x), sy(y), sy(y2)]);
          else if (runs[runs.length - 1].length) runs.push([]);
        });
        let d = "";
        for (const run of runs.filter((r) => r.length)) {
          if (s.type === "band") {
            d += "M" + run.map((p) => `${p[0].toFixed(1)},${p[1].toFixed(1)}`).join("L")
              + "L" + run.slice().reverse().map((p) => `${p[0].toFixed(1)},${p[2].toFixed(1)}`).join("L") + "Z";
          } else d += "M" + run.map((p) => `${p[0].toFixed(1)},${p[1].toFixed(1)}`).join("L");
        }
        out.push(`<path${id} class="${s.cls}" d="${d}"/>`);
      }
      if (s.label) legend.push(s);
    }
    out.push("</g>");
    legend.forEach((s, i) => {  // below the axes, two columns
      const Y = H + 4 + 13 * Math.floor(i / 2), X = 8 + (i % 2) * (W - 8) / 2;
      const mark = s.type === "band" ? `<rect class="${s.cls}" x="${X}" y="${Y - 8}" width="14" height="9"/>`
        : s.type === "points" ? `<circle class="${s.cls}" cx="${X + 7}" cy="${Y - 3}" r="3"/>`
          : `<line class="${s.cls}" x1="${X}" x2="${X + 14}" y1="${Y - 3}" y2="${Y - 3}"/>`;
      out.push(`${mark}<text class="legend" x="${X + 18}" y="${Y}">${esc(s.label)}</text>`);
    });
    out.push("</svg>");
    this.el.innerHTML = out.join("");
  }
}

// A colour scale from 0 to vmax: viridis-like ramp as an RGB string.
function ramp(t, stops) {
  t = Math.min(Math.max(t, 0), 1);
  const i = Math.min(Math.floor(t * (stops.length - 1)), stops.length - 2), f = t * (stops.length - 1) - i;
  const c = stops[i].map((v, k) => Math.round(v + f * (stops[i + 1][k] - v)));
  return `rgb(${c[0]},${c[1]},${c[2]})`;
}
