// The design explorer: kappa controls, presets, the URL fragment, and the panels (docs/explorer.md).
"use strict";

const DATA = JSON.parse(document.getElementById("explorer-data").textContent);
const NAMES = { q_res_z: "|q_res,z|", omega0: "ω0", zeta: "ζ", gamma: "γ" };
// display scale and unit of each output (SI values times the scale)
const SHOW = {
  q_res_z: { scale: 1e6, unit: "µm" }, omega0: { scale: 1, unit: "1, normalised" },
  zeta: { scale: 100, unit: "%" }, gamma: { scale: 1, unit: "N" },
};
const N_NEAREST = 3;
const surrogate = new Surrogate(DATA);
const state = { kappa: [0, 0, 0], gamma: null };
const timing = { interactive_ms: null, redraw_ms: [], redraw_frame_ms: [] };

function scaled(values, out) { return values.map((v) => (v === null ? null : v * SHOW[out].scale)); }
function label(out) { return `${NAMES[out]} (${SHOW[out].unit})`; }
function num(v, out, digits = 4) { return v === null || !Number.isFinite(v) ? "no model" : `${Number((v * SHOW[out].scale).toPrecision(digits))} ${SHOW[out].unit}`; }
function kappaText(k) { return "(" + k.map((v) => (+v.toFixed(3)).toString()).join(", ") + ")"; }
const $ = (id) => document.getElementById(id);

// ---------- kappa input: clamping, URL fragment ----------
function clampNote(messages) {
  const note = $("clamp-note");
  note.textContent = messages.join(" ");
  note.classList.toggle("visible", messages.length > 0);
}

function parseKappa(raw, previous) {
  // kappa from three strings; out-of-range values clamped to [-1, 1], non-numbers keep ``previous``
  const messages = [];
  const k = raw.map((s, i) => {
    const v = Number(s);
    if (String(s).trim() === "" || !Number.isFinite(v)) { messages.push(`κ${i + 1} = “${s}” is not a number: kept ${previous[i]}.`); return previous[i]; }
    if (v < -1 || v > 1) { const c = Math.min(Math.max(v, -1), 1); messages.push(`κ${i + 1} = ${v} is outside [−1, 1]: clamped to ${c}.`); return c; }
    return v;
  });
  return { kappa: k, messages };
}

function writeHash() {
  const hash = "#k=" + state.kappa.map((v) => +v.toFixed(4)).join(",");
  if (location.hash !== hash) history.replaceState(null, "", hash);
  $("share").textContent = location.href;
}

function readHash() {
  const m = /^#k=([^&]*)/.exec(location.hash);
  if (!m) return false;
  const parts = decodeURIComponent(m[1]).split(",");
  while (parts.length < 3) parts.push("");
  const { kappa, messages } = parseKappa(parts.slice(0, 3), state.kappa);
  clampNote(messages.map((s) => "URL: " + s));
  setKappa(kappa, false);
  return true;
}

function setKappa(k, clearNote = true) {
  state.kappa = k.slice();
  if (clearNote) clampNote([]);
  for (let i = 0; i < 3; i++) { $(`slider-k${i + 1}`).value = k[i]; $(`input-k${i + 1}`).value = k[i]; }
  update();
}

// ---------- the computed rings ----------
function distance(a, b) { return Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]); }
function nearestRings(k) {
  return DATA.rings.map((r) => ({ ring: r, d: distance(r.kappa, k) })).sort((a, b) => a.d - b.d).slice(0, N_NEAREST);
}

// ---------- backbone read at a forcing level (E-EBM resonant amplitude) ----------
function atLevel(x, y, level, last) {
  // y where x = level on the piecewise-linear curve (the last crossing if ``last``); null if never
  const segs = [];
  for (let i = 0; i + 1 < x.length; i++) {
    const [xa, xb, ya, yb] = [x[i], x[i + 1], y[i], y[i + 1]];
    if ([xa, xb, ya, yb].some((v) => v === null)) continue;
    if (Math.min(xa, xb) <= level && level <= Math.max(xa, xb)) segs.push([xa, xb, ya, yb]);
  }
  if (!segs.length) return null;
  const [xa, xb, ya, yb] = last ? segs[segs.length - 1] : segs[0];
  const t = xb !== xa ? (level - xa) / (xb - xa) : 0;
  return ya + t * (yb - ya);
}

