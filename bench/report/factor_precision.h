// bench/report/factor_precision.h: how far bpp's downdated factor and a fresh factor of A_FF each
// are from the exact factor, the precision floor against which Table 4's factor error
// ‖L_deleted − chol(A_FF)‖_F is read (docs/benchmarks.md, "Table 4 at the precision floor").
#pragma once

#include <limits>
#include <vector>

#include "ode_bpp/io.h"
#include "ode_bpp/solver.h"

namespace ode_bpp::bench {

/// Distances from the exact factor of M, M = Ap with the tight rows and columns replaced by the
/// identity (Ap = P A Pᵀ in the given order; its factor is chol(A_FF) with identity rows, the
/// one Table 4 compares). The exact factor is taken in long double (64-bit mantissa, 2^11 times
/// double's precision).
struct FactorPrecision {
    /// ‖chol(M) − L_exact‖_F, chol(M) in double (Eigen's LLT): a fresh factorization's own error.
    double fresh = std::numeric_limits<double>::quiet_NaN();
    /// ‖L_deleted − L_exact‖_F: L0 = chol(Ap) in envelope storage (skyline_cholesky) with every
    /// tight row deleted in ascending order (skyline_delete_row), as Table 4's L_deleted.
    double deleted = std::numeric_limits<double>::quiet_NaN();
};

/// file: the problem, A n x n in original order. ordering: perm[new] = old, n entries (the
/// method's Result::ordering; the Frobenius norm of a factor's error depends on the order).
/// states: n entries, original order; T = the rows not Free. Both fields 0 when T is empty (no
/// deletion: L0 itself), both NaN when the sizes disagree or a factorization breaks down.
FactorPrecision factor_precision(const MlcpFile& file, const std::vector<int>& ordering,
                                 const std::vector<RowState>& states);

}  // namespace ode_bpp::bench
