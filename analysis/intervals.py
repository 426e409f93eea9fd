"""Means over replications with their 95 % Student t confidence intervals.

One file for the report (analysis/) and the Python package latsim, which
carries a copy the build makes (python/CMakeLists.txt): no scipy needed.
"""

import math

# Two-sided 95 % quantiles of Student's t by degrees of freedom.
_T975 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306, 9: 2.262,
         10: 2.228, 11: 2.201, 12: 2.179, 13: 2.160, 14: 2.145, 15: 2.131, 16: 2.120, 17: 2.110,
         18: 2.101, 19: 2.093, 20: 2.086, 21: 2.080, 22: 2.074, 23: 2.069, 24: 2.064, 25: 2.060,
         26: 2.056, 27: 2.052, 28: 2.048, 29: 2.045, 30: 2.042, 40: 2.021, 60: 2.000, 120: 1.980}


def t975(df):
    """Student's t 97.5 % quantile; between tabulated points, linear in 1/df (exact to 3 decimals)."""
    if df in _T975:
        return _T975[df]
    keys = sorted(_T975)
    if df > keys[-1]:
        lo, hi, t_lo, t_hi = keys[-1], math.inf, _T975[keys[-1]], 1.960
    else:
        hi = next(k for k in keys if k > df)
        lo = max(k for k in keys if k < df)
        t_lo, t_hi = _T975[lo], _T975[hi]
    inv = lambda d: 0.0 if math.isinf(d) else 1.0 / d
    frac = (inv(lo) - inv(df)) / (inv(lo) - inv(hi))
    return t_lo + frac * (t_hi - t_lo)


def mean_ci95(values):
    """(mean, half width of the 95 % t-interval); the half width is 0 for fewer than two values."""
    n = len(values)
    mean = sum(values) / n
    if n < 2:
        return mean, 0.0
    var = sum((v - mean) ** 2 for v in values) / (n - 1)
    return mean, t975(n - 1) * math.sqrt(var / n)