// ---------- panels ----------
const charts = {};
function makeCharts() {
  const q = label("q_res_z");
  for (const out of ["omega0", "zeta", "gamma"]) {
    charts[out] = new Chart($(`chart-${out}`), { title: `${NAMES[out]} against ${NAMES.q_res_z}`, xlabel: q + ", log", ylabel: label(out), xlog: true });
  }
  charts.forcing = new Chart($("chart-forcing"), { title: `resonant ${NAMES.q_res_z} against forcing`, xlabel: label("gamma") + ", log", ylabel: q, xlog: true });
  for (const [a, b] of [[0, 1], [0, 2], [1, 2]]) {
    charts[`k${a + 1}${b + 1}`] = new Chart($(`chart-k${a + 1}${b + 1}`), { title: `κ${a + 1}–κ${b + 1} projection`, xlabel: `κ${a + 1} (1)`, ylabel: `κ${b + 1} (1)`, width: 270, height: 250 });
  }
  for (const kind of ["pressure", "gap"]) charts[kind] = new Chart($(`map-${kind}`), { xlabel: "circumferential position (mm)", ylabel: "z (mm)", width: 420, height: 200 });
}

const reference = {};  // predictions of the default ring and the optimum, computed once
function backboneSeries(out, pred, nearest) {
  const x = scaled(pred.q_res_z.median, "q_res_z");
  const series = [
    { type: "band", x, y: scaled(pred[out].lower, out), y2: scaled(pred[out].upper, out), cls: "band", label: "95.45 % Kriging band at κ", id: `band-${out}` },
    { type: "line", x: scaled(reference.default.q_res_z.median, "q_res_z"), y: scaled(reference.default[out].median, out), cls: "default", label: "default ring (median)" },
    { type: "line", x: scaled(reference.optimum.q_res_z.median, "q_res_z"), y: scaled(reference.optimum[out].median, out), cls: "optimum", label: "optimum (median)" },
    { type: "line", x, y: scaled(pred[out].median, out), cls: "current", label: "prediction at κ (median)", id: `curve-${out}` },
  ];
  nearest.forEach(({ ring, d }, i) => series.push({
    type: "points", x: scaled(ring.backbone.q_res_z, "q_res_z"), y: scaled(ring.backbone[out], out),
    cls: `ring ring${i}`, label: `${ring.gid} computed (d = ${d.toFixed(2)})`, names: ring.backbone.q_res_z.map(() => `${ring.gid} (${ring.split}), κ = ${kappaText(ring.kappa)}`),
  }));
  return series;
}

function drawForcing(pred) {
  const g = state.gamma, q = "q_res_z";
  const at = (p) => atLevel(p.gamma.median, p.q_res_z.median, g, true);
  const qk = at(pred), qd = at(reference.default);
  charts.forcing.draw([
    { type: "line", x: reference.default.gamma.median, y: scaled(reference.default.q_res_z.median, q), cls: "default", label: "default ring (median backbone)" },
    { type: "line", x: pred.gamma.median, y: scaled(pred.q_res_z.median, q), cls: "current", label: "prediction at κ (median backbone)", id: "curve-forcing" },
    { type: "vline", at: g, cls: "forcing", label: `forcing γ = ${g.toPrecision(3)} N` },
    { type: "points", x: [g, g], y: [qd === null ? null : qd * 1e6, qk === null ? null : qk * 1e6], cls: "resonance", r: 4, names: ["default", "κ"] },
  ]);
  const ratio = qk !== null && qd !== null && qd > 0 ? ` (${qk >= qd ? "+" : ""}${((qk / qd - 1) * 100).toFixed(1)} %)` : "";
  $("forcing-readout").textContent = `At γ = ${g.toPrecision(3)} N the predicted E-EBM resonant amplitude is `
    + `${qk === null ? "not reached (the backbone at κ does not reach this forcing)" : num(qk, q)} at κ against `
    + `${qd === null ? "not reached" : num(qd, q)} for the default ring${ratio}.`;
}

