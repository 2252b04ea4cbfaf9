// Alg. 1 line 5: L_FF <- Cholesky(A_FF), gathered densely at every pivot step.
#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <algorithm>
#include <vector>

#include "linalg/cholesky_pivot.h"
#include "linalg/dense_cholesky.h"

#include "pivoting/kept_buffers_impl.h"
#include "pivoting/strategies.h"

namespace ode_bpp::pivoting {

namespace {

/// Up to this |F| the factor is linalg::dense_cholesky's plain loops, beyond it Eigen's blocked
/// LLT: on 6-row islands the LLT's set-up per call cost more than its flops (callgrind, ODE's
/// demo_motors), while on hundreds of rows (Alg. 1 in the paper's comparison) blocking wins.
constexpr int kPlainLoopsUpTo = 32;

/// Buffers kept by the caller (DenseRefactorBuffers) so that their capacity outlives one solve
/// (allocation dominated small islands). One solver object per buffers at a time.
struct DenseWorkspace {
    std::vector<double> store, rhs, diagonal, inverse_diagonal;  ///< inverse_diagonal: 1 / L(k,k)
    std::vector<int> free, position;
};

DenseWorkspace& sized_workspace(DenseWorkspace& w, int n) {
    w.store.resize(static_cast<std::size_t>(n) * n);
    w.rhs.resize(static_cast<std::size_t>(n));
    w.diagonal.resize(static_cast<std::size_t>(n));
    w.inverse_diagonal.resize(static_cast<std::size_t>(n));
    w.position.assign(static_cast<std::size_t>(n), -1);
    w.free.clear();
    return w;
}

class DenseRefactorSolver final : public FreeSolver {
public:
    /// Every buffer is sized for |F| = n once: a solve allocates nothing per pivot step.
    DenseRefactorSolver(const linalg::SymmetricRows& Ap, DenseWorkspace& ws) : A_(Ap), ws_(sized_workspace(ws, Ap.n())) {}

    bool prepare(double shift) override {
        shift_ = shift;
        return true;
    }

    FactorOutcome solve_free(const std::vector<char>& tight, std::vector<double>& x, bool) override {
        factored_ = false;
        const int nf = gather_free(tight);
        for (int i = 0; i < A_.n(); ++i)
            if (tight[i]) x[i] = 0;
        if (nf == 0) return FactorOutcome::Refactored;
        if (!factor(nf)) return FactorOutcome::Breakdown;
        factored_ = true;
        solve_in_place(x);
        return FactorOutcome::Refactored;
    }

    void solve_again(std::vector<double>& x) override {
        for (int i = 0; i < A_.n(); ++i)
            if (ws_.position[i] < 0) x[i] = 0;
        if (factored_) solve_in_place(x);
    }

private:
    /// L_FF L_FF^T = A_FF, in place in the leading |F| x |F| block of store. Row-major lower
    /// is column-major upper: Eigen's LLT<Upper> writes U = L^T where L belongs.
    bool factor(int nf) {
        if (nf <= kPlainLoopsUpTo)
            return linalg::dense_cholesky(ws_.store.data(), nf, A_.n(), ws_.diagonal.data(), ws_.inverse_diagonal.data()) < 0;
        Eigen::Map<Eigen::MatrixXd> store(ws_.store.data(), A_.n(), A_.n());
        Eigen::Ref<Eigen::MatrixXd> leading = store.topLeftCorner(nf, nf);
        const Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>, Eigen::Upper> llt(leading);
        if (llt.info() != Eigen::Success) return false;
        for (int k = 0; k < nf; ++k) {
            const double l = leading(k, k);
            if (linalg::pivot_breaks_down(l * l, ws_.diagonal[k])) return false;
            ws_.inverse_diagonal[k] = 1.0 / l;
        }
        return true;
    }

    /// x_F <- L_FF^-T L_FF^-1 x_F.
    void solve_in_place(std::vector<double>& x) {
        const std::vector<int>& free = ws_.free;
        const int nf = static_cast<int>(free.size());
        double* rhs = ws_.rhs.data();
        for (int k = 0; k < nf; ++k) rhs[k] = x[free[k]];
        linalg::dense_cholesky_solve(ws_.store.data(), ws_.inverse_diagonal.data(), nf, A_.n(), rhs);
        for (int k = 0; k < nf; ++k) x[free[k]] = rhs[k];
    }

    /// A_FF (+ shift I) into store's leading |F| x |F| block (row stride n, lower triangle: all
    /// the factorization reads) and its diagonal into ws_.diagonal, free rows in increasing
    /// permuted order; returns |F|.
    int gather_free(const std::vector<char>& tight) {
        const int n = A_.n();
        std::vector<int>& free = ws_.free;
        std::vector<int>& position = ws_.position;
        free.clear();
        for (int i = 0; i < n; ++i) {
            position[i] = tight[i] ? -1 : static_cast<int>(free.size());
            if (!tight[i]) free.push_back(i);
        }
        const int nf = static_cast<int>(free.size());
        for (int a = 0; a < nf; ++a) {
            double* row = ws_.store.data() + static_cast<std::size_t>(a) * n;
            std::fill(row, row + a, 0.0);
            const int i = free[a];
            row[a] = ws_.diagonal[a] = A_.diag(i) + shift_;
            for (int k = A_.row_begin(i); k < A_.row_end(i); ++k) {
                const int b = position[A_.col(k)];
                if (b >= 0 && b < a) row[b] = A_.val(k);
            }
        }
        return nf;
    }

    const linalg::SymmetricRows& A_;
    double shift_ = 0;
    DenseWorkspace& ws_;  ///< store: n x n, the leading |F| x |F| block holds A_FF, then L_FF
    bool factored_ = false;  ///< store holds the factor of the latest successful solve_free
};

}  // namespace

struct DenseRefactorVectors {
    DenseWorkspace workspace;
};

template class KeptBuffers<DenseRefactorVectors>;

std::unique_ptr<FreeSolver> make_dense_refactor_solver(const linalg::SymmetricRows& Ap, DenseRefactorBuffers& buffers) {
    return std::make_unique<DenseRefactorSolver>(Ap, buffers.contents().workspace);
}

}  // namespace ode_bpp::pivoting
