// Alg. 2 (BppDown), Alg. 2 + 3 (BppSky) and ours (Bpp): L_FF from one factor L0 of Ap per shift.
//
// Index space: the permuted space of Ap throughout. L_ is the working factor; it equals L0_
// except in columns >= dirty_from_ and, before that column, in the rows dirty_rows_: deleting
// (or removing) the tight rows T of a step rewrites columns >= min T and zeroes the rows of T
// (linalg/row_delete.h, skyline_cholesky's removed rows). So a step restores L0 by copying that
// tail and those rows (SkylineMatrix::copy_rows_from), not everything from the first column
// holding min T, which on wide envelopes is most of the matrix.
#include <algorithm>
#include <cassert>
#include <limits>
#include <optional>

#include "linalg/cost_model.h"
#include "linalg/factor_error.h"
#include "linalg/row_delete.h"
#include "linalg/skyline.h"
#include "linalg/skyline_cholesky.h"
#include "linalg/skyline_solve.h"
#include "linalg/step_cost.h"
#include "pivoting/kept_buffers_impl.h"
#include "pivoting/strategies.h"

namespace ode_bpp::pivoting {

namespace {

using linalg::SkylineMatrix;
using linalg::SkylineShape;

}  // namespace

struct SkylineStorage {
    /// What shape and cost were made for: the variant, and the row profile of Ap (its size for
    /// DenseDelete, whose shape depends on n only).
    std::optional<SkylineVariant> variant;
    std::vector<int> profile, new_profile;
    SkylineShape shape;
    std::optional<linalg::CostModel> cost;
    SkylineMatrix A_env, L0, L;
    std::vector<int> dirty_rows, tight_rows;
    std::vector<double> work;

    /// The shape and cost model of Ap's envelope: those already held when Ap's envelope is the
    /// one they were made for, else made afresh. O(nnz) for the check.
    void shape_for(const linalg::SymmetricRows& A, SkylineVariant v) {
        if (v == SkylineVariant::DenseDelete) new_profile.assign(1, A.n());
        else A.row_profile(new_profile);
        if (variant == v && new_profile == profile) return;
        variant = v;
        profile.swap(new_profile);
        shape = v == SkylineVariant::DenseDelete ? SkylineShape::dense(A.n()) : SkylineShape::from_row_profile(profile);
        cost.emplace(shape);
    }
};

template class KeptBuffers<SkylineStorage>;

namespace {

/// Storage prepared for A: its shape and cost model in place.
SkylineStorage& prepared(SkylineBuffers& buffers, const linalg::SymmetricRows& A, SkylineVariant variant) {
    buffers.contents().shape_for(A, variant);
    return buffers.contents();
}

class SkylineSolver final : public FreeSolver {
public:
    SkylineSolver(const linalg::SymmetricRows& A, SkylineVariant variant, SkylineStorage& storage)
        : A_(A), variant_(variant), shape_(storage.shape), cost_(*storage.cost), A_env_(storage.A_env), L0_(storage.L0),
          L_(storage.L), dirty_rows_(storage.dirty_rows), tight_rows_(storage.tight_rows), work_(storage.work) {}

    /// Alg. 2 line 2: L0 L0^T = Ap + shift I inside the envelope.
    bool prepare(double shift) override {
        load_matrix(shift);
        L0_ = A_env_;
        if (linalg::skyline_cholesky(L0_, 0, {}) >= 0) return false;
        L_ = L0_;
        dirty_from_ = shape_.n;
        dirty_rows_.clear();
        last_factor_ = nullptr;
        return true;
    }

    FactorOutcome solve_free(const std::vector<char>& tight, std::vector<double>& x, bool fresh) override {
        collect_tight(tight);
        for (int i : tight_rows_) x[i] = 0;
        if (tight_rows_.empty()) {  // L_FF = L0 itself, a fresh factor
            last_factor_ = &L0_;
            linalg::skyline_solve(L0_, x.data());
            return FactorOutcome::Refactored;
        }
        FactorOutcome outcome = fresh || prefers_refactor() ? refactor_tail(tight) : delete_rows();
        // A refactor the cost model chose may meet a pivot that deletion (a rank-1 update,
        // which only adds) never would: delete instead. Only the accuracy retry reports it.
        if (outcome == FactorOutcome::Breakdown && !fresh) outcome = delete_rows();
        if (outcome == FactorOutcome::Breakdown) {
            last_factor_ = nullptr;
            return outcome;
        }
        last_factor_ = &L_;
        linalg::skyline_solve(L_, x.data());
        return outcome;
    }

