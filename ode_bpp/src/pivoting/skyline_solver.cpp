// Alg. 2 (BppDown), Alg. 2 + 3 (BppSky) and ours (Bpp): L_FF from one factor L0 of Ap per shift.
//
// Index space: the permuted space of Ap throughout. L is the working factor; it equals L0
// except in columns >= dirty_from_ and, before that column, in the rows dirty_rows: deleting
// (or removing) the tight rows T of a step rewrites columns >= min T and zeroes the rows of T
// (linalg/row_delete.h, skyline_cholesky's removed rows). So a step restores L0 by copying that
// tail and those rows (SkylineMatrix::copy_rows_from), not everything from the first column
// holding min T, which on wide envelopes is most of the matrix. Right after a factorization L
// holds nothing yet; the first step that needs it copies all of L0 (a step with no tight row
// solves with L0 and copies nothing).
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
    SkylineMatrix A_env, L0, L;  ///< A_env: Ap + shift I, loaded only where L0 no longer holds it
    std::vector<int> dirty_rows;  ///< rows of L that differ from L0 before SkylineSolver::dirty_from_
    bool needed_a_env = false;    ///< the latest prepare refactored from a column L0 had factored
    std::vector<int> tight_rows;
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
        : A_(A), variant_(variant), s_(storage) {}

    /// Alg. 2 line 2: L0 L0^T = Ap + shift I inside the envelope. Alg. 2 and 3 (BppDown, BppSky)
    /// delete at every step and need all of L0 at once. Bpp factors it lazily, as many leading
    /// columns as its steps need (l0_columns_): a refactoring from column k0 reads L0's columns
    /// < k0 alone, and only a deletion, a step with no tight row and Table 4 need all of L0.
    /// Where every step refactors (most warm steps), L0's columns from the largest k0 on are
    /// never factored, and a breakdown in them shows where a step needs the column (solve_free's
    /// Breakdown) or not at all.
    bool prepare(double shift) override {
        shift_ = shift;
        load_l0();
        l0_columns_ = 0;
        l0_broken_ = false;
        if (variant_ != SkylineVariant::CostModel && !factor_l0_through(s_.shape.n)) return false;
        // L is not copied from L0 here (l_unset_): the first step that needs L restores all of
        // it, and a step with no tight row, which solves with L0 itself, copies nothing
        s_.L.reshape(s_.shape);
        l_unset_ = true;
        dirty_from_ = s_.shape.n;
        s_.dirty_rows.clear();
        last_factor_ = nullptr;
        return true;
    }

    FactorOutcome solve_free(const std::vector<char>& tight, std::vector<double>& x, bool fresh) override {
        collect_tight(tight);
        for (int i : s_.tight_rows) x[i] = 0;
        if (s_.tight_rows.empty()) {  // L_FF = L0 itself, a fresh factor
            if (!factor_l0_through(s_.shape.n)) return breakdown();
            return solve_with_l0(s_.shape.n, x);
        }
        // T = {k0 .. n-1} (Frozen friction's first solve with the friction rows ordered last): L_FF
        // is L0's leading block, factored through k0 alone, and nothing is copied
        if (variant_ == SkylineVariant::CostModel && tight_is_the_tail()) {
            if (!factor_l0_through(s_.tight_rows.front())) return breakdown();
            return solve_with_l0(s_.tight_rows.front(), x);
        }
        FactorOutcome outcome = fresh || prefers_refactor() ? refactor_tail(tight) : delete_rows();
        // A refactor the cost model chose may meet a pivot that deletion (a rank-1 update,
        // which only adds) never would: delete instead. Only the accuracy retry reports it.
        if (outcome == FactorOutcome::Breakdown && !fresh) outcome = delete_rows();
        if (outcome == FactorOutcome::Breakdown) return breakdown();
        last_factor_ = &s_.L;
        last_rows_ = s_.shape.n;
        linalg::skyline_solve(s_.L, x.data());
        return outcome;
    }

    void solve_again(std::vector<double>& x) override {
        for (int i : s_.tight_rows) x[i] = 0;
        if (last_factor_ != nullptr) linalg::skyline_solve_leading(*last_factor_, last_rows_, x.data());
    }

    EnvelopeFactor latest_factor() const override {
        if (last_factor_ == nullptr) return {};
        return {last_factor_, &s_.tight_rows};
    }

    /// Table 4: L0 with every tight row deleted against a fresh factor of A_FF.
    double factor_error(const std::vector<char>& tight) const override {
        if (l0_broken_) return std::numeric_limits<double>::quiet_NaN();
        SkylineMatrix deleted = s_.L0;
        if (linalg::skyline_cholesky(deleted, l0_columns_, {}) >= 0) return std::numeric_limits<double>::quiet_NaN();
        std::vector<double> work;
        for (int i = 0; i < s_.shape.n; ++i)
            if (tight[i]) linalg::skyline_delete_row(deleted, i, work);
        SkylineMatrix fresh(s_.shape);
        load_columns(fresh, 0);
        if (linalg::skyline_cholesky(fresh, 0, tight) >= 0) return std::numeric_limits<double>::quiet_NaN();
        return linalg::factor_error(deleted, fresh, tight);
    }

