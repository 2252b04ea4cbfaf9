#include "pivoting/friction_update.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace ode_bpp::pivoting {

namespace {

double squared_norm(const std::vector<double>& a) {
    double s = 0;
    for (double v : a) s += v * v;
    return s;
}

std::vector<double> difference(const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> d(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) d[i] = a[i] - b[i];
    return d;
}

}  // namespace

std::vector<double> FrictionBoundUpdate::next(const std::vector<double>& bound, const std::vector<double>& target) {
    const std::size_t m = bound.size();
    const std::vector<double> f = difference(target, bound);
    if (!last_residual_.empty()) {
        if (squared_norm(f) < squared_norm(last_residual_)) {
            damping_ = std::min(initial_damping_, 2 * damping_);
            bound_differences_.push_back(difference(bound, last_bound_));
            residual_differences_.push_back(difference(f, last_residual_));
            if (static_cast<int>(bound_differences_.size()) > kDepth) {
                bound_differences_.pop_front();
                residual_differences_.pop_front();
            }
        } else {
            damping_ = std::max(kMinDamping, 0.5 * damping_);
            bound_differences_.clear();
            residual_differences_.clear();
        }
    }
    std::vector<double> step(m);
    for (std::size_t k = 0; k < m; ++k) step[k] = damping_ * f[k];
    const int depth = static_cast<int>(residual_differences_.size());
    if (depth > 0) {
        Eigen::MatrixXd dF(m, depth);
        for (int c = 0; c < depth; ++c)
            for (std::size_t k = 0; k < m; ++k) dF(k, c) = residual_differences_[c][k];
        const Eigen::VectorXd gamma = dF.colPivHouseholderQr().solve(Eigen::Map<const Eigen::VectorXd>(f.data(), m));
        if (gamma.allFinite())
            for (int c = 0; c < depth; ++c)
                for (std::size_t k = 0; k < m; ++k)
                    step[k] -= gamma[c] * (bound_differences_[c][k] + damping_ * residual_differences_[c][k]);
    }
    last_bound_ = bound;
    last_residual_ = f;
    std::vector<double> result(m);
    for (std::size_t k = 0; k < m; ++k) result[k] = std::max(0.0, bound[k] + step[k]);
    return result;
}

}  // namespace ode_bpp::pivoting
