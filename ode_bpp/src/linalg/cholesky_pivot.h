// The breakdown test of every Cholesky factorization here that may meet a dependent column
// (dense_cholesky, incremental_cholesky, the pivoting layer's dense refactoring).
#pragma once

#include <limits>

namespace ode_bpp::linalg {

/// True when a Cholesky pivot d = L_kk^2 of a column whose diagonal entry was a_kk is not safely
/// positive: d <= eps * a_kk means column k is dependent on the earlier ones to machine
/// precision (or d is NaN), and the factor would amplify rounding by 1/eps.
inline bool pivot_breaks_down(double pivot_squared, double diagonal) {
    return !(pivot_squared > std::numeric_limits<double>::epsilon() * diagonal);
}

}  // namespace ode_bpp::linalg
