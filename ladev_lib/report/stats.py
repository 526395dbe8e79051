"""Interval estimates and tests for success rates.

- Wilson score interval for one proportion (vectorised; also as polars expressions).
- McNemar's exact test for paired binary outcomes (same scene, two instructions).
- Newcombe's hybrid score intervals for a difference of two proportions,
  independent (Newcombe 1998a, method 10) and paired (Newcombe 1998b, method 10).
- Cochran–Armitage test for a linear trend of a proportion over ordered levels.
- Pearson's chi-squared test of homogeneity over unordered levels.
- Power: the minimum detectable difference (MDD) of an unpaired and a paired
  comparison at its n (80 % power, 5 % level by default).
- Cluster bootstrap intervals (scenes resampled whole) for rates over
  episodes that share a scene: trials, paired instructions.

All functions take counts and return plain floats (``None`` where a quantity is
undefined, e.g. a rate over zero episodes), so callers never divide by zero.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import polars as pl
from scipy import stats as sps
from scipy.optimize import brentq


def z_value(confidence: float) -> float:
    """Two-sided standard-normal quantile for ``confidence`` (1.96 for 0.95)."""
    return float(sps.norm.ppf(0.5 + confidence / 2.0))


def wilson_interval(successes: float, n: float, confidence: float = 0.95) -> tuple[float, float] | None:
    """Wilson score interval for ``successes`` out of ``n``; ``None`` when ``n`` is 0."""
    if n <= 0:
        return None
    z = z_value(confidence)
    p = successes / n
    denom = 1.0 + z * z / n
    centre = (p + z * z / (2.0 * n)) / denom
    half = z * math.sqrt(p * (1.0 - p) / n + z * z / (4.0 * n * n)) / denom
    return max(0.0, centre - half), min(1.0, centre + half)


def wilson_exprs(successes: pl.Expr, n: pl.Expr, confidence: float = 0.95) -> tuple[pl.Expr, pl.Expr]:
    """The Wilson bounds as polars expressions (null where ``n`` is 0)."""
    z2 = z_value(confidence) ** 2
    nf = n.cast(pl.Float64)
    p = successes.cast(pl.Float64) / nf
    denom = 1.0 + z2 / nf
    centre = (p + z2 / (2.0 * nf)) / denom
    half = (z2 * (p * (1.0 - p) / nf + z2 / (4.0 * nf * nf))).sqrt() / denom
    low = pl.when(n > 0).then(pl.max_horizontal(centre - half, pl.lit(0.0)))
    high = pl.when(n > 0).then(pl.min_horizontal(centre + half, pl.lit(1.0)))
    return low, high


def mcnemar_exact(b: int, c: int) -> float:
    """Two-sided exact McNemar p-value from the discordant counts ``b`` and ``c``.

    Under the null, ``b`` ~ Binomial(b + c, 1/2); the p-value doubles the smaller
    tail (capped at 1). With no discordant pairs there is no evidence either way: 1.
    """
    m = b + c
    if m == 0:
        return 1.0
    return float(min(1.0, 2.0 * sps.binom.cdf(min(b, c), m, 0.5)))


@dataclass(frozen=True)
class Difference:
    """A difference of two proportions ``p1 - p2`` with its interval."""

    estimate: float
    low: float
    high: float


def newcombe_unpaired(k1: int, n1: int, k2: int, n2: int, confidence: float = 0.95) -> Difference | None:
    """Hybrid score interval for ``k1/n1 - k2/n2`` from independent samples (Newcombe's method 10)."""
    w1 = wilson_interval(k1, n1, confidence)
    w2 = wilson_interval(k2, n2, confidence)
    if w1 is None or w2 is None:
        return None
    p1, p2 = k1 / n1, k2 / n2
    (l1, u1), (l2, u2) = w1, w2
    d = p1 - p2
    low = d - math.sqrt((p1 - l1) ** 2 + (u2 - p2) ** 2)
    high = d + math.sqrt((u1 - p1) ** 2 + (p2 - l2) ** 2)
    return Difference(d, max(-1.0, low), min(1.0, high))


def newcombe_paired(
    both: int, first_only: int, second_only: int, neither: int, confidence: float = 0.95
) -> Difference | None:
    """Hybrid score interval for the paired difference ``p1 - p2`` (Newcombe's method 10).

    ``first_only`` pairs succeeded under condition 1 only, ``second_only`` under 2 only.
    The correlation between the two outcomes (phi) narrows the interval; it is
    shrunk towards zero by n/2 when positive, as Newcombe prescribes.
    """
    a, b, c, d = both, first_only, second_only, neither
    n = a + b + c + d
    if n == 0:
        return None
    w1 = wilson_interval(a + b, n, confidence)
    w2 = wilson_interval(a + c, n, confidence)
    assert w1 is not None and w2 is not None
    p1, p2 = (a + b) / n, (a + c) / n
    (l1, u1), (l2, u2) = w1, w2
    margins = (a + b) * (c + d) * (a + c) * (b + d)
    cross = a * d - b * c
    if margins == 0:
        phi = 0.0
    elif cross > n / 2:
        phi = (cross - n / 2) / math.sqrt(margins)
    elif cross < 0:
        phi = cross / math.sqrt(margins)
    else:
        phi = 0.0
    diff = p1 - p2
    lower_sq = (p1 - l1) ** 2 - 2 * phi * (p1 - l1) * (u2 - p2) + (u2 - p2) ** 2
    upper_sq = (u1 - p1) ** 2 - 2 * phi * (u1 - p1) * (p2 - l2) + (p2 - l2) ** 2
    low = diff - math.sqrt(max(lower_sq, 0.0))
    high = diff + math.sqrt(max(upper_sq, 0.0))
    return Difference(diff, max(-1.0, low), min(1.0, high))


def fisher_exact(k1: int, n1: int, k2: int, n2: int) -> float:
    """Two-sided Fisher exact p-value for two independent proportions."""
    table = [[k1, n1 - k1], [k2, n2 - k2]]
    return float(sps.fisher_exact(table, alternative="two-sided").pvalue)


@dataclass(frozen=True)
class TrendTest:
    """Cochran–Armitage trend: ``z`` > 0 when success rises with the score."""

    z: float
    p_value: float
    slope: float  # least-squares change of the rate per unit of score


def cochran_armitage(
    successes: Sequence[int], totals: Sequence[int], scores: Sequence[float]
) -> TrendTest | None:
    """Cochran–Armitage test for a linear trend in proportions; ``None`` if undefined.

    Undefined when all rates are 0 or 1 overall, or fewer than two scores have data.
    """
    x = np.asarray(successes, dtype=float)
    n = np.asarray(totals, dtype=float)
    t = np.asarray(scores, dtype=float)
    big_n = n.sum()
    if big_n == 0:
        return None
    p_bar = x.sum() / big_n
    s_tt = float((n * t * t).sum() - (n * t).sum() ** 2 / big_n)
    variance = p_bar * (1.0 - p_bar) * s_tt
    if variance <= 0:
        return None
    statistic = float((t * (x - n * p_bar)).sum())
    z = statistic / math.sqrt(variance)
    return TrendTest(z=z, p_value=float(2.0 * sps.norm.sf(abs(z))), slope=statistic / s_tt)


@dataclass(frozen=True)
class HomogeneityTest:
    chi2: float
    dof: int
    p_value: float
    min_expected: float  # below 5, the chi-squared approximation is rough


def chi2_homogeneity(successes: Sequence[int], totals: Sequence[int]) -> HomogeneityTest | None:
    """Pearson's chi-squared test that all levels share one success rate.

    ``None`` when fewer than two levels have episodes or no level varies (all
    successes or all failures overall), where the test is undefined.
    """
    rows = [(k, m - k) for k, m in zip(successes, totals, strict=True) if m > 0]
    if len(rows) < 2:
        return None
    table = np.asarray(rows, dtype=float)
    if (table.sum(axis=0) == 0).any():
        return None
    expected = table.sum(axis=1, keepdims=True) * table.sum(axis=0, keepdims=True) / table.sum()
    chi2 = float(((table - expected) ** 2 / expected).sum())
    dof = len(rows) - 1
    return HomogeneityTest(chi2, dof, float(sps.chi2.sf(chi2, dof)), float(expected.min()))


# -- power: the smallest difference a comparison could detect ------------------

def _z_power(alpha: float, power: float) -> tuple[float, float]:
    return float(sps.norm.ppf(1.0 - alpha / 2.0)), float(sps.norm.ppf(power))


def _smallest_root(gap: Callable[[float], float], high: float) -> float | None:
    """The smallest d in (0, high] with gap(d) >= 0 (gap rises with d), or None."""
    if high <= 0 or gap(high) < 0:
        return None
    grid = np.linspace(0.0, high, 401)[1:]
    ok = [d for d in grid if gap(float(d)) >= 0]
    hi = float(ok[0])
    lo = max(hi - high / 400.0, 1e-12)
    if gap(lo) >= 0:
        return lo
    return float(brentq(gap, lo, hi, xtol=1e-9))


def mdd_two_proportions(p0: float, n0: int, n1: int, alpha: float = 0.05, power: float = 0.8) -> float | None:
    """Minimum detectable difference between two independent proportions (two-sided z test).

    The smallest ``d`` such that a level at ``p0 ± d`` (n1 episodes) differs from a
    baseline at ``p0`` (n0 episodes) with probability ``power`` at level ``alpha``
    (Fleiss' normal approximation, no continuity correction: pooled variance under the
    null, unpooled under the alternative). The smaller of the two directions that fit
    in [0, 1]; None when no difference is detectable at these n.
    """
    if n0 <= 0 or n1 <= 0:
        return None
    za, zb = _z_power(alpha, power)
    best: float | None = None
    for sign in (-1.0, 1.0):
        room = p0 if sign < 0 else 1.0 - p0

        def gap(d: float, sign: float = sign) -> float:
            p1 = p0 + sign * d
            pbar = (n0 * p0 + n1 * p1) / (n0 + n1)
            null_sd = math.sqrt(max(pbar * (1 - pbar), 0.0) * (1 / n0 + 1 / n1))
            alt_sd = math.sqrt(max(p0 * (1 - p0) / n0 + p1 * (1 - p1) / n1, 0.0))
            return d - (za * null_sd + zb * alt_sd)

        d = _smallest_root(gap, room)
        if d is not None and (best is None or d < best):
            best = d
    return best


def mdd_paired(n_pairs: int, discordant_rate: float, alpha: float = 0.05, power: float = 0.8) -> float | None:
    """Minimum detectable paired difference (McNemar, Connor 1987's normal approximation).

    A difference ``d`` = p(level only) - p(baseline only) is detected with ``power`` when
    sqrt(n) d >= z_(1-alpha/2) sqrt(psi) + z_power sqrt(psi - d^2), with psi the rate of
    discordant pairs: the observed one, and never below ``d`` (pairs cannot differ by more
    than they disagree). None when no difference up to 1 is detectable with n pairs.
    """
    if n_pairs <= 0:
        return None
    za, zb = _z_power(alpha, power)
    root_n = math.sqrt(n_pairs)

    def gap(d: float) -> float:
        psi = min(1.0, max(discordant_rate, d))
        return root_n * d - (za * math.sqrt(psi) + zb * math.sqrt(max(psi - d * d, 0.0)))

    return _smallest_root(gap, 1.0)


# -- clustered intervals ---------------------------------------------------------

def cluster_bootstrap_rate(
    successes: Sequence[float],
    totals: Sequence[float],
    confidence: float = 0.95,
    samples: int = 2000,
    seed: int = 0,
) -> tuple[float, float] | None:
    """Percentile interval of sum(successes)/sum(totals), resampling clusters (scenes) whole.

    Episodes of one scene (its trials, its instructions) are not independent; resampling
    scenes with replacement keeps that dependence. Deterministic for a given seed.
    None without clusters or episodes.
    """
    k = np.asarray(successes, dtype=float)
    n = np.asarray(totals, dtype=float)
    if k.size == 0 or n.sum() <= 0:
        return None
    rng = np.random.default_rng(seed)
    idx = rng.integers(0, k.size, size=(samples, k.size))
    num, den = k[idx].sum(axis=1), n[idx].sum(axis=1)
    rates = num[den > 0] / den[den > 0]
    tail = (1.0 - confidence) / 2.0
    return float(np.quantile(rates, tail)), float(np.quantile(rates, 1.0 - tail))


def cluster_bootstrap_mean(
    values: Sequence[float],
    weights: Sequence[float],
    confidence: float = 0.95,
    samples: int = 2000,
    seed: int = 0,
) -> tuple[float, float] | None:
    """Percentile interval of a weighted mean over clusters: sum(values)/sum(weights), where
    ``values[i]`` sums a cluster's per-unit values (e.g. paired differences) and
    ``weights[i]`` counts its units. The same resampling as :func:`cluster_bootstrap_rate`."""
    return cluster_bootstrap_rate(values, weights, confidence, samples, seed)
