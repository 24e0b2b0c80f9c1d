"""Benchmark of the nonlinear dynamics core on a synthetic system of the real size (docs/design.md §8).

The synthetic blisk + ring: per harmonic ``h = 0..5`` a reference sector with ``n_blisk``
blisk and ``n_ring`` ring DoFs (Hermitian, complex for h ≥ 1 as under a cyclic constraint; the
ring's rotation and axial motion are zero-frequency modes of harmonic 0), ``npairs`` contact
pairs ring–blisk (70 % preloaded, 30 % with a small gap) whose motion amplitudes spread over two
decades (so that slip spreads progressively over the interface, as on the paper's ring), and a
response/forcing DoF on the blisk.
It reproduces the sizes that set the cost (≈100 pairs, a few hundred modes per harmonic), not the
physics of a particular geometry. :func:`run` times the dNNM + E-EBM for H = 1, 3, 5 and one
forced-response curve, and returns the timings; it asserts nothing.
"""
from __future__ import annotations

import cProfile
import io
import pstats
import time

import numpy as np

from ringdamper.nonlinear.contact.friction import FrictionContacts
from ringdamper.nonlinear.harmonic_balance.eebm import eebm
from ringdamper.nonlinear.harmonic_balance.epmc import epmc, linear_limit
from ringdamper.nonlinear.harmonic_balance.frf import forced_response, resonance_peak
from ringdamper.nonlinear.harmonic_balance.structure import HarmonicData, Structure


def synthetic_system(npairs: int = 100, n_blisk: int = 300, n_ring: int = 90, H: int = 5,
                     seed: int = 0, amp: float = 0.5, spread: float = 1.0):
    """Synthetic structure and contacts (see module docstring); target mode near 936 Hz with
    contact traces of size ``amp`` spread over ``spread`` decades across the pairs."""
    rng = np.random.default_rng(seed)
    p = 3 * npairs
    n = n_blisk + n_ring
    f_target = 936.0
    data = []
    for h in range(H + 1):
        cplx = h > 0
        wb = 2 * np.pi * np.r_[f_target * rng.uniform(0.97, 0.99),          # target mode first
                               np.exp(rng.uniform(np.log(300), np.log(2e4), n_blisk - 1))]
        wr = 2 * np.pi * np.exp(rng.uniform(np.log(1500), np.log(3e4), n_ring))
        if h == 0:
            wr[:2] = 0.0                                      # ring rotation and axial motion
        w2 = np.r_[wb, wr] ** 2
        # contact traces of the modes: the target blisk mode and the ring modes move the contacts
        amp_b = 0.3 / (1 + wb / wb.min())
        amp_b[0] = amp
        Pb = _random(rng, (p, n_blisk), cplx) * amp_b * 0.2
        Pb *= np.repeat(10.0 ** rng.uniform(-spread, 0.0, npairs), 3)[:, None]  # uneven slip
        Pr = _random(rng, (p, n_ring), cplx) * 0.05
        if h == 0:                                            # rigid ring: uniform t1 / t2
            Pr[:, :2] = 0.0
            Pr[1::3, 0] = Pr[2::3, 1] = 0.3
        Psi = np.hstack([-Pb, Pr])
        U = _unitary(rng, n, cplx)                            # hide the modal form
        K = (U * w2) @ U.conj().T
        M = np.eye(n)
        B = Psi @ U.conj().T
        e = np.zeros(n, complex if cplx else float)
        e[0] = 1.0
        resp = e @ U.conj().T
        data.append(HarmonicData(M=M, K=K, B=B, response=resp, force=resp.conj() if h == 1 else None))
    st = Structure(data)
    preload = rng.uniform(size=npairs) < 0.7
    contacts = FrictionContacts(kn=2e6, kt=1e6, mu=0.3, N0=np.where(preload, 20.0, 0.0),
                                gap=np.where(preload, 0.0, 2e-7))
    return st, contacts


