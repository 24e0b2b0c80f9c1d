// Ordinary Kriging prediction from the exported parameters, the same arithmetic as
// ringdamper/campaign/kriging/gp.py (GPModel) and transform.py (Transform):
//   R = [rho_theta(x_i - x_j)] + nu I = L L^T,  alpha = R^-1 (z - beta 1)
//   m(x0) = beta + r0 . alpha
//   s(x0) = sigma sqrt(psi max(1 + nu - |L^-1 r0|^2 + (1 - 1^T R^-1 r0)^2 / (1^T R^-1 1), 0))
// and the output y = T^-1(m), band [T^-1(m - 2 s), T^-1(m + 2 s)] with T^-1(z) = max(e^z - c, 0) (log)
// or z (identity).
"use strict";

const SIGMA_BAND = 2.0;

function correlation(kernel, d2) {
  if (kernel === "matern52") {
    const s = Math.sqrt(d2 * 5.0);
    return (s * s * (1.0 / 3.0) + s + 1.0) * Math.exp(-s);
  }
  if (kernel === "squared_exponential") return Math.exp(d2 * -0.5);
  throw new Error("unknown kernel " + kernel);
}

function scaledD2(a, b, invScale2) {
  let d2 = 0.0;
  for (let k = 0; k < 3; k++) { const d = a[k] - b[k]; d2 += invScale2[k] * (d * d); }
  return d2;
}

// Lower Cholesky factor (row-major rows) of a symmetric positive definite matrix.
function cholesky(A) {
  const n = A.length, L = A.map(() => new Float64Array(n));
  for (let j = 0; j < n; j++) {
    let d = A[j][j];
    const Lj = L[j];
    for (let k = 0; k < j; k++) d -= Lj[k] * Lj[k];
    if (!(d > 0)) throw new Error("correlation matrix not positive definite");
    const ljj = Math.sqrt(d);
    Lj[j] = ljj;
    for (let i = j + 1; i < n; i++) {
      const Li = L[i];
      let s = A[i][j];
      for (let k = 0; k < j; k++) s -= Li[k] * Lj[k];
      Li[j] = s / ljj;
    }
  }
  return L;
}

function forward(L, b) {  // L^-1 b
  const n = L.length, x = new Float64Array(n);
  for (let i = 0; i < n; i++) {
    const Li = L[i];
    let s = b[i];
    for (let k = 0; k < i; k++) s -= Li[k] * x[k];
    x[i] = s / Li[i];
  }
  return x;
}

function backward(L, b) {  // L^-T b
  const n = L.length, x = new Float64Array(n);
  for (let i = n - 1; i >= 0; i--) {
    let s = b[i];
    for (let k = i + 1; k < n; k++) s -= L[k][i] * x[k];
    x[i] = s / L[i][i];
  }
  return x;
}

// One model of kriging.nc, factorised once: p = exported parameters, kappa = training kappa rows.
class KrigingModel {
  constructor(p, kappa) {
    this.p = p;
    this.x = p.rows.map((r) => kappa[r]);
    this.invScale2 = p.scale.map((t) => 1.0 / (t * t));
    this.constant = p.sigma === 0.0;
    if (this.constant) return;
    const n = this.x.length;
    const R = this.x.map((xi) => this.x.map((xj) => correlation(p.kernel, scaledD2(xi, xj, this.invScale2))));
    for (let i = 0; i < n; i++) R[i][i] += p.nugget;
    this.L = cholesky(R);
    const ones = new Float64Array(n).fill(1.0);
    this.Linv1 = forward(this.L, ones);
    const Rinv1 = backward(this.L, this.Linv1);
    this.oneRinv1 = Rinv1.reduce((a, v) => a + v, 0.0);
    const Rinvz = backward(this.L, forward(this.L, Float64Array.from(p.z)));
    this.alpha = Rinvz.map((v, i) => v - p.beta * Rinv1[i]);
  }

  // Kriging mean m and standard deviation s of z = T(y) at kappa0.
  latent(kappa0) {
    const p = this.p;
    if (this.constant) return [p.beta, 0.0];
    const n = this.x.length, r = new Float64Array(n);
    let mean = 0.0;
    for (let i = 0; i < n; i++) {
      r[i] = correlation(p.kernel, scaledD2(kappa0, this.x[i], this.invScale2));
      mean += r[i] * this.alpha[i];
    }
    mean += p.beta;
    const b = forward(this.L, r);
    let bb = 0.0, l1b = 0.0;
    for (let i = 0; i < n; i++) { bb += b[i] * b[i]; l1b += this.Linv1[i] * b[i]; }
    const u = 1.0 - l1b;
    const v = 1.0 + p.nugget - bb + u * u / this.oneRinv1;
    return [mean, p.sigma * Math.sqrt(p.variance_factor * Math.max(v, 0.0))];
  }

  inverse(z) { return this.p.transform === "log" ? Math.max(Math.exp(z) - this.p.offset, 0.0) : z; }

  // {median, lower, upper} of the output y at kappa0 (the 95.45 % band).
  predict(kappa0) {
    const [m, s] = this.latent(kappa0);
    if (this.p.transform !== "log") return { median: m, lower: m - SIGMA_BAND * s, upper: m + SIGMA_BAND * s };
    return { median: this.inverse(m), lower: this.inverse(m - SIGMA_BAND * s), upper: this.inverse(m + SIGMA_BAND * s) };
  }
}

// Every model of the page: models[output][amplitude index] (null where none was fitted).
class Surrogate {
  constructor(data) {
    this.outputs = Object.keys(data.models);
    this.nAmp = data.amplitude.length;
    this.models = {};
    this.unfactorised = {};  // output -> amplitude indices whose R the browser could not factorise
    for (const out of this.outputs) {
      this.unfactorised[out] = [];
      this.models[out] = data.models[out].map((p, i) => {
        if (!p) return null;
        try { return new KrigingModel(p, data.training_kappa); } catch (err) { this.unfactorised[out].push(i); return null; }
      });
    }
  }

  // output -> {median, lower, upper} arrays over the amplitudes; null where no model was fitted.
  predict(kappa0) {
    const res = {};
    for (const out of this.outputs) {
      const med = [], lo = [], up = [];
      for (const model of this.models[out]) {
        const p = model ? model.predict(kappa0) : null;
        med.push(p ? p.median : null); lo.push(p ? p.lower : null); up.push(p ? p.upper : null);
      }
      res[out] = { median: med, lower: lo, upper: up };
    }
    return res;
  }
}
