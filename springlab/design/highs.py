"""Small linear programmes solved by HiGHS through highspy directly.

scipy's ``linprog`` wraps the same solver; called directly a programme of a few dozen rows costs
about 0.3 ms here against 1.5-3 ms through ``linprog`` (its checks and conversions), and the
searches of :mod:`springlab.design.feasibility` and :mod:`springlab.design.certificates` solve
thousands.
"""

from __future__ import annotations

import os
import sys

import numpy as np

INF = float("inf")

_BANNER_SHOWN = False


def new_model():
    """A silent single-threaded HiGHS model. The first one of a process is made with the C library's
    standard output sent to /dev/null: HiGHS prints its banner there when the first model is made,
    before any option can turn output off (in a notebook it landed in the cell's output)."""
    import highspy

    global _BANNER_SHOWN
    if _BANNER_SHOWN:
        h = highspy.Highs()
    else:
        sys.stdout.flush()
        saved, null = os.dup(1), os.open(os.devnull, os.O_WRONLY)
        try:
            os.dup2(null, 1)
            h = highspy.Highs()
        finally:
            os.dup2(saved, 1)
            os.close(saved)
            os.close(null)
        _BANNER_SHOWN = True
    h.setOptionValue("output_flag", False)
    h.setOptionValue("threads", 1)  # thousands of tiny programmes: no thread pool
    return h


_MODEL = None


def solve(cost, A, row_lower, row_upper, col_lower, col_upper):
    """Minimise cost @ x subject to row_lower <= A x <= row_upper and col_lower <= x <= col_upper
    (``inf`` for no bound; A dense or scipy sparse). Returns (x, row duals), or None when the
    programme is infeasible or the solver stops short of an optimum."""
    import highspy
    from scipy.sparse import csc_matrix

    global _MODEL
    if _MODEL is None:
        _MODEL = new_model()
    A = csc_matrix(A)
    lp = highspy.HighsLp()
    lp.num_col_, lp.num_row_ = A.shape[1], A.shape[0]
    lp.col_cost_ = np.asarray(cost, dtype=float)
    lp.col_lower_ = np.where(np.isinf(col_lower), -highspy.kHighsInf, col_lower).astype(float)
    lp.col_upper_ = np.where(np.isinf(col_upper), highspy.kHighsInf, col_upper).astype(float)
    lp.row_lower_ = np.where(np.isinf(row_lower), -highspy.kHighsInf, row_lower).astype(float)
    lp.row_upper_ = np.where(np.isinf(row_upper), highspy.kHighsInf, row_upper).astype(float)
    lp.a_matrix_.format_ = highspy.MatrixFormat.kColwise
    lp.a_matrix_.start_ = A.indptr.astype(np.int32)
    lp.a_matrix_.index_ = A.indices.astype(np.int32)
    lp.a_matrix_.value_ = A.data.astype(float)
    _MODEL.passModel(lp)
    _MODEL.run()
    if _MODEL.getModelStatus() != highspy.HighsModelStatus.kOptimal:
        return None
    sol = _MODEL.getSolution()
    return np.array(sol.col_value), np.array(sol.row_dual)