private:
    /// Columns k0 .. n-1 of M (shape s_.shape) = those of Ap + shift_ I, entries outside Ap's
    /// pattern 0. Column k of the lower triangle is row k of Ap from its diagonal on (A_ stores
    /// both triangles), so each column is written in one contiguous pass. L0 is loaded so, not
    /// copied from a loaded A_env: a warm step that deletes rows, or none, never reads A_env.
    void load_columns(SkylineMatrix& M, int k0) const {
        if (k0 >= A_.n()) return;
        std::fill(M.column(k0), M.values().data() + s_.shape.size(), 0.0);
        for (int k = k0; k < A_.n(); ++k) {
            double* column = M.column(k);
            column[0] = A_.diag(k) + shift_;
            for (int e = A_.row_begin(k); e < A_.row_end(k); ++e)
                if (A_.col(e) > k) column[A_.col(e) - k] = A_.val(e);
        }
    }

    /// L_FF = L0's leading k1 x k1 block, factored: x_F from it (x's tight rows are 0 already).
    FactorOutcome solve_with_l0(int k1, std::vector<double>& x) {
        last_factor_ = &s_.L0;
        last_rows_ = k1;
        linalg::skyline_solve_leading(s_.L0, k1, x.data());
        return FactorOutcome::Refactored;
    }

    /// T is every row from its first on (s_.tight_rows ascending, distinct, non-empty).
    bool tight_is_the_tail() const {
        return static_cast<int>(s_.tight_rows.size()) == s_.shape.n - s_.tight_rows.front();
    }

    void collect_tight(const std::vector<char>& tight) {
        s_.tight_rows.clear();
        for (int i = 0; i < s_.shape.n; ++i)
            if (tight[i]) s_.tight_rows.push_back(i);
    }

    /// First column of s_.L that this step needs restored to L0: min(dirty_from_, min T). The
    /// cost model prices that restore (as if prepare had copied L0 into L).
    int restore_from() const { return std::min(dirty_from_, s_.tight_rows.front()); }
    /// The same for the copy itself: column 0 while L holds nothing yet.
    int copy_from() const { return l_unset_ ? 0 : restore_from(); }

    /// Bpp's cost model: the cheaper of deleting |T| rows and refactoring from the first tight
    /// column (docs/maths.md: deletion costs ~ |T| (m - i) height, refactoring ~ m height^2).
    bool prefers_refactor() const {
        if (variant_ != SkylineVariant::CostModel) return false;
        const double deletion = linalg::deletion_price(*s_.cost, s_.tight_rows, restore_from());
        // The refactor's price with nothing skipped bounds the exact one (O(n)) from above, and
        // both are sums of quarter-integers, exact in doubles: below the deletion's, it decides
        // alike at O(1) (on the crane most refactors win by that margin).
        const double unskipped = linalg::kCopyUnit * s_.cost->copy_cost(restore_from()) +
                                 linalg::kRefactorUnit * s_.cost->refactor_cost(s_.tight_rows.front());
        if (unskipped < deletion) return true;
        return linalg::refactor_price(*s_.cost, s_.tight_rows, restore_from()) < deletion;
    }

    /// Alg. 2 lines 7-11: L = L0 (BppDown: all of it, as the paper copies; else only the tail
    /// and the rows that differ), then DOWNDATE for each i in T, ascending.
    FactorOutcome delete_rows() {
        if (!factor_l0_through(s_.shape.n)) return FactorOutcome::Breakdown;
        if (variant_ == SkylineVariant::DenseDelete) {
            s_.L.copy_tail_from(s_.L0, 0);
        } else {
            const int from = copy_from();
            s_.L.copy_tail_from(s_.L0, from);
            s_.L.copy_rows_from(s_.L0, s_.dirty_rows, from);
        }
        assert(equal_in_envelope(s_.L, s_.L0));  // brute-force check of the restore (debug builds)
        for (int i : s_.tight_rows) linalg::skyline_delete_row(s_.L, i, s_.work);
        mark_dirty();
        return FactorOutcome::Deleted;
    }

    /// L's columns < k0 = min T from L0 (the factor of the leading block is unchanged), columns
    /// >= k0 loaded from Ap, then Cholesky from k0 with the tight rows removed.
    FactorOutcome refactor_tail(const std::vector<char>& tight) {
        const int k0 = s_.tight_rows.front();
        if (!factor_l0_through(k0)) return FactorOutcome::Breakdown;
        const int from = copy_from();
        copy_columns(s_.L0, from, k0);
        s_.L.copy_rows_from(s_.L0, s_.dirty_rows, from);
        restore_tail_of_ap(k0);
        mark_dirty();
        if (linalg::skyline_cholesky(s_.L, k0, tight) >= 0) return FactorOutcome::Breakdown;
        return FactorOutcome::Refactored;
    }

    /// L's columns >= k0 = Ap + shift_ I. L0 is factored lazily, and its columns from
    /// l0_columns_ on still hold Ap + shift_ I: a refactorization from there (the usual one, right
    /// after factor_l0_through(k0)) copies them; one from an earlier column, after a step that
    /// needed more of L0, copies them from A_env, loaded at the first such need. (Where L0 broke
    /// down, its column l0_columns_ holds partial values; a refactorization from it has k0 = min T
    /// there, which skyline_cholesky makes an identity column before reading anything of it.)
    void restore_tail_of_ap(int k0) {
        if (k0 >= l0_columns_) {
            s_.L.copy_tail_from(s_.L0, k0);
            return;
        }
        if (!a_env_loaded_) load_a_env();
        s_.needed_a_env = true;
        s_.L.copy_tail_from(s_.A_env, k0);
    }

    /// L0 = Ap + shift_ I, unfactored. Loaded straight from Ap, unless the previous prepare of
    /// these buffers (as a rule the same island one step earlier) came to need A_env: then A_env
    /// is loaded and L0 copied from it, a copy costing less than a second load.
    void load_l0() {
        s_.L0.reshape(s_.shape);
        // A_env's storage grows to this shape's now, loaded or not: the memory follows the
        // largest envelope met, not the first step that happens to need A_env (a long run's
        // resident memory then stops growing once its largest island has been met: make soak).
        // Only the values: the shape itself is copied by load_a_env, where A_env is used.
        std::vector<double>& a_env = s_.A_env.values();
        if (a_env.size() < static_cast<std::size_t>(s_.shape.size())) a_env.resize(static_cast<std::size_t>(s_.shape.size()));
        const bool a_env_wanted = s_.needed_a_env;
        s_.needed_a_env = false;
        a_env_loaded_ = false;
        if (!a_env_wanted) {
            load_columns(s_.L0, 0);
            return;
        }
        load_a_env();
        s_.L0.copy_tail_from(s_.A_env, 0);
    }

    /// s_.A_env = Ap + shift_ I in the shape of this prepare.
    void load_a_env() {
        s_.A_env.reshape(s_.shape);
        load_columns(s_.A_env, 0);
        a_env_loaded_ = true;
    }

