"""Fatigue model of the specification, section 3, with exact closed forms.

Per half-joint:  dc/dt = -k f c + R(f) (1 - c),   dU/dt = f / c^2   (t in minutes)
R(f) = R_rest x^2 (3 - 2x),  x = 1 - f/f_lim for f < f_lim, else 0.

A step of constant load f for a time T, from capacity c0:
    lam = k f + R,  a = R/lam,  b = c0 - a
    c(T) = a + b e^{-lam T}
    U(T) - U(0) = int_0^T f / c(t)^2 dt
                = f/(lam c0^2) [ phi(y) (u-1)^2 + (u-1)/(1+y) ]
      with u = e^{lam T}, y = a (u-1)/c0,  phi(y) = (log(1+y) - y/(1+y)) / y^2.
This is an algebraic rearrangement of the textbook antiderivative
    int dt/(a + b e^{-lam t})^2 = 1/(lam a^2) [ ln(a e^{lam t} + b) + b/(a e^{lam t} + b) ]
that stays accurate when a -> 0 (no recovery: phi(0) = 1/2 gives (e^{2kfT}-1)/(2 k c0^2)).
All functions accept complex loads so that derivatives can be taken by the complex-step method
(exact to machine precision, no subtractive cancellation).
"""
import cmath
import math

import numpy as np
from numba import njit


@njit(cache=True)
def _expm1c(z):
    if abs(z) < 1e-3:
        return z * (1.0 + z * (0.5 + z * (1.0 / 6.0 + z * (1.0 / 24.0 + z / 120.0))))
    return cmath.exp(z) - 1.0


@njit(cache=True)
def _phi(y):
    # (log(1+y) - y/(1+y)) / y^2 = sum_{n>=2} (-1)^n (n-1)/n y^(n-2)
    if abs(y) < 2e-2:
        s = 0.0 + 0.0j
        p = 1.0 + 0.0j
        for n in range(2, 14):
            sign = 1.0 if n % 2 == 0 else -1.0
            s += sign * (n - 1.0) / n * p
            p *= y
        return s
    return (cmath.log(1.0 + y) - y / (1.0 + y)) / (y * y)


@njit(cache=True)
def recovery_rate(f, r_rest, f_lim):
    if r_rest == 0.0:
        return 0.0 * f
    if f.real < f_lim:
        x = 1.0 - f / f_lim
        return r_rest * x * x * (3.0 - 2.0 * x)
    return 0.0 * f


@njit(cache=True)
def step(c0, f, k, T, r_rest, f_lim):
    """One step of constant load: returns (c(T), U increment). Complex-safe."""
    R = recovery_rate(f, r_rest, f_lim)
    lam = k * f + R
    if abs(lam) * T < 1e-300 or abs(lam) == 0.0:
        return c0 + 0.0 * f, f * T / (c0 * c0)
    a = R / lam
    em1 = _expm1c(lam * T)          # u - 1
    emt = 1.0 / (1.0 + em1)         # e^{-lam T}
    cT = a + (c0 - a) * emt
    y = a * em1 / c0
    dU = f / (lam * c0 * c0) * (_phi(y) * em1 * em1 + em1 / (1.0 + y))
    return cT, dU


@njit(cache=True)
def simulate(loads, ks, step_idx, step_dur, cycles, r_rest, f_lim):
    """loads[P1, H] (complex), ks[H], step_idx/step_dur: one cycle's steps (load row, minutes).

    Returns (U[H], c_end[H], t_exhaust[H] (minutes, -1 if never)) with U the fatigue index at the
    end of the task."""
    H = loads.shape[1]
    U = np.zeros(H, dtype=np.complex128)
    c = np.ones(H, dtype=np.complex128)
    tex = -np.ones(H)
    t = 0.0
    ns = step_idx.shape[0]
    for cyc in range(cycles):
        for s in range(ns):
            row = step_idx[s]
            T = step_dur[s]
            for h in range(H):
                f = loads[row, h]
                c0 = c[h]
                cT, dU = step(c0, f, ks[h], T, r_rest, f_lim)
                if tex[h] < 0.0 and f.real > 0.0:
                    if c0.real <= f.real:
                        tex[h] = t
                    elif cT.real <= f.real:
                        # c(t) = a + (c0-a) e^{-lam t} = f
                        fr = f.real
                        R = recovery_rate(f, r_rest, f_lim).real
                        lam = ks[h] * fr + R
                        a = R / lam
                        tex[h] = t + math.log((c0.real - a) / (fr - a)) / lam
                c[h] = cT
                U[h] += dU
            t += T
    return U, c, tex


