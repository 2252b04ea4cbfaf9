#include "pivoting/lemke_rules.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ode_bpp::pivoting {

namespace {

/// A column entry blocks the ratio test only above this fraction of the column's largest entry:
/// smaller ones are rounding of structural zeros of B^-1 [I -M -d].
constexpr double kPivotTolerance = 1e-11;
/// Ratios and lexicographic keys within this relative distance of the least are ties.
constexpr double kTieTolerance = 1e-12;

/// Keeps the rows of `ties` whose key(i) / c_i is least (the lexicographic rule on one column).
void narrow(const Eigen::VectorXd& key, const Eigen::VectorXd& c, std::vector<int>& ties) {
    double least = std::numeric_limits<double>::infinity(), largest = 0;
    for (int i : ties) {
        least = std::min(least, key[i] / c[i]);
        largest = std::max(largest, std::abs(key[i] / c[i]));
    }
    const double slack = kTieTolerance * largest;
    ties.erase(std::remove_if(ties.begin(), ties.end(), [&](int i) { return key[i] / c[i] > least + slack; }), ties.end());
}

}  // namespace

int lexicographic_ratio_test(const Eigen::VectorXd& rhs, const Eigen::VectorXd& c, const std::vector<int>& basis,
                             const LemkeKeyColumn& key_column) {
    const int n = static_cast<int>(c.size());
    const double c_max = c.cwiseAbs().maxCoeff();
    if (!(c_max > 0)) return -1;
    const auto ratio = [&](int i) { return std::max(rhs[i], 0.0) / c[i]; };
    double least = std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i)
        if (c[i] > kPivotTolerance * c_max) least = std::min(least, ratio(i));
    if (!std::isfinite(least)) return -1;
    const double rhs_scale = kTieTolerance * rhs.cwiseAbs().maxCoeff();
    std::vector<int> ties;
    for (int i = 0; i < n; ++i)
        if (c[i] > kPivotTolerance * c_max && ratio(i) <= least * (1 + kTieTolerance) + rhs_scale / c[i]) ties.push_back(i);
    for (int i : ties)
        if (basis[i] == 2 * n) return i;
    Eigen::VectorXd key;
    for (int k = 0; k < n && ties.size() > 1; ++k) {
        key_column(k, key);
        narrow(key, c, ties);
    }
    return ties.front();
}

void read_lemke_solution(const std::vector<int>& basis, const Eigen::VectorXd& xb, LemkeSolution& s) {
    const int n = static_cast<int>(xb.size());
    s.z = Eigen::VectorXd::Zero(n);
    s.z_basic.assign(static_cast<std::size_t>(n), 0);
    s.u_basic.assign(static_cast<std::size_t>(n), 0);
    for (int r = 0; r < n; ++r) {
        const int var = basis[r];
        if (var < n) {
            s.u_basic[var] = 1;
        } else if (var < 2 * n) {
            s.z_basic[var - n] = 1;
            s.z[var - n] = std::max(0.0, xb[r]);
        }
    }
}

}  // namespace ode_bpp::pivoting
