"""The statistics of scripts/experiments.py (scripts/landing/common.py) against values worked by hand: pooling of
small expected counts, the χ² with the predictions' Monte-Carlo error, the degrees of freedom, Holm–Bonferroni and
the labellings the authors' rounded values cannot tell apart.

Run: /usr/bin/python3 -m pytest -q tests/scripts/landing_stats_test.py (Debian's python3 has scipy).
"""
import math
import os
import sys

import pytest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                "scripts"))
from landing import common  # noqa: E402


def test_holm_worked_by_hand():
    # p = [0.01, 0.04, 0.03, 0.005], m = 4. Sorted: 0.005 (#3), 0.01 (#0), 0.03 (#2), 0.04 (#1).
    # Times m − i + 1 = 4, 3, 2, 1: 0.02, 0.03, 0.06, 0.04; running maximum: 0.02, 0.03, 0.06, 0.06.
    # Back in the given order: [0.03, 0.06, 0.06, 0.02]. Rejected at 0.05: #3 and #0 (0.005 ≤ 0.05/4,
    # 0.01 ≤ 0.05/3, then 0.03 > 0.05/2 stops).
    assert common.holm([0.01, 0.04, 0.03, 0.005]) == pytest.approx([0.03, 0.06, 0.06, 0.02])


def test_holm_caps_at_one_and_keeps_ties():
    # m = 3: 0.2·3 = 0.6, 0.5·2 = 1.0, 0.5·1 = 0.5 → running maximum 0.6, 1.0, 1.0.
    assert common.holm([0.5, 0.2, 0.5]) == pytest.approx([1.0, 0.6, 1.0])
    assert common.holm([0.9]) == pytest.approx([0.9])
    assert common.holm([]) == []


def test_pooling_merges_smallest_into_next_smallest():
    # n = 100: expected 2, 10, 20, 30, 3, 35. The smallest (2, #0) joins the next-smallest (3, #4): 5 ≥ 5, done.
    counts, probs, groups = common.pool_small_expected([1, 10, 20, 30, 2, 37], [0.02, 0.1, 0.2, 0.3, 0.03, 0.35])
    assert groups == [[0, 4], [1], [2], [3], [5]]
    assert counts == [3, 10, 20, 30, 37]
    assert probs == pytest.approx([0.05, 0.1, 0.2, 0.3, 0.35])


def test_pooling_chains_and_stops_at_two_categories():
    # n = 100: expected 1, 1.5, 2, 95.5. 1 joins 1.5 → 2.5; then 2 (the smallest) joins 2.5 → 4.5, still < 5,
    # but only two categories are left, so pooling stops there.
    counts, probs, groups = common.pool_small_expected([0, 3, 1, 96], [0.01, 0.015, 0.02, 0.955])
    assert groups == [[0, 1, 2], [3]]
    assert counts == [4, 96]
    assert probs == pytest.approx([0.045, 0.955])
    assert common.goodness_of_fit([0, 3, 1, 96], [0.01, 0.015, 0.02, 0.955]).min_expected == pytest.approx(4.5)


def test_pooling_leaves_large_expected_counts_and_two_outcomes_alone():
    assert common.pool_small_expected([40, 60], [0.4, 0.6]) == ([40, 60], [0.4, 0.6], [[0], [1]])
    # Two outcomes are never pooled, however small the expected count (the cuboids' 2.5).
    assert common.pool_small_expected([3, 497], [0.005, 0.995])[2] == [[0], [1]]