    void solve_again(std::vector<double>& x) override {
        for (int i : tight_rows_) x[i] = 0;
        if (last_factor_ != nullptr) linalg::skyline_solve(*last_factor_, x.data());
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
        A_env_.reset(shape_);
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

    /// First column of L_ that this step needs restored to L0: min(dirty_from_, min T).
    int restore_from() const { return std::min(dirty_from_, tight_rows_.front()); }

    /// Bpp's cost model: the cheaper of deleting |T| rows and refactoring from the first tight
    /// column (docs/maths.md: deletion costs ~ |T| (m - i) height, refactoring ~ m height^2).
    bool prefers_refactor() const {
        if (variant_ != SkylineVariant::CostModel) return false;
        return linalg::refactor_price(cost_, tight_rows_, restore_from()) < linalg::deletion_price(cost_, tight_rows_, restore_from());
    }

    /// Alg. 2 lines 7-11: L = L0 (BppDown: all of it, as the paper copies; else only the tail
    /// and the rows that differ), then DOWNDATE for each i in T, ascending.
    FactorOutcome delete_rows() {
        if (variant_ == SkylineVariant::DenseDelete) {
            L_.copy_tail_from(L0_, 0);
        } else {
            const int from = restore_from();
            L_.copy_tail_from(L0_, from);
            L_.copy_rows_from(L0_, dirty_rows_, from);
        }
        assert(equal_in_envelope(L_, L0_));  // brute-force check of the restore (debug builds)
        for (int i : tight_rows_) linalg::skyline_delete_row(L_, i, work_);
        mark_dirty();
        return FactorOutcome::Deleted;
    }

    /// L's columns < k0 = min T from L0 (the factor of the leading block is unchanged), columns
    /// >= k0 from Ap, then Cholesky from k0 with the tight rows removed.
    FactorOutcome refactor_tail(const std::vector<char>& tight) {
        const int k0 = tight_rows_.front();
        const int from = restore_from();
        copy_columns(L0_, from, k0);
        L_.copy_rows_from(L0_, dirty_rows_, from);
        L_.copy_tail_from(A_env_, k0);
        mark_dirty();
        if (linalg::skyline_cholesky(L_, k0, tight) >= 0) return FactorOutcome::Breakdown;
        return FactorOutcome::Refactored;
    }

#ifndef NDEBUG
    static bool equal_in_envelope(const SkylineMatrix& a, const SkylineMatrix& b) {
        for (int k = 0; k < a.n(); ++k)
            for (int r = k; r <= a.sky(k); ++r)
                if (!(a.at(r, k) == b.at(r, k))) return false;
        return true;
    }
#endif

    void mark_dirty() {
        dirty_from_ = tight_rows_.front();
        dirty_rows_ = tight_rows_;
    }

    /// Columns [from, to) of source into L_ (same shape; columns are stored contiguously).
    void copy_columns(const SkylineMatrix& source, int from, int to) {
        if (from >= to) return;
        const auto& colptr = shape_.colptr;
        std::copy(source.values().begin() + colptr[from], source.values().begin() + colptr[to],
                  L_.values().begin() + colptr[from]);
    }

    const linalg::SymmetricRows& A_;
    const SkylineVariant variant_;
    // in the caller's SkylineBuffers
    const SkylineShape& shape_;
    const linalg::CostModel& cost_;
    SkylineMatrix &A_env_, &L0_, &L_;
    int dirty_from_ = 0;
    std::vector<int>& dirty_rows_;  ///< rows of L_ that differ from L0_ before dirty_from_
    const SkylineMatrix* last_factor_ = nullptr;  ///< L_FF of the latest successful solve_free
    std::vector<int>& tight_rows_;
    std::vector<double>& work_;
};

}  // namespace

std::unique_ptr<FreeSolver> make_skyline_solver(const linalg::SymmetricRows& Ap, SkylineVariant variant,
                                                SkylineBuffers& buffers) {
    return std::make_unique<SkylineSolver>(Ap, variant, prepared(buffers, Ap, variant));
}

}  // namespace ode_bpp::pivoting
