// The factor strategy behind the pivoting loop: how L_FF of Eq. 6 is obtained at each step.
// One implementation per Method (Alg. 1 dense refactoring, Alg. 2 deletion, Alg. 2 + 3 skyline,
// and ours with the cost model); the loop itself (pivot_loop.h) is written once.
#pragma once

#include <memory>
#include <vector>

#include "ode_bpp/solver.h"
#include "linalg/skyline.h"
#include "linalg/symmetric_rows.h"

namespace ode_bpp::pivoting {

/// How solve_free obtained L_FF.
enum class FactorOutcome {
    Deleted,     ///< copied from L0 with the tight rows deleted (Alg. 2 lines 7-11)
    Refactored,  ///< a (partial) Cholesky factorization of A_FF
    Breakdown,   ///< a Cholesky pivot was not safely positive: A_FF is not numerically SPD
};

/// The factor of a strategy's latest successful solve_free, where it keeps one on the envelope:
/// L of Ap + shift I in skyline storage whose entries on the free rows and columns are L_FF. Its
/// tight rows and columns are the identity (row_delete.h, skyline_cholesky.h's removed rows), or,
/// where T is every row from some k0 on, not factored at all (L0 through column k0): read only
/// the free ones.
struct EnvelopeFactor {
    const linalg::SkylineMatrix* L = nullptr;   ///< null: none kept
    const std::vector<int>* tight_rows = nullptr;  ///< T, ascending, permuted space
};

/// Everything in the permuted index space of the linalg::SymmetricRows the strategy was built on.
class FreeSolver {
public:
    virtual ~FreeSolver() = default;
    /// Readies L0 L0^T = Ap + shift I for this shift (Alg. 2 line 2). False on breakdown. A
    /// strategy may factor L0 only as far as its steps need it; a breakdown found later comes
    /// out of solve_free as FactorOutcome::Breakdown, which the loop treats alike.
    virtual bool prepare(double shift) = 0;
    /// Solves (Ap + shift I)_FF x_F = rhs_F with F = { i : tight[i] == 0 } (Eq. 6).
    /// x: n entries; in: rhs at free rows (tight entries ignored); out: x_F at free rows and 0 at
    /// tight rows. fresh: obtain L_FF by refactoring, never by deletion (the accuracy retry).
    virtual FactorOutcome solve_free(const std::vector<char>& tight, std::vector<double>& x, bool fresh) = 0;
    /// Solves (Ap + shift I)_FF x_F = rhs_F again, with the factor and the free set of the latest
    /// solve_free that succeeded (x as there: rhs in at free rows, x_F out, 0 at tight rows).
    /// O(envelope) per call: what extra right-hand sides at one index set cost.
    virtual void solve_again(std::vector<double>& x) = 0;
    /// Table 4: ||L_deleted - chol(A_FF)||_F at this tight set, or NaN where not meaningful.
    virtual double factor_error(const std::vector<char>& tight) const;
    /// The latest solve_free's factor, valid until the next call of prepare or solve_free; none
    /// after a breakdown, after prepare, and for the dense strategies.
    virtual EnvelopeFactor latest_factor() const { return {}; }
};

struct StrategyBuffers;  // strategies.h

/// The strategy of a BPP method (BppChol, BppDown, BppSky, Bpp) on Ap; null for other methods
/// or when the method's kernels are not available. buffers: where the strategy works, kept by
/// the caller; they must outlive the strategy.
std::unique_ptr<FreeSolver> make_free_solver(Method method, const linalg::SymmetricRows& Ap, StrategyBuffers& buffers);

}  // namespace ode_bpp::pivoting