def target_mode(st: Structure, contacts: FrictionContacts):
    """Index, frequency and shape of the stuck mode most similar to the response DoF's mode."""
    omega, phi = st.stuck_modes(contacts.stuck_stiffness().ravel())
    hd = st.harmonics[1]
    k = int(np.argmax(np.abs(hd.response @ phi)))
    return k, omega[k], phi[:, k]


def _random(rng, shape, cplx):
    a = rng.standard_normal(shape)
    return a + 1j * rng.standard_normal(shape) if cplx else a


def _unitary(rng, n, cplx):
    q, r = np.linalg.qr(_random(rng, (n, n), cplx))
    return q * (np.diag(r) / np.abs(np.diag(r)))


def time_frf(structure, contacts, gamma: float, omega: float, q_eebm: float, H: int,
             zeta_s: float, band: tuple) -> dict:
    """One forced-response curve at the E-EBM forcing ``gamma`` [N] of a backbone point
    (``omega`` [rad/s], peak amplitude ``q_eebm`` [m]) over ``band × omega``: wall time, points,
    status and the resonance peak relative to the E-EBM prediction."""
    t0 = time.perf_counter()
    frf = forced_response(structure, contacts, gamma, band[0] * omega, band[1] * omega, H=H,
                          zeta_s=zeta_s)
    peak = resonance_peak(frf)
    return {"seconds": time.perf_counter() - t0, "gamma_N": gamma, "points": len(frf.points),
            "status": int(frf.status), "peak_over_eebm": float(peak.q_peak / q_eebm),
            "peak_frequency_over_eebm": float(peak.omega / omega)}


def run(H_values=(1, 3, 5), n_alpha: int = 30, frf_H: int = 1, profile: bool = False) -> dict:
    """Time dNNM + E-EBM for each H and one forced-response curve; returns a dict of timings
    (seconds), point counts, Newton iterations and statuses. ``profile`` adds the top cumulative
    entries of a cProfile run of the largest H."""
    out = {}
    st, c = synthetic_system(H=max(max(H_values), frf_H))
    k, _, phi = target_mode(st, c)
    a_slip = linear_limit(st, c, phi)
    alpha = a_slip * np.logspace(-1, 2, n_alpha)
    t0 = time.perf_counter()
    for h in range(max(max(H_values), frf_H) + 1):
        st.modal(h)
    out["modal_decomposition_s"] = time.perf_counter() - t0
    for H in H_values:
        t0 = time.perf_counter()
        bb = epmc(st, c, alpha, H=H, mode=k)
        res = eebm(bb, zeta_s=1e-3)
        out[f"H{H}"] = {"dnnm_eebm_s": time.perf_counter() - t0,
                        "continuation_points": int(len(bb.branch)),
                        "newton_iterations": int(bb.iterations.sum()),
                        "converged": int(np.sum(bb.status == 0)), "grid": int(alpha.size),
                        "zeta_max": float(np.nanmax(res.zeta)),
                        "omega_drop": float(1 - np.nanmin(bb.omega) / bb.omega[0])}
        if H == frf_H:
            ref = res
    mid = int(np.nanargmax(np.where(ref.status == 0, ref.zeta, np.nan)))
    out["frf"] = {"H": frf_H, **time_frf(st, c, float(ref.gamma[mid]), float(ref.omega[mid]),
                                          float(ref.q_res_peak[mid]), frf_H, 1e-3, (0.985, 1.01))}
    if profile:
        pr = cProfile.Profile()
        pr.enable()
        epmc(st, c, alpha, H=max(H_values), mode=k)
        pr.disable()
        s = io.StringIO()
        pstats.Stats(pr, stream=s).sort_stats("cumulative").print_stats(25)
        out["profile"] = s.getvalue()
    return out


if __name__ == "__main__":
    import json
    import sys
    res = run(profile="--profile" in sys.argv)
    prof = res.pop("profile", None)
    print(json.dumps(res, indent=2))
    if prof:
        print(prof)