function drawKappaSpace(nearest) {
  const train = DATA.rings.filter((r) => r.split === "training"), valid = DATA.rings.filter((r) => r.split === "validation");
  for (const [a, b] of [[0, 1], [0, 2], [1, 2]]) {
    const pts = (rs, cls, lab) => ({ type: "points", x: rs.map((r) => r.kappa[a]), y: rs.map((r) => r.kappa[b]), cls, label: lab, names: rs.map((r) => `${r.gid}, κ = ${kappaText(r.kappa)}`) });
    charts[`k${a + 1}${b + 1}`].draw([
      pts(train, "train", "training rings"), pts(valid, "valid", "validation rings"),
      pts(nearest.slice(0, 1).map((n) => n.ring), "near", "nearest ring"),
      { type: "points", x: [DATA.presets.optimum[a]], y: [DATA.presets.optimum[b]], cls: "opt-mark", r: 5, label: "optimum" },
      { type: "points", x: [state.kappa[a]], y: [state.kappa[b]], cls: "current-mark", r: 5, label: "current κ", names: [kappaText(state.kappa)] },
    ], { x: [-1.08, 1.08], y: [-1.08, 1.08] });
  }
}

const VIRIDIS = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
const MAGMA = [[0, 0, 4], [81, 18, 124], [183, 55, 121], [252, 137, 97], [252, 253, 191]];
function drawContact(ring) {
  const c = ring && ring.contact;
  $("contact-title").textContent = c ? `Contact maps of the nearest computed ring ${ring.gid} (${ring.split}), κ = ${kappaText(ring.kappa)}: ${c.n_in_contact >= 0 ? `${c.n_in_contact} of ${c.pressure.length} pairs in contact` : "its static solve failed"}`
    : "No static state was given for the nearest ring.";
  for (const [kind, scale, unit, stops, what] of [["pressure", 1e-3, "kPa", VIRIDIS, "static contact pressure N0 / area"], ["gap", 1e6, "µm", MAGMA, "static gap"]]) {
    if (!c) { $(`map-${kind}`).innerHTML = ""; continue; }
    const v = c[kind].map((x) => (x === null ? null : x * scale));
    const top = Math.max(0, ...v.filter((x) => x !== null)), vmax = top > 0 ? top : 1;
    charts[kind].o.title = `${what} (${unit})`;
    charts[kind].draw([{ type: "points", x: c.s.map((s) => (s === null ? null : s * 1e3)), y: c.z.map((z) => (z === null ? null : z * 1e3)), cls: "pair", r: 4,
      fill: v.map((x) => (x === null ? "#ccc" : ramp(x / vmax, stops))), names: v.map((x) => (x === null ? "no value" : `${x.toPrecision(3)} ${unit}`)) }]);
    $(`bar-${kind}`).innerHTML = `<span>0</span><span class="bar" style="background:linear-gradient(to right,${stops.map((s) => `rgb(${s})`).join(",")})"></span><span>${top > 0 ? `${top.toPrecision(3)} ${unit}` : `${unit}: every pair at 0`}</span>`;
  }
}

function drawNearestTable(nearest) {
  $("nearest").innerHTML = "<tr><th>ring</th><th>split</th><th>κ</th><th>κ-distance</th></tr>"
    + nearest.map(({ ring, d }, i) => `<tr class="ring${i}"><td>${ring.gid}</td><td>${ring.split}</td><td>${kappaText(ring.kappa)}</td><td>${d.toFixed(3)}</td></tr>`).join("");
}

function drawSummary(pred) {
  let best = -1;
  pred.zeta.median.forEach((z, i) => { if (z !== null && (best < 0 || z > pred.zeta.median[best])) best = i; });
  $("summary").textContent = best < 0 ? "No ζ model at any amplitude." :
    `Largest predicted ζ along the backbone at κ = ${kappaText(state.kappa)}: ${num(pred.zeta.median[best], "zeta")} `
    + `(95.45 % band ${num(pred.zeta.lower[best], "zeta")} – ${num(pred.zeta.upper[best], "zeta")}) at ${NAMES.q_res_z} = ${num(pred.q_res_z.median[best], "q_res_z")}.`;
}

