#!/usr/bin/env python3
"""Rayleigh–Fourier reference efficiencies of shallow sine gratings for iridis-rigorous (numpy only).

Writes crates/rigorous/tests/fixtures/rayleigh_sine.json. Usage: python3 tools/gen_rayleigh_fixtures.py

The Rayleigh–Fourier method (Petit, "Electromagnetic Theory of Gratings", Springer 1980, ch. 1 and 5; Maystre,
Prog. Opt. 21, 1984, sec. 2) expands the field above and below the interface z = h(x) in the Rayleigh plane
waves down to the surface itself,

    above:  F = exp(i α₀x − i β₀z) + Σ_n R_n exp(i α_n x + i β_n z)
    below:  F = Σ_n T_n exp(i α_n x − i β'_n z),    α_n = α₀ + nK, β_n² = ε₁ − α_n², β'_n² = ε₂ − α_n²,

(F = E_y for TE, H_y for TM, lengths times k₀) and projects the boundary conditions at z = h(x) on exp(i α_m x):
F continuous, and p ∂F/∂N continuous with ∂/∂N = ∂/∂z − h'(x) ∂/∂x and p = 1 (TE) or 1/ε (TM). With
c_j(κ) the Fourier coefficients of exp(i κ h(x)), the projection of a wave exp(i α_n x + i κ z) gives
c_{m−n}(κ) for F and i c_{m−n}(κ) (ε − α_m α_n)/κ for ∂F/∂N (using FT[h' e^{iκh}]_j = (jK/κ) c_j(κ)).
The expansion holds on the surface (the Rayleigh hypothesis) for a sinusoid with K a < 0.448 (Petit &
Cadilhac 1966; Millar 1969), a/Λ < 0.071: the cases here stay at a/Λ ≤ 0.05, and each is solved with N = 25 and
N = 35 orders, both stored; the change is the reference's convergence estimate.

Nothing here shares code with the C-method of crates/rigorous (no coordinate transform, no eigenproblem):
an independent solution of the same boundary-value problem. Classical mount (φ = 0) only.
"""
import json
import os

import numpy as np

PERIOD = 1000.0
NX = 4096
HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "crates", "rigorous", "tests", "fixtures", "rayleigh_sine.json")


def kz(eps, a):
    k = np.sqrt(complex(eps) - a * a)
    if k.imag < 0 or (k.imag == 0 and k.real < 0):
        k = -k
    return k


def rayleigh_fourier(eps1, eps2, lam, theta_deg, amp, n_half, pol):
    k0 = 2 * np.pi / lam
    K = lam / PERIOD
    x = np.arange(NX) / NX
    h = k0 * amp * np.sin(2 * np.pi * x)  # normalised by k0
    ns = np.arange(-n_half, n_half + 1)
    n = len(ns)
    a0 = -np.sqrt(eps1) * np.sin(np.radians(theta_deg))  # incident wave travels along −ω_i
    al = a0 + ns * K
    b1 = np.array([kz(eps1, a) for a in al])
    b2 = np.array([kz(eps2, a) for a in al])
    p1, p2 = (1.0, 1.0) if pol == "te" else (1.0 / eps1, 1.0 / eps2)

    def coeffs(kappa):
        c = np.fft.fft(np.exp(1j * kappa * h)) / NX
        return c  # c[j] for j mod NX

    A = np.zeros((2 * n, 2 * n), dtype=complex)
    rhs = np.zeros(2 * n, dtype=complex)
    for j, (a_n, bn1, bn2) in enumerate(zip(al, b1, b2)):
        c_up = coeffs(bn1)
        c_dn = coeffs(-bn2)
        for i, a_m in enumerate(al):
            d = (ns[i] - ns[j]) % NX
            A[i, j] = c_up[d]
            A[i, n + j] = -c_dn[d]
            A[n + i, j] = p1 * c_up[d] * (eps1 - a_m * a_n) / bn1
            A[n + i, n + j] = -p2 * c_dn[d] * (eps2 - a_m * a_n) / (-bn2)
    b0 = kz(eps1, a0)
    c_in = coeffs(-b0)
    i0 = n_half
    for i, a_m in enumerate(al):
        d = (ns[i] - ns[i0]) % NX
        rhs[i] = -c_in[d]
        rhs[n + i] = -p1 * c_in[d] * (eps1 - a_m * a0) / (-b0)
    sol = np.linalg.solve(A, rhs)
    R, T = sol[:n], sol[n:]
    refl = {}
    trans = {}
    for j, m in enumerate(ns):
        if b1[j].imag == 0 and b1[j].real > 0:
            refl[int(m)] = float(b1[j].real / b0.real * abs(R[j]) ** 2)
        if np.imag(eps2) == 0 and b2[j].imag == 0 and b2[j].real > 0:
            # Flux ∝ β|E|² (TE) or β|H|²/ε (TM), relative to the incident β₀/ε₁^{0 or 1}.
            f = b2[j].real / b0.real * abs(T[j]) ** 2
            if pol == "tm":
                f *= eps1 / np.real(eps2)
            trans[int(m)] = float(f)
    return refl, trans


def main():
    media = {"glass": 2.25 + 0j, "metal": -20 + 1j}
    cases = []
    for material, eps in media.items():
        for ratio in (0.01, 0.03, 0.05):
            for lam in (450.0, 550.0, 650.0):
                for theta in (0.0, 30.0):
                    for pol in ("te", "tm"):
                        runs = []
                        for n_half in (25, 35):
                            refl, trans = rayleigh_fourier(1.0, eps, lam, theta, ratio * PERIOD, n_half, pol)
                            runs.append({"orders": n_half,
                                         "reflected": {str(m): v for m, v in sorted(refl.items())},
                                         "transmitted": {str(m): v for m, v in sorted(trans.items())}})
                        cases.append({"material": material, "eps": [eps.real, eps.imag], "period_nm": PERIOD,
                                      "amplitude_nm": ratio * PERIOD, "wavelength_nm": lam, "theta_deg": theta,
                                      "phi_deg": 0.0, "pol": pol, "runs": runs})
    doc = {"source": "Rayleigh–Fourier method, numpy; tools/gen_rayleigh_fixtures.py", "cases": cases}
    with open(OUT, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    # Energy check of the reference itself on glass.
    worst = 0.0
    for c in cases:
        if c["material"] == "glass":
            r = c["runs"][-1]
            worst = max(worst, abs(sum(r["reflected"].values()) + sum(r["transmitted"].values()) - 1))
    print("cases", len(cases), "worst |R+T-1| on glass", worst)


if __name__ == "__main__":
    main()