def test_chi2_with_monte_carlo_error_by_hand():
    # n = 100, expected 40, 60: Pearson (30 − 40)²/40 + (70 − 60)²/60 = 2.5 + 1.6667 = 4.1667.
    assert common.chi2_statistic([30, 70], [0.4, 0.6]) == pytest.approx(25 / 6)
    # N = 100 drops: each term over (1 + n/N) = 2 → 2.0833.
    assert common.chi2_statistic([30, 70], [0.4, 0.6], drops=100) == pytest.approx(25 / 12)
    # n = 100, N = 400, expected 10, 30, 60: (4/10 + 0 + 4/60) / 1.25 = 0.46667 / 1.25 = 0.37333.
    assert common.chi2_statistic([12, 30, 58], [0.1, 0.3, 0.6], drops=400) == pytest.approx(0.37333333)


def test_goodness_of_fit_p_value_by_hand():
    # Two degrees of freedom: the χ² survival function is exp(−x/2); exp(−0.37333/2) = 0.82972.
    fit = common.goodness_of_fit([12, 30, 58], [0.1, 0.3, 0.6], drops=400)
    assert fit.dof == 2 and fit.groups == [[0], [1], [2]]
    assert fit.p == pytest.approx(math.exp(-0.37333333 / 2))
    assert fit.p == pytest.approx(0.82972, abs=1e-5)
    # One degree of freedom: the survival function is erfc(sqrt(x/2)); plain Pearson when N is not given.
    assert common.p_value([30, 70], [0.4, 0.6]) == pytest.approx(math.erfc(math.sqrt(25 / 12)))


def test_dof_rule():
    assert common.dof(5) == 4  # an object E and μ were not fitted on: k − 1
    assert common.dof(5, fitted=2) == 2  # the fit object, tossed: k − 1 − 2
    assert common.dof(3, fitted=2) == 0
    # The degrees of freedom follow the pooled k: 4 outcomes, expected 2, 3, 45, 50 → 3 categories.
    counts, probs = [3, 2, 45, 50], [0.02, 0.03, 0.45, 0.5]
    assert common.goodness_of_fit(counts, probs).dof == 2
    assert common.goodness_of_fit(counts, probs, fitted=2).dof == 0
    # No degree of freedom left: no p-value, and the table says so.
    fit = common.goodness_of_fit(counts, probs, fitted=2)
    assert math.isnan(fit.p)
    assert common.format_p(fit) == "— (0 dof)"


def test_tied_labellings_equal_authors_values():
    # The armadillo: the authors give 0.34, 0.34, 0.32; swapping the labels of their two 0.34 is not seen.
    exact, theirs = [0.3402, 0.3391, 0.3207], [0.34, 0.34, 0.32]
    assert common.tied_labellings(exact, theirs) == [(0, 1, 2), (1, 0, 2)]
    # The rule holds without the distance tolerance too.
    assert sorted(common.tied_labellings(exact, theirs, tolerance=0.0)) == [(0, 1, 2), (1, 0, 2)]


def test_tied_labellings_within_tolerance():
    # theirs 0.4001, 0.4, 0.2; exact 0.4, 0.4002, 0.2. (1, 0, 2): 0.0001² = 1e-8, the best; (0, 1, 2):
    # 0.0001² + 0.0002² = 5e-8, within 1e-6 of it; anything moving 0.2: ≥ 0.04.
    assert common.tied_labellings([0.4, 0.4002, 0.2], [0.4001, 0.4, 0.2]) == [(1, 0, 2), (0, 1, 2)]
    assert common.tied_labellings([0.4, 0.4002, 0.2], [0.4001, 0.4, 0.2], tolerance=1e-8) == [(1, 0, 2)]


def test_one_labelling_when_values_separate():
    # The kitten: repose 0.3368, 0.3487, 0.3145 against the authors' 0.3388, 0.3236, 0.3377; the best (1, 2, 0)
    # at 1.8e-4, the next (0, 2, 1) at 2.1e-4, 2.7e-5 apart: more than 1e-6.
    exact = [0.3367997857414922, 0.3486633659058956, 0.31453684835261264]
    theirs = [0.33879075542738124, 0.3235500280381319, 0.33765921653448694]
    assert common.tied_labellings(exact, theirs) == [(1, 2, 0)]
