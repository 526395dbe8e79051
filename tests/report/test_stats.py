"""Interval estimates and tests against independent or published reference values."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats as sps

from ladev_lib.report.stats import (
    chi2_homogeneity,
    cochran_armitage,
    fisher_exact,
    mcnemar_exact,
    newcombe_paired,
    newcombe_unpaired,
    wilson_interval,
)


@pytest.mark.parametrize("k,n", [(0, 1), (1, 1), (0, 10), (3, 10), (7, 34), (50, 100), (99, 100), (1, 500)])
@pytest.mark.parametrize("confidence", [0.9, 0.95, 0.99])
def test_wilson_matches_scipy(k, n, confidence):
    ref = sps.binomtest(k, n).proportion_ci(confidence_level=confidence, method="wilson")
    low, high = wilson_interval(k, n, confidence)
    assert low == pytest.approx(ref.low, abs=1e-12)
    assert high == pytest.approx(ref.high, abs=1e-12)


def test_wilson_textbook_value_and_empty_cell():
    # Newcombe (1998), Stat Med 17:857, Table II: 81/263 -> 0.2553 to 0.3662 (Wilson, method 3).
    low, high = wilson_interval(81, 263)
    assert (round(low, 4), round(high, 4)) == (0.2553, 0.3662)
    assert wilson_interval(0, 0) is None


def test_mcnemar_exact_on_hand_worked_tables():
    # b=8, c=2: P(X <= 2 | Bin(10, 1/2)) = (1 + 10 + 45) / 1024; two-sided doubles it.
    assert mcnemar_exact(8, 2) == pytest.approx(112 / 1024)
    assert mcnemar_exact(2, 8) == pytest.approx(112 / 1024)
    # b=0, c=5: 2 * (1/2)^5
    assert mcnemar_exact(0, 5) == pytest.approx(2 / 32)
    # Symmetric table: no evidence; no discordant pairs: p = 1.
    assert mcnemar_exact(4, 4) == 1.0
    assert mcnemar_exact(0, 0) == 1.0
    # Cavo et al. (2012) via Fagerland et al. (2017), ch. 8: b=6, c=16 -> exact p = 0.052.
    c22 = [math.comb(22, k) for k in range(7)]
    assert mcnemar_exact(6, 16) == pytest.approx(2 * sum(c22) / 2**22)
    assert round(mcnemar_exact(6, 16), 3) == 0.052


def test_newcombe_paired_matches_published_example():
    # Fagerland, Lydersen & Laake (2017), ch. 8, Cavo et al. (2012): [[59, 6], [16, 80]]
    # -> estimate -0.0621, 95% CI -0.1186 to -0.0046 (Newcombe square-and-add).
    d = newcombe_paired(59, 6, 16, 80)
    assert (round(d.estimate, 4), round(d.low, 4), round(d.high, 4)) == (-0.0621, -0.1186, -0.0046)


def test_newcombe_unpaired_matches_published_example():
    # Fagerland et al. (2017), ch. 4, Perondi et al. (2004): 7/34 vs 1/34
    # -> estimate 0.1765, 95% CI 0.0189 to 0.3404 (Newcombe hybrid score).
    d = newcombe_unpaired(7, 34, 1, 34)
    assert (round(d.estimate, 4), round(d.low, 4), round(d.high, 4)) == (0.1765, 0.0189, 0.3404)
    assert newcombe_unpaired(1, 0, 1, 10) is None


def test_paired_difference_interval_contains_estimate_and_stays_in_range():
    for a, b, c, d in [(0, 0, 0, 10), (10, 0, 0, 0), (0, 10, 0, 0), (3, 8, 2, 7), (1, 0, 5, 0)]:
        diff = newcombe_paired(a, b, c, d)
        assert -1.0 <= diff.low <= diff.estimate <= diff.high <= 1.0


def test_cochran_armitage_matches_agresti_and_an_independent_computation():
    # Agresti (2002), Table 2.7: alcohol consumption and malformation, scores 0, .5, 1.5, 4, 7.
    # Published: trend statistic 6.57, P = 0.01 (R prop.trend.test: 6.5699, p = 0.01037).
    cases, totals, scores = [48, 38, 5, 1, 1], [17114, 14502, 793, 127, 38], [0, 0.5, 1.5, 4, 7]
    test = cochran_armitage(cases, totals, scores)
    assert test.z**2 == pytest.approx(6.5699, abs=1e-3)
    assert test.p_value == pytest.approx(0.01037, abs=1e-5)
    assert test.z > 0  # malformation rises with consumption
    # Independently: z^2 = N r^2, r the correlation of score and outcome over all subjects.
    x = np.repeat(scores, totals)
    y = np.concatenate([np.r_[np.ones(k), np.zeros(n - k)] for k, n in zip(cases, totals, strict=True)])
    assert test.z**2 == pytest.approx(len(x) * np.corrcoef(x, y)[0, 1] ** 2, rel=1e-9)


def test_cochran_armitage_undefined_without_variation():
    assert cochran_armitage([0, 0, 0], [5, 5, 5], [1, 2, 3]) is None
    assert cochran_armitage([5, 5], [5, 5], [1, 2]) is None
    assert cochran_armitage([1, 2], [0, 0], [1, 2]) is None


def test_chi2_homogeneity_and_fisher_match_scipy():
    ks, ns = [3, 9, 5], [20, 20, 18]
    test = chi2_homogeneity(ks, ns)
    ref = sps.chi2_contingency([[k, n - k] for k, n in zip(ks, ns, strict=True)], correction=False)
    assert test.chi2 == pytest.approx(ref.statistic)
    assert test.p_value == pytest.approx(ref.pvalue)
    assert test.dof == 2
    assert chi2_homogeneity([0, 0, 0], [4, 4, 4]) is None
    assert fisher_exact(7, 10, 1, 10) == pytest.approx(sps.fisher_exact([[7, 3], [1, 9]]).pvalue)