def simulate_real(loads, ks, step_idx, step_dur, cycles, r_rest, f_lim):
    U, c, tex = simulate(np.asarray(loads, dtype=np.complex128), np.asarray(ks, float),
                         np.asarray(step_idx, np.int64), np.asarray(step_dur, float), int(cycles),
                         float(r_rest), float(f_lim))
    return U.real, c.real, tex


@njit(cache=True)
def simulate_grad(loads, ks, step_idx, step_dur, cycles, r_rest, f_lim, nvar):
    """Total U per half-joint and dU_h/d loads[p, h] for rows p < nvar (complex step, h=1e-30).

    Because half-joints are independent, perturbing a whole row at once gives every half-joint's
    partial derivative with respect to its own load in that row."""
    H = loads.shape[1]
    P1 = loads.shape[0]
    G = np.zeros((nvar, H))
    Ureal = np.zeros(H)
    hstep = 1e-30
    for p in range(nvar):
        L = np.zeros((P1, H), dtype=np.complex128)
        for i in range(P1):
            for h in range(H):
                L[i, h] = loads[i, h]
        for h in range(H):
            L[p, h] = loads[p, h] + 1j * hstep
        U, c, tex = simulate(L, ks, step_idx, step_dur, cycles, r_rest, f_lim)
        for h in range(H):
            G[p, h] = U[h].imag / hstep
            Ureal[h] = U[h].real
    return Ureal, G


# ----------------------------------------------------------------------------------------------
# real-valued versions: value only, and value + forward-mode derivatives
# ----------------------------------------------------------------------------------------------
@njit(cache=True)
def _phi_r(y):
    if abs(y) < 2e-2:
        s = 0.0
        p = 1.0
        for n in range(2, 14):
            sign = 1.0 if n % 2 == 0 else -1.0
            s += sign * (n - 1.0) / n * p
            p *= y
        return s
    return (math.log1p(y) - y / (1.0 + y)) / (y * y)


@njit(cache=True)
def step_real(c0, f, k, T, r_rest, f_lim):
    if r_rest == 0.0 or f >= f_lim:
        R = 0.0
    else:
        x = 1.0 - f / f_lim
        R = r_rest * x * x * (3.0 - 2.0 * x)
    lam = k * f + R
    if lam == 0.0:
        return c0, f * T / (c0 * c0)
    a = R / lam
    em1 = math.expm1(lam * T)
    emt = 1.0 / (1.0 + em1)
    cT = a + (c0 - a) * emt
    y = a * em1 / c0
    dU = f / (lam * c0 * c0) * (_phi_r(y) * em1 * em1 + em1 / (1.0 + y))
    return cT, dU


@njit(cache=True)
def simulate_value(loads, ks, step_idx, step_dur, cycles, r_rest, f_lim):
    H = loads.shape[1]
    U = np.zeros(H)
    c = np.ones(H)
    ns = step_idx.shape[0]
    for cyc in range(cycles):
        for s in range(ns):
            row = step_idx[s]
            T = step_dur[s]
            for h in range(H):
                cT, dU = step_real(c[h], loads[row, h], ks[h], T, r_rest, f_lim)
                c[h] = cT
                U[h] += dU
    return U


