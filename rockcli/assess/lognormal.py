"""Lognormal fragility fitted by maximum likelihood with censoring, and its bootstrap.

The statistics of :mod:`rockcli.assess.fragility` (read its docstring for the method): capacities are a
sample of a lognormal variable, some right-censored (no overturning up to the largest factor scanned)
or left-censored (overturning already at the smallest); :func:`fit_lognormal` maximises the censored
(Tobit) likelihood in ``ln IM`` by Newton's method in Olsen's parameters, :func:`bootstrap_lognormal`
resamples the records, :func:`fragility_probability` evaluates ``Phi(ln(x/theta)/beta)``.
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.errors import RockcliInputError

#: Bootstrap resamples of the confidence intervals, and the seed that makes them repeatable.
DEFAULT_N_BOOT = 1000
DEFAULT_SEED = 13

CENSORED_RIGHT = "right"
CENSORED_LEFT = "left"


def _censor_codes(censored, n: int) -> np.ndarray:
    """0 exact, +1 right-censored, -1 left-censored, from bools or ``"right"``/``"left"``/``""``."""
    if censored is None:
        return np.zeros(n, dtype=np.int8)
    codes = np.zeros(n, dtype=np.int8)
    for i, c in enumerate(censored):
        if c is True or c == CENSORED_RIGHT or c == 1:
            codes[i] = 1
        elif c == CENSORED_LEFT or c == -1:
            codes[i] = -1
        elif c not in (False, "", 0, None):
            raise RockcliInputError(f"censoring {c!r} is not one of '', 'right', 'left'")
    return codes


def _tobit_mle(x: np.ndarray, codes: np.ndarray, W: np.ndarray, *, max_iter: int = 100, tol: float = 1e-10):
    """MLE of a normal (mu, sigma) from exact and censored values, for each row of weights ``W``.

    Parameters
    ----------
    x : (n,) array
        Values (exact values, or censoring bounds).
    codes : (n,) int array
        0 exact, +1 right-censored (value > x), -1 left-censored (value < x).
    W : (B, n) array
        Non-negative weights (bootstrap counts; 1 for the plain fit).

    Returns
    -------
    mu, sigma : (B,) arrays
        NaN where the maximum does not exist (fewer than two distinct exact values).
    """
    from scipy.special import log_ndtr

    W = np.atleast_2d(np.asarray(W, dtype=float))
    exact = codes == 0
    right = codes == 1
    left = codes == -1
    # centre and scale for conditioning (the MLE is equivariant)
    shift = float(np.median(x))
    scale = float(np.std(x)) or 1.0
    z = (x - shift) / scale
    we = W * exact
    ne = we.sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        m0 = (we * z).sum(axis=1) / ne
        v0 = (we * (z - m0[:, None]) ** 2).sum(axis=1) / ne
    ok = (ne >= 2) & (v0 > 1e-12)
    B = W.shape[0]
    mu, sigma = np.full(B, np.nan), np.full(B, np.nan)
    if not ok.any():
        return mu, sigma
    Wk = W[ok]
    # Olsen's parameters: g = mu/sigma, d = 1/sigma; start from the moments of the exact values
    g = m0[ok] / np.sqrt(v0[ok])
    d = 1.0 / np.sqrt(v0[ok])

    def loglik(g, d):
        u = d[:, None] * z[None, :] - g[:, None]
        ll = np.where(exact, np.log(d)[:, None] - 0.5 * u * u, 0.0)
        ll = ll + np.where(right, log_ndtr(-u), 0.0) + np.where(left, log_ndtr(u), 0.0)
        return (Wk * ll).sum(axis=1)

    def derivatives(g, d):
        u = d[:, None] * z[None, :] - g[:, None]
        log_phi = -0.5 * u * u - 0.5 * math.log(2.0 * math.pi)
        lam = np.exp(log_phi - log_ndtr(-u))  # phi/Q: d/du of -log Q
        kap = np.exp(log_phi - log_ndtr(u))  # phi/Phi: d/du of log Phi
        # l_u and l_uu of each censored term
        l_u = np.where(right, -lam, np.where(left, kap, 0.0))
        l_uu = np.where(right, -lam * (lam - u), np.where(left, -kap * (kap + u), 0.0))
        # exact: l = log d - u^2/2
        gg = np.where(exact, u, -l_u)
        gd = np.where(exact, 1.0 / d[:, None] - u * z[None, :], l_u * z[None, :])
        hgg = np.where(exact, -1.0, l_uu)
        hgd = np.where(exact, z[None, :], -l_uu * z[None, :])
        hdd = np.where(exact, -1.0 / d[:, None] ** 2 - z[None, :] ** 2, l_uu * z[None, :] ** 2)
        s = lambda a: (Wk * a).sum(axis=1)  # noqa: E731
        return s(gg), s(gd), s(hgg), s(hgd), s(hdd)

    ll = loglik(g, d)
    active = np.ones(g.size, dtype=bool)
    for _ in range(max_iter):
        if not active.any():
            break
        Gg, Gd, Hgg, Hgd, Hdd = derivatives(g, d)
        det = Hgg * Hdd - Hgd * Hgd
        # Newton step of a concave function: -H^-1 grad (H negative definite)
        sg = -(Hdd * Gg - Hgd * Gd) / det
        sd = -(-Hgd * Gg + Hgg * Gd) / det
        sg, sd = np.where(active, sg, 0.0), np.where(active, sd, 0.0)
        t = np.ones_like(g)
        for _ in range(60):  # backtracking: keep d > 0 and do not decrease the likelihood
            gn, dn = g + t * sg, d + t * sd
            good = dn > 0
            lln = np.where(good, loglik(gn, np.where(good, dn, 1.0)), -np.inf)
            bad = active & ~(lln >= ll - 1e-12 * np.abs(ll))
            if not bad.any():
                break
            t = np.where(bad, 0.5 * t, t)
        g, d, ll = np.where(active, gn, g), np.where(active, dn, d), np.where(active, lln, ll)
        active &= (np.abs(t * sg) > tol * (1 + np.abs(g))) | (np.abs(t * sd) > tol * d)
    mu[ok] = shift + scale * g / d
    sigma[ok] = scale / d
    return mu, sigma


def fit_lognormal(values, censored=None) -> tuple[float, float]:
    """Maximum-likelihood lognormal (median, beta) of capacities, some of them censored.

    Parameters
    ----------
    values : sequence of float
        Capacities (> 0); for a censored record, its bound.
    censored : sequence, optional
        Per value: ``""``/False (exact), ``"right"``/True (the capacity exceeds the value: the
        record did not overturn the column up to the largest scale), ``"left"`` (it is below).

    Returns
    -------
    (median, beta)
        NaN when the maximum does not exist (fewer than two distinct exact values).

    Examples
    --------
    >>> m, b = fit_lognormal([0.2, 0.3, 0.45])
    >>> round(m, 4), round(b, 4)
    (0.3, 0.3311)
    """
    x = np.asarray(values, dtype=float)
    if x.ndim != 1 or not np.all(np.isfinite(x)) or np.any(x <= 0):
        raise RockcliInputError("capacities must be positive finite numbers")
    codes = _censor_codes(censored, x.size)
    mu, sigma = _tobit_mle(np.log(x), codes, np.ones((1, x.size)))
    return float(np.exp(mu[0])), float(sigma[0])


def bootstrap_lognormal(values, censored=None, *, n_boot: int = DEFAULT_N_BOOT, seed: int = DEFAULT_SEED,
                        indices: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Median and beta of ``n_boot`` resamples (with replacement) of the records; NaN where no fit exists.

    ``indices`` (n_boot x n) gives the resamples (to pair several fits on the same records).
    """
    x = np.log(np.asarray(values, dtype=float))
    codes = _censor_codes(censored, x.size)
    if indices is None:
        indices = np.random.default_rng(seed).integers(0, x.size, size=(n_boot, x.size))
    W = np.zeros((indices.shape[0], x.size))
    np.add.at(W, (np.repeat(np.arange(indices.shape[0]), indices.shape[1]), indices.ravel()), 1.0)
    mu, sigma = _tobit_mle(x, codes, W)
    return np.exp(mu), sigma


def fragility_probability(im, median: float, beta: float):
    """``Phi(ln(im / median) / beta)``: probability of overturning at intensity ``im``."""
    from scipy.special import ndtr

    im = np.asarray(im, dtype=float)
    with np.errstate(divide="ignore"):
        return ndtr(np.log(im / median) / beta)
