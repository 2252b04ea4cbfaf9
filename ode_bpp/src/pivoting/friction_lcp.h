// The consistent-friction MLCP as a standard LCP for Lemke's method (lemke.h), in the driver's
// permuted space. A last resort for the frames that the linked block pivoting does not finish
// (a chain wound on a drum: friction raises its own normal impulses).
//
// With w = (A + shift I) x - b, rows split into unbounded U (w_U = 0), known K (pinned rows,
// friction rows with mu = 0) and bounded R. Eliminating U (Schur complement, A_UU is SPD):
//     w_R = S x_R - b~,   S = A_RR - A_RU A_UU^-1 A_UR,   b~ = b_R - A_RK x_K - A_RU A_UU^-1 (b_U - A_UK x_K).
// Each bounded row becomes non-negative variables y, x_R = x0 + Q y (Stewart & Trinkle 1996,
// with ODE's box friction |x_f| <= mu x_n instead of a polyhedral cone):
//     lower bound only     x = lo + y          u = w               >= 0 _|_ y
//     upper bound only     x = hi - y          u = -w              >= 0 _|_ y
//     box [lo, hi]         x = lo + y          u = w + l           >= 0 _|_ y
//                                              v = (hi - lo) - y   >= 0 _|_ l
//     friction, normal n   x = y+ - y-         u+ = w + l, u- = -w + l  >= 0 _|_ y+, y-
//                                              v = mu x_n - y+ - y-     >= 0 _|_ l
// so that M = [Q'SQ  E; N  0] with N = mu (normal selection) - E' on friction and -E' on boxes:
// z'Mz = y'Q'SQy + mu l'(x_n) >= 0 for z >= 0, i.e. M is copositive. A solution makes l > 0
// only where a friction row sits at +-mu x_n of its own normal: the MLCP with consistent bounds.
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <optional>
#include <string>
#include <vector>

#include "ode_bpp/solver.h"
#include "pivoting/boxed_lcp.h"
#include "pivoting/lemke.h"

namespace ode_bpp::pivoting {

/// Friction rows of the problem (permuted indices): row rows[k] has normal normals[k] and
/// coefficient |mu[k]|.
struct FrictionRows {
    const std::vector<int>& rows;
    const std::vector<int>& normals;
    const std::vector<double>& mu;
};

class FrictionLcp {
public:
    /// Builds the LCP of lcp (A + shift I, b, lo, hi, always_free; the friction rows' own lo/hi
    /// are ignored). Returns nothing, with the reason in why, when the problem is outside the
    /// formulation: a normal row that can go negative or is itself unbounded or friction, an
    /// infinite mu, or A_UU not positive definite.
    static std::optional<FrictionLcp> build(const BoxedLcp& lcp, const FrictionRows& friction, std::string& why);

    /// The same LCP with M sparse (sparse_M(); M() stays empty), for problems without unbounded
    /// rows: then S = A_RR keeps A's sparsity, and M has O(nnz(A)) entries. Returns nothing, with
    /// the reason in why, where build() would, or when the problem has unbounded rows.
    static std::optional<FrictionLcp> build_sparse(const BoxedLcp& lcp, const FrictionRows& friction, std::string& why);

    /// True when no row but the friction rows is unbounded (always free, or lo = -inf and
    /// hi = inf): the problems build_sparse takes, as far as their rows' kinds decide. O(n).
    static bool has_sparse_form(const BoxedLcp& lcp, const FrictionRows& friction);

    /// The LCP, balanced by a positive diagonal D (M = D M0 D, q = D q0, z0 = D z).
    const Eigen::MatrixXd& M() const { return M_; }
    const Eigen::SparseMatrix<double>& sparse_M() const { return sparse_M_; }
    const Eigen::VectorXd& q() const { return q_; }

    /// A complementary basis guessed from an index set and answer of the MLCP (states, x: n
    /// entries each, permuted space): z_k basic (N flags) for every LCP variable the guess makes
    /// positive, its slack u_k basic elsewhere. Lemke's path started there (sparse_lemke.h) ends
    /// at once when the guess is an answer.
    std::vector<char> basis_guess(const std::vector<RowState>& states, const std::vector<double>& x) const;

    /// x (out, n entries, permuted space) and the index set it implies (out, n): rows whose
    /// slack is nonbasic are tight, every other row free.
    void recover(const LemkeSolution& s, std::vector<double>& x, std::vector<RowState>& states) const;

private:
    enum class Kind { Unbounded, Known, Lower, Upper, Box, Friction };
    struct Row {
        Kind kind = Kind::Unbounded;
        double value = 0;  ///< Known: x; Lower/Box: lo; Upper: hi
        double width = 0;  ///< Box: hi - lo
        double mu = 0;     ///< Friction
        int normal = -1;   ///< Friction: the normal row
        int y = -1;        ///< first LCP variable (Friction: y+ at y, y- at y + 1)
        int l = -1;        ///< the bound's multiplier (Box, Friction)
        int local = -1;    ///< position within U or R
    };

    bool classify(const BoxedLcp& lcp, const FrictionRows& friction, std::string& why);
    void number_variables();
    bool eliminate_unbounded(const Eigen::MatrixXd& A, const BoxedLcp& lcp, std::string& why);
    void assemble(const Eigen::MatrixXd& S, const Eigen::VectorXd& b_reduced);
    void assemble_sparse(const BoxedLcp& lcp);
    /// Each y variable's row of R (row_of) and sign of Q (sign), num_y_ entries each.
    void y_rows(std::vector<int>& row_of, std::vector<double>& sign) const;
    /// The entries of M outside Q'SQ (add(k, l, value)) and q's entries of the multipliers l.
    template <class Add>
    void add_bound_rows(Add add);
    /// D of balance() from the diagonal of Q'SQ (num_y_ entries).
    void balance_scale(const Eigen::VectorXd& y_diagonal);
    void balance();
    Eigen::VectorXd offset_x0() const;

    std::vector<Row> rows_;
    std::vector<int> unbounded_, bounded_;  ///< rows of U and R, ascending
    int num_y_ = 0, num_l_ = 0;
    Eigen::MatrixXd G_;   ///< A_UU^-1 A_UR
    Eigen::VectorXd g_;   ///< A_UU^-1 (b_U - A_UK x_K)
    Eigen::MatrixXd M_;
    Eigen::SparseMatrix<double> sparse_M_;
    Eigen::VectorXd q_;
    Eigen::VectorXd scale_;  ///< D of the balanced LCP: z = D z'
};

}  // namespace ode_bpp::pivoting
