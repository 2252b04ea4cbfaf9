// Alg. 1 line 5: L_FF <- Cholesky(A_FF), gathered densely at every pivot step.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "pivoting/strategies.h"

namespace ode_bpp::pivoting {

namespace {

/// Buffers kept per thread so that their capacity outlives one solve (allocation dominated small
/// islands). One solver object per thread at a time: the driver makes one per solve.
struct DenseWorkspace {
    std::vector<double> store, rhs, diagonal;
    std::vector<int> free, position;
};

[[gnu::noinline]] DenseWorkspace& sized_workspace(int n) {
    thread_local DenseWorkspace workspace;
    DenseWorkspace& w = workspace;
    w.store.resize(static_cast<std::size_t>(n) * n);
    w.rhs.resize(static_cast<std::size_t>(n));
    w.diagonal.resize(static_cast<std::size_t>(n));
    w.position.assign(static_cast<std::size_t>(n), -1);
    w.free.clear();
    return w;
}

class DenseRefactorSolver final : public FreeSolver {
public:
    /// Every buffer is sized for |F| = n once: a solve allocates nothing per pivot step.
    explicit DenseRefactorSolver(const linalg::SymmetricRows& Ap)
        : A_(Ap), ws_(sized_workspace(Ap.n())), store_(ws_.store.data(), Ap.n(), Ap.n()), rhs_(ws_.rhs.data(), Ap.n()) {}

    bool prepare(double shift) override {
        shift_ = shift;
        return true;
    }

    FactorOutcome solve_free(const std::vector<char>& tight, std::vector<double>& x, bool) override {
        llt_.reset();
        const int nf = gather_free(tight);
        for (int i = 0; i < A_.n(); ++i)
            if (tight[i]) x[i] = 0;
        if (nf == 0) return FactorOutcome::Refactored;
        for (int k = 0; k < nf; ++k) diagonal_[k] = store_(k, k);
        Block leading = store_.topLeftCorner(nf, nf);
        llt_.emplace(leading);  // L_FF L_FF^T = A_FF, in place in store_'s leading block
        if (llt_->info() != Eigen::Success) return breakdown();
        for (int k = 0; k < nf; ++k) {
            const double l = store_(k, k);
            if (pivot_breaks_down(l * l, diagonal_[k])) return breakdown();
        }
        solve_in_place(x);
        return FactorOutcome::Refactored;
    }

    void solve_again(std::vector<double>& x) override {
        for (int i = 0; i < A_.n(); ++i)
            if (position_[i] < 0) x[i] = 0;
        if (llt_) solve_in_place(x);
    }

private:
    using Block = Eigen::Ref<Eigen::MatrixXd>;

    FactorOutcome breakdown() {
        llt_.reset();
        return FactorOutcome::Breakdown;
    }

    /// x_F <- L_FF^-T L_FF^-1 x_F.
    void solve_in_place(std::vector<double>& x) {
        const int nf = static_cast<int>(free_.size());
        auto rhs = rhs_.head(nf);
        for (int k = 0; k < nf; ++k) rhs[k] = x[free_[k]];
        llt_->solveInPlace(rhs);
        for (int k = 0; k < nf; ++k) x[free_[k]] = rhs[k];
    }

    /// A_FF (+ shift I) into store_'s leading |F| x |F| block (lower triangle: all LLT reads),
    /// free rows in increasing permuted order; returns |F|.
    int gather_free(const std::vector<char>& tight) {
        const int n = A_.n();
        free_.clear();
        for (int i = 0; i < n; ++i) {
            position_[i] = tight[i] ? -1 : static_cast<int>(free_.size());
            if (!tight[i]) free_.push_back(i);
        }
        const int nf = static_cast<int>(free_.size());
        store_.topLeftCorner(nf, nf).triangularView<Eigen::Lower>().setZero();
        for (int a = 0; a < nf; ++a) {
            const int i = free_[a];
            store_(a, a) = A_.diag(i) + shift_;
            for (int k = A_.row_begin(i); k < A_.row_end(i); ++k) {
                const int b = position_[A_.col(k)];
                if (b >= 0 && b < a) store_(a, b) = A_.val(k);
            }
        }
        return nf;
    }

    const linalg::SymmetricRows& A_;
    double shift_ = 0;
    DenseWorkspace& ws_;
    Eigen::Map<Eigen::MatrixXd> store_;  ///< n x n; the leading |F| x |F| block holds A_FF, then L_FF
    Eigen::Map<Eigen::VectorXd> rhs_;
    std::vector<double>& diagonal_ = ws_.diagonal;  ///< A_FF's diagonal before factoring (the breakdown test)
    std::vector<int>&free_ = ws_.free, &position_ = ws_.position;
    std::optional<Eigen::LLT<Block>> llt_;  ///< the latest successful factor (views store_)
};

}  // namespace

std::unique_ptr<FreeSolver> make_dense_refactor_solver(const linalg::SymmetricRows& Ap) {
    return std::make_unique<DenseRefactorSolver>(Ap);
}

}  // namespace ode_bpp::pivoting
