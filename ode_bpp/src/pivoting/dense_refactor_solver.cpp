// Alg. 1 line 5: L_FF <- Cholesky(A_FF), gathered densely at every pivot step.
#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "pivoting/strategies.h"

namespace ode_bpp::pivoting {

namespace {

class DenseRefactorSolver final : public FreeSolver {
public:
    explicit DenseRefactorSolver(const SymmetricRows& Ap) : A_(Ap) {}

    bool prepare(double shift) override {
        shift_ = shift;
        return true;
    }

    FactorOutcome solve_free(const std::vector<char>& tight, std::vector<double>& x, bool) override {
        const int nf = gather_free(tight);
        for (int i = 0; i < A_.n(); ++i)
            if (tight[i]) x[i] = 0;
        if (nf == 0) return FactorOutcome::Refactored;
        llt_.compute(dense_);
        if (llt_.info() != Eigen::Success) return FactorOutcome::Breakdown;
        for (int k = 0; k < nf; ++k) {
            const double l = llt_.matrixLLT()(k, k);
            if (pivot_breaks_down(l * l, dense_(k, k))) return FactorOutcome::Breakdown;
        }
        for (int k = 0; k < nf; ++k) rhs_[k] = x[free_[k]];
        llt_.solveInPlace(rhs_);
        for (int k = 0; k < nf; ++k) x[free_[k]] = rhs_[k];
        return FactorOutcome::Refactored;
    }

    void solve_again(std::vector<double>& x) override {
        const int nf = static_cast<int>(free_.size());
        for (int k = 0; k < nf; ++k) rhs_[k] = x[free_[k]];
        for (int i = 0; i < A_.n(); ++i)
            if (position_[i] < 0) x[i] = 0;
        if (nf == 0) return;
        llt_.solveInPlace(rhs_);
        for (int k = 0; k < nf; ++k) x[free_[k]] = rhs_[k];
    }

private:
    /// A_FF (+ shift I) into dense_, free rows in increasing permuted order; returns |F|.
    int gather_free(const std::vector<char>& tight) {
        const int n = A_.n();
        free_.clear();
        position_.assign(static_cast<std::size_t>(n), -1);
        for (int i = 0; i < n; ++i)
            if (!tight[i]) {
                position_[i] = static_cast<int>(free_.size());
                free_.push_back(i);
            }
        const int nf = static_cast<int>(free_.size());
        dense_.setZero(nf, nf);
        rhs_.resize(nf);
        for (int a = 0; a < nf; ++a) {
            const int i = free_[a];
            dense_(a, a) = A_.diag(i) + shift_;
            for (int k = A_.row_begin(i); k < A_.row_end(i); ++k) {
                const int b = position_[A_.col(k)];
                if (b >= 0) dense_(a, b) = A_.val(k);
            }
        }
        return nf;
    }

    const SymmetricRows& A_;
    double shift_ = 0;
    std::vector<int> free_, position_;
    Eigen::MatrixXd dense_;
    Eigen::VectorXd rhs_;
    Eigen::LLT<Eigen::MatrixXd> llt_;
};

}  // namespace

std::unique_ptr<FreeSolver> make_dense_refactor_solver(const SymmetricRows& Ap) {
    return std::make_unique<DenseRefactorSolver>(Ap);
}

}  // namespace ode_bpp::pivoting