@njit(cache=True)
def simulate_fwd(loads, ks, step_idx, step_dur, cycles, r_rest, f_lim, nvar):
    """U[H] and G[nvar, H] = dU_h / d loads[p, h] by forward-mode propagation; the partial
    derivatives of each step are taken by the complex-step method (exact)."""
    H = loads.shape[1]
    U = np.zeros(H)
    G = np.zeros((nvar, H))
    ns = step_idx.shape[0]
    hs = 1e-30
    for h in range(H):
        c = 1.0
        dc = np.zeros(nvar)
        k = ks[h]
        # per step type partials depend on c0, so they are evaluated at every step
        for cyc in range(cycles):
            for s in range(ns):
                row = step_idx[s]
                T = step_dur[s]
                f = loads[row, h]
                # derivative wrt c0
                cT1, dU1 = step(complex(c, hs), complex(f, 0.0), k, T, r_rest, f_lim)
                dcT_dc0 = cT1.imag / hs
                ddU_dc0 = dU1.imag / hs
                cTv = cT1.real
                dUv = dU1.real
                if row < nvar:
                    cT2, dU2 = step(complex(c, 0.0), complex(f, hs), k, T, r_rest, f_lim)
                    dcT_df = cT2.imag / hs
                    ddU_df = dU2.imag / hs
                for p in range(nvar):
                    G[p, h] += ddU_dc0 * dc[p]
                    dc[p] = dcT_dc0 * dc[p]
                if row < nvar:
                    G[row, h] += ddU_df
                    dc[row] += dcT_df
                c = cTv
                U[h] += dUv
    return U, G


# ----------------------------------------------------------------------------------------------
# capacity constraint (statement section 4, bullet "capacity (no muscle group gives out)")
# ----------------------------------------------------------------------------------------------
@njit(cache=True)
def capacity_ends(loads, ks, step_idx, step_dur, cycles, r_rest, f_lim):
    """Capacity at the end of every step of the first and of the last cycle, in closed form.

    A step is affine in its start capacity, c -> alpha c + beta with alpha = e^{-lam T} and
    beta = a (1 - alpha); so is a cycle, c -> A c + B, and n cycles from c = 1 give
    c_n = A^n + B (1 + A + .. + A^{n-1}) with A = e^{-Lam}, Lam = sum lam T, and the geometric sum
    written as expm1(-n Lam) / expm1(-Lam) (n when Lam = 0). Complex-safe (complex-step
    derivatives). Returns C[ns, 2, H]: [:, 0] first cycle, [:, 1] last cycle."""
    H = loads.shape[1]
    ns = step_idx.shape[0]
    C = np.zeros((ns, 2, H), dtype=np.complex128)
    al = np.zeros(ns, dtype=np.complex128)
    be = np.zeros(ns, dtype=np.complex128)
    for h in range(H):
        Lam = 0.0 + 0.0j
        for s in range(ns):
            f = loads[step_idx[s], h]
            T = step_dur[s]
            R = recovery_rate(f, r_rest, f_lim)
            lam = ks[h] * f + R
            if abs(lam) == 0.0:
                al[s] = 1.0 + 0.0 * f
                be[s] = 0.0 * f
            else:
                e = _expm1c(-lam * T)        # alpha - 1
                al[s] = 1.0 + e
                be[s] = -(R / lam) * e
            Lam += lam * T
        B = 0.0 + 0.0j
        for s in range(ns):
            B = al[s] * B + be[s]
        m = cycles - 1
        if m == 0:
            cstart = 1.0 + 0.0j
        else:
            if abs(Lam) < 1e-12:
                geo = m + 0.0j
            else:
                geo = _expm1c(-m * Lam) / _expm1c(-Lam)
            cstart = cmath.exp(-m * Lam) + B * geo
        c1 = 1.0 + 0.0j
        cn = cstart
        for s in range(ns):
            c1 = al[s] * c1 + be[s]
            cn = al[s] * cn + be[s]
            C[s, 0, h] = c1
            C[s, 1, h] = cn
    return C
