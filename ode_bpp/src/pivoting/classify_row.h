// Eq. 4 for one row, with the per-row tolerances every pivoting loop uses (pivot_loop.cpp and
// small_island.cpp classify alike, so that both accept the same answers).
#pragma once

#include <limits>
#include <vector>

#include "ode_bpp/solver.h"

namespace ode_bpp::pivoting {

/// Where Eq. 4 moves one row, and by how much it breaks its condition (in units of w).
struct RowVerdict {
    RowState to;           ///< the row's next state (its current one when it is feasible)
    double excess = 0;     ///< (lo - x) A_ii, (x - hi) A_ii, -w or w for an infeasible row
};

/// Row i in state s at x_i with w_i = (A x - b)_i and bounds [lo, hi]: a free row outside its
/// bounds by more than the x-tolerance goes to that bound; a tight row whose w has the wrong sign
/// beyond the w-tolerance goes free. The w-tolerance is tol * scale (scale = (|A||x| + |b|)_i,
/// never an absolute constant) and the x-tolerance the same divided by the diagonal diag (A_ii x_i
/// is bounded by the same sum). A row pinned at lo = hi is never infeasible.
inline RowVerdict classify_row(RowState s, double x, double w, double lo, double hi, double diag, double scale,
                               double tol) {
    if (lo == hi) return {s};
    const double w_tol = tol * scale;
    switch (s) {
        case RowState::Free: {
            const double x_tol = w_tol / diag;
            if (x < lo - x_tol) return {RowState::AtLo, (lo - x) * diag};
            if (x > hi + x_tol) return {RowState::AtHi, (x - hi) * diag};
            break;
        }
        case RowState::AtLo:
            if (w < -w_tol) return {RowState::Free, -w};
            break;
        case RowState::AtHi:
            if (w > w_tol) return {RowState::Free, w};
            break;
    }
    return {s};
}

/// Infeasible rows of one iterate and their total violation (in units of w, for tie-breaks).
struct Infeasibility {
    std::vector<int> rows;            ///< ascending index, in the caller's index space
    std::vector<RowState> flip_to;    ///< the state Eq. 4 moves each of them to
    std::vector<double> excess;       ///< how far each breaks its condition (RowVerdict::excess)
    double violation = 0;
    int count() const { return static_cast<int>(rows.size()); }
    void clear() {
        rows.clear();
        flip_to.clear();
        excess.clear();
        violation = 0;
    }
};

/// Eq. 4 over rows 0 .. n-1 (classify_row each), into inf. diag(i): A_ii (+ shift). Every
/// vector has n entries in one index space, the caller's (the permuted space of the pivoting
/// loops, the original one on the small-island path). always_inline: the small-island path calls
/// it from its plain steps and its active set, and GCC's -O2 then kept it out of line, which cost
/// its islands of a few rows 1 % of their solve.
template <typename Diagonal>
[[gnu::always_inline]] inline void classify_rows(int n, const std::vector<RowState>& states, const std::vector<double>& x, const std::vector<double>& w,
                   const std::vector<double>& lo, const std::vector<double>& hi, Diagonal diag,
                   const std::vector<double>& scale, double tol, Infeasibility& inf) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    inf.clear();
    for (int i = 0; i < n; ++i) {
        // a free row without bounds (ODE's joint rows) meets Eq. 4 whatever x and w are
        if (states[i] == RowState::Free && lo[i] == -kInf && hi[i] == kInf) continue;
        const RowVerdict v = classify_row(states[i], x[i], w[i], lo[i], hi[i], diag(i), scale[i], tol);
        if (v.to == states[i]) continue;
        inf.rows.push_back(i);
        inf.flip_to.push_back(v.to);
        inf.excess.push_back(v.excess);
        inf.violation += v.excess;
    }
}

/// The multiplier of a tight row with the wrong sign (w > 0 at hi, w < 0 at lo), else 0: what
/// the polish of a converged index set frees beyond the factor's accuracy (pivot_loop.cpp).
inline double wrong_sign(RowState s, double w) {
    return s == RowState::AtHi ? w : s == RowState::AtLo ? -w : 0.0;
}

}  // namespace ode_bpp::pivoting
