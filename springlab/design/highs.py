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
    programme is infeasible or the solver stops short of an optimum.

    The programme goes to HiGHS as arrays in one call (``passModel``'s array form): filling a
    ``HighsLp`` field by field cost 2-4 ms a programme of a few hundred rows, more than solving it."""
    import highspy
    from scipy.sparse import csc_matrix, issparse

    global _MODEL
    if _MODEL is None:
        _MODEL = new_model()
    if issparse(A):
        A = csc_matrix(A)
        n_row, n_col = A.shape
        start, index, value = A.indptr, A.indices, A.data
    else:  # column by column, the zeros left out, as csc_matrix would (without its coordinate pass)
        columns = np.asarray(A, dtype=float).T
        n_row, n_col = columns.shape[1], columns.shape[0]
        nonzero = columns != 0
        start = np.concatenate([[0], np.cumsum(np.count_nonzero(nonzero, axis=1))])
        index, value = np.nonzero(nonzero)[1], columns[nonzero]

    def bounds(values, sign):
        values = np.asarray(values, dtype=float)
        return np.where(np.isinf(values), sign * highspy.kHighsInf, values)

    _MODEL.passModel(n_col, n_row, len(value), int(highspy.MatrixFormat.kColwise), int(highspy.ObjSense.kMinimize), 0.0,
                     np.asarray(cost, dtype=float), bounds(col_lower, -1), bounds(col_upper, 1), bounds(row_lower, -1),
                     bounds(row_upper, 1), np.asarray(start, dtype=np.int32), np.asarray(index, dtype=np.int32),
                     np.asarray(value, dtype=float), np.zeros(n_col, dtype=np.int32))  # every column continuous
    _MODEL.run()
    if _MODEL.getModelStatus() != highspy.HighsModelStatus.kOptimal:
        return None
    sol = _MODEL.getSolution()
    return np.array(sol.col_value), np.array(sol.row_dual)
