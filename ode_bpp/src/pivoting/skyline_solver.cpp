// Alg. 2 (BppDown), Alg. 2 + 3 (BppSky) and ours (Bpp): L_FF from one factor L0 of Ap per shift.
//
// Index space: the permuted space of Ap throughout. L_ is the working factor; it equals L0_ on
// columns < dirty_from_, which is what lets a step copy only L0's tail (row deletion at i writes
// columns first_column_holding(i) .. n-1, linalg/row_delete.h).
#include <algorithm>
#include <limits>

#include "linalg/cost_model.h"
#include "linalg/factor_error.h"
#include "linalg/row_delete.h"
#include "linalg/skyline.h"
#include "linalg/skyline_cholesky.h"
#include "linalg/skyline_solve.h"
#include "pivoting/step_cost.h"
#include "pivoting/strategies.h"

namespace ode_bpp::pivoting {

namespace {

using linalg::SkylineMatrix;
using linalg::SkylineShape;

SkylineShape shape_for(const SymmetricRows& A, SkylineVariant variant) {
    return variant == SkylineVariant::DenseDelete ? SkylineShape::dense(A.n())
                                                  : SkylineShape::from_row_profile(A.row_profile());
}

class SkylineSolver final : public FreeSolver {
public:
    SkylineSolver(const SymmetricRows& A, SkylineVariant variant)
        : A_(A), variant_(variant), shape_(shape_for(A, variant)), cost_(shape_) {}

    /// Alg. 2 line 2: L0 L0^T = Ap + shift I inside the envelope.
    bool prepare(double shift) override {
        load_matrix(shift);
        L0_ = A_env_;
        if (linalg::skyline_cholesky(L0_, 0, {}) >= 0) return false;
        L_ = L0_;
        dirty_from_ = shape_.n;
        return true;
    }

    FactorOutcome solve_free(const std::vector<char>& tight, std::vector<double>& x, bool fresh) override {
        collect_tight(tight);
        for (int i : tight_rows_) x[i] = 0;
        if (tight_rows_.empty()) {  // L_FF = L0 itself, a fresh factor
            linalg::skyline_solve(L0_, x.data());
            return FactorOutcome::Refactored;
        }
        FactorOutcome outcome = fresh || prefers_refactor() ? refactor_tail(tight) : delete_rows();
        // A refactor the cost model chose may meet a pivot that deletion (a rank-1 update,
        // which only adds) never would: delete instead. Only the accuracy retry reports it.
        if (outcome == FactorOutcome::Breakdown && !fresh) outcome = delete_rows();
        if (outcome == FactorOutcome::Breakdown) return outcome;
        linalg::skyline_solve(L_, x.data());
        return outcome;
    }

    /// Table 4: L0 with every tight row deleted against a fresh factor of A_FF.
    double factor_error(const std::vector<char>& tight) const override {
        SkylineMatrix deleted = L0_;
        std::vector<double> work;
        for (int i = 0; i < shape_.n; ++i)
            if (tight[i]) linalg::skyline_delete_row(deleted, i, work);
        SkylineMatrix fresh = A_env_;
        if (linalg::skyline_cholesky(fresh, 0, tight) >= 0) return std::numeric_limits<double>::quiet_NaN();
        return linalg::factor_error(deleted, fresh, tight);
    }

private:
    /// A_env_ = Ap + shift I in the skyline shape (entries outside Ap's pattern stay 0).
    void load_matrix(double shift) {
        A_env_ = SkylineMatrix(shape_);
        for (int i = 0; i < A_.n(); ++i) {
            A_env_.at(i, i) = A_.diag(i) + shift;
            for (int k = A_.row_begin(i); k < A_.row_end(i); ++k)
                if (A_.col(k) < i) A_env_.at(i, A_.col(k)) = A_.val(k);
        }
    }

    void collect_tight(const std::vector<char>& tight) {
        tight_rows_.clear();
        for (int i = 0; i < shape_.n; ++i)
            if (tight[i]) tight_rows_.push_back(i);
    }

    /// First column this step writes: deleting (or zeroing) row k0 reaches back that far.
    int first_written_column() const { return shape_.first_column_holding(tight_rows_.front()); }

    /// Bpp's cost model: the cheaper of deleting |T| rows and refactoring from the first tight
    /// column (NOTES: deletion costs ~ |T| (m - i) height, refactoring ~ m height^2).
    bool prefers_refactor() const {
        if (variant_ != SkylineVariant::CostModel) return false;
        const int copy_from = std::min(dirty_from_, first_written_column());
        return refactor_price(cost_, tight_rows_, copy_from) < deletion_price(cost_, tight_rows_, copy_from);
    }

    /// Alg. 2 lines 7-11: L = L0 (BppDown: all of it; else from the first column that differs
    /// or will be written), then DOWNDATE for each i in T, ascending.
    FactorOutcome delete_rows() {
        const int written = first_written_column();
        const int copy_from = variant_ == SkylineVariant::DenseDelete ? 0 : std::min(dirty_from_, written);
        L_.copy_tail_from(L0_, copy_from);
        for (int i : tight_rows_) linalg::skyline_delete_row(L_, i, work_);
        dirty_from_ = written;
        return FactorOutcome::Deleted;
    }

    /// L's columns < k0 from L0 (the factor of the leading block is unchanged), columns >= k0
    /// from Ap, then Cholesky from k0 with the tight rows removed.
    FactorOutcome refactor_tail(const std::vector<char>& tight) {
        const int k0 = tight_rows_.front();
        const int written = first_written_column();
        const int copy_from = std::min(dirty_from_, written);
        copy_columns(L0_, copy_from, k0);
        L_.copy_tail_from(A_env_, k0);
        dirty_from_ = written;
        if (linalg::skyline_cholesky(L_, k0, tight) >= 0) return FactorOutcome::Breakdown;
        return FactorOutcome::Refactored;
    }

    /// Columns [from, to) of source into L_ (same shape; columns are stored contiguously).
    void copy_columns(const SkylineMatrix& source, int from, int to) {
        if (from >= to) return;
        const auto& colptr = shape_.colptr;
        std::copy(source.values().begin() + colptr[from], source.values().begin() + colptr[to],
                  L_.values().begin() + colptr[from]);
    }

    const SymmetricRows& A_;
    const SkylineVariant variant_;
    const SkylineShape shape_;
    const linalg::CostModel cost_;
    SkylineMatrix A_env_, L0_, L_;
    int dirty_from_ = 0;
    std::vector<int> tight_rows_;
    std::vector<double> work_;
};

}  // namespace

std::unique_ptr<FreeSolver> make_skyline_solver(const SymmetricRows& Ap, SkylineVariant variant) {
    return std::make_unique<SkylineSolver>(Ap, variant);
}

}  // namespace ode_bpp::pivoting