function modelNotes() {
  // where an output has no model (not fitted) or a constant one, in words
  const notes = [];
  for (const out of surrogate.outputs) {
    const none = [], constant = [];
    DATA.models[out].forEach((p, i) => { if (!p) none.push(i); else if (p.sigma === 0) constant.push(i); });
    const amps = (idx) => idx.map((i) => DATA.amplitude[i].toExponential(2)).join(", ");
    if (none.length) notes.push(`${NAMES[out]}: no model at ${none.length} of ${DATA.amplitude.length} amplitudes (α = ${amps(none)} ${DATA.amplitude_units}): too few usable training rings; not drawn.`);
    const bad = surrogate.unfactorised[out];
    if (bad.length) notes.push(`${NAMES[out]}: the browser could not factorise the model at ${bad.length} amplitude${bad.length > 1 ? "s" : ""} (α = ${amps(bad)} ${DATA.amplitude_units}): not drawn.`);
    if (constant.length) notes.push(`${NAMES[out]}: constant model at ${constant.length} amplitude${constant.length > 1 ? "s" : ""} (α = ${amps(constant)} ${DATA.amplitude_units}): the training data are constant there, the band has zero width.`);
  }
  $("model-notes").innerHTML = notes.length ? notes.map((n) => `<li>${n}</li>`).join("") : "<li>Every output has a Gaussian-process model at every amplitude.</li>";
}

function update() {
  const t0 = performance.now();
  const pred = surrogate.predict(state.kappa);
  const nearest = nearestRings(state.kappa);
  for (const out of ["omega0", "zeta", "gamma"]) charts[out].draw(backboneSeries(out, pred, nearest));
  drawForcing(pred);
  drawKappaSpace(nearest);
  drawNearestTable(nearest);
  drawContact(nearest.length ? nearest[0].ring : null);
  drawSummary(pred);
  writeHash();
  const t1 = performance.now();
  if (timing.redraw_ms.length >= 1000) { timing.redraw_ms.length = 0; timing.redraw_frame_ms.length = 0; }
  timing.redraw_ms.push(t1 - t0);
  requestAnimationFrame(() => setTimeout(() => timing.redraw_frame_ms.push(performance.now() - t0), 0));
}

// ---------- controls ----------
function gammaRange() {
  const g = DATA.rings.flatMap((r) => r.backbone.gamma).filter((v) => v !== null && v > 0);
  return g.length ? [Math.min(...g), Math.max(...g)] : [1, 10];
}

function initControls() {
  for (let i = 0; i < 3; i++) {
    $(`slider-k${i + 1}`).addEventListener("input", (e) => { const k = state.kappa.slice(); k[i] = Number(e.target.value); setKappa(k); });
    $(`input-k${i + 1}`).addEventListener("change", (e) => {
      if (e.target.value.trim() === "") return;  // emptied to type a new value
      const raw = state.kappa.map(String); raw[i] = e.target.value;
      const { kappa, messages } = parseKappa(raw, state.kappa);
      setKappa(kappa, false);
      clampNote(messages);
    });
  }
  const box = $("presets");
  for (const [name, k] of Object.entries(DATA.presets)) {
    const b = document.createElement("button");
    b.textContent = name; b.title = `κ = ${kappaText(k)}`; b.dataset.preset = name;
    b.addEventListener("click", () => setKappa(k));
    box.appendChild(b);
  }
  const [g0, g1] = gammaRange(), slider = $("gamma-slider");
  const toGamma = (t) => g0 * Math.pow(g1 / g0, t);
  let start = atLevel(reference.default.q_res_z.median, reference.default.gamma.median, DATA.reference_amplitude, false);
  if (start === null || !(start > 0)) start = Math.sqrt(g0 * g1);
  state.gamma = start;
  slider.value = Math.min(Math.max(Math.log(start / g0) / Math.log(g1 / g0), 0), 1);
  slider.addEventListener("input", () => { state.gamma = toGamma(Number(slider.value)); drawForcing(surrogate.predict(state.kappa)); });
  window.addEventListener("hashchange", readHash);
}

function init() {
  reference.default = surrogate.predict(DATA.presets.default);
  reference.optimum = surrogate.predict(DATA.presets.optimum);
  makeCharts();
  initControls();
  modelNotes();
  if (!readHash()) setKappa(DATA.presets.default);
  timing.interactive_ms = performance.now();
  document.body.dataset.ready = "1";
}

init();
window.explorer = {
  predict: (k) => surrogate.predict(k), setKappa, kappa: () => state.kappa.slice(), timing,
};