#ifndef NDEBUG
    static bool equal_in_envelope(const SkylineMatrix& a, const SkylineMatrix& b) {
        for (int k = 0; k < a.n(); ++k)
            for (int r = k; r <= a.sky(k); ++r)
                if (!(a.at(r, k) == b.at(r, k))) return false;
        return true;
    }
#endif

    /// L0's columns < k1 factored (skyline_cholesky's partial form: the same values as one whole
    /// factorization). False when one of them breaks down: Ap + shift I is not numerically SPD.
    /// The columns before the failing one stay usable; from it on L0 holds partly factored
    /// values, so every later call that needs it fails too, without factoring them again.
    bool factor_l0_through(int k1) {
        if (k1 <= l0_columns_) return true;
        if (l0_broken_) return false;
        const int failed = linalg::skyline_cholesky(s_.L0, l0_columns_, k1, {});
        l0_broken_ = failed >= 0;
        l0_columns_ = l0_broken_ ? failed : k1;
        return !l0_broken_;
    }

    FactorOutcome breakdown() {
        last_factor_ = nullptr;
        return FactorOutcome::Breakdown;
    }

    void mark_dirty() {
        l_unset_ = false;
        dirty_from_ = s_.tight_rows.front();
        s_.dirty_rows = s_.tight_rows;
    }

    /// Columns [from, to) of source into s_.L (same shape; columns are stored contiguously).
    void copy_columns(const SkylineMatrix& source, int from, int to) {
        if (from >= to) return;
        const auto& colptr = s_.shape.colptr;
        std::copy(source.values().begin() + colptr[from], source.values().begin() + colptr[to],
                  s_.L.values().begin() + colptr[from]);
    }

    const linalg::SymmetricRows& A_;
    const SkylineVariant variant_;
    // in the caller's SkylineBuffers
    /// The buffers: shape, cost model, A's envelope, L0, the working factor L and scratch.
    SkylineStorage& s_;
    int dirty_from_ = 0;
    double shift_ = 0;      ///< of the latest prepare: L0 and every refactored tail factor Ap + shift_ I
    bool a_env_loaded_ = false;  ///< s_.A_env holds Ap + shift_ I (restore_tail_of_ap)
    int l0_columns_ = 0;    ///< L0's columns factored so far (prepare: none; factor_l0_through)
    bool l0_broken_ = false;  ///< L0's column l0_columns_ broke down (factor_l0_through)
    bool l_unset_ = false;  ///< L holds no values since prepare (copy_from)
    const SkylineMatrix* last_factor_ = nullptr;  ///< L_FF of the latest successful solve_free
    int last_rows_ = 0;  ///< its leading rows that hold L_FF (the rest: tight rows, not factored in L0)
};

}  // namespace

std::unique_ptr<FreeSolver> make_skyline_solver(const linalg::SymmetricRows& Ap, SkylineVariant variant,
                                                SkylineBuffers& buffers) {
    return std::make_unique<SkylineSolver>(Ap, variant, prepared(buffers, Ap, variant));
}

}  // namespace ode_bpp::pivoting
