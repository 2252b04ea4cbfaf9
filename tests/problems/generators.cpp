#include "problems/generators.h"

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <cmath>
#include <limits>
#include <random>

namespace ode_bpp::problems {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Uniform [0, 1) and standard normal numbers, reproducible across standard libraries.
class Random {
public:
    explicit Random(std::uint64_t seed) : engine_(seed) {}
    double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
    double uniform(double a, double b) { return a + (b - a) * uniform(); }
    double normal() {  // Box-Muller
        const double u1 = 1.0 - uniform(), u2 = uniform();
        return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
    }

private:
    std::mt19937_64 engine_;
};

using Mat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

void copy_matrix(const Mat& M, OwnedProblem& p) {
    for (int i = 0; i < p.n; ++i)
        for (int j = 0; j < p.n; ++j) p.a(i, j) = M(i, j);
}

/// ODE's MLCP of one step (step.cpp): A = J M^-1 J^T + (cfm / h) I, symmetrized, and
/// b = -J (v / h + M^-1 f). J: rows x dofs; Minv, v, f: dofs. Writes p.A and p.b.
void fill_from_dynamics(const Mat& J, const Eigen::VectorXd& Minv, const Eigen::VectorXd& v, const Eigen::VectorXd& f,
                        double cfm, double h, OwnedProblem& p) {
    // J has at most 12 non-zeros a row: the product of the sparse factors costs O(entries of A),
    // where the dense one cost rows^2 dofs (3 s for a 2,400-row chain, minutes under ASan)
    const Eigen::SparseMatrix<double, Eigen::RowMajor> Js = J.sparseView();
    Mat A = Mat(Js * Minv.asDiagonal() * Js.transpose());
    A.diagonal().array() += cfm / h;
    copy_matrix(0.5 * (A + A.transpose()), p);
    const Eigen::VectorXd rhs = -J * (v / h + Minv.asDiagonal() * f);
    for (int i = 0; i < p.n; ++i) p.b[i] = rhs[i];
}

/// The 3x3 matrix [r]x with [r]x v = r x v.
Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& r) {
    Eigen::Matrix3d c;
    c << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
    return c;
}

}  // namespace

std::vector<double> random_spd(int n, double cond, std::uint64_t seed) {
    Random rng(seed);
    Mat G(n, n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) G(i, j) = rng.normal();
    const Mat Q = Eigen::HouseholderQR<Mat>(G).householderQ();
    Eigen::VectorXd lambda(n);
    for (int k = 0; k < n; ++k) lambda[k] = n > 1 ? std::pow(cond, -double(k) / (n - 1)) : 1.0;
    Mat A = Q * lambda.asDiagonal() * Q.transpose();
    A = 0.5 * (A + A.transpose()).eval();  // exactly symmetric
    return std::vector<double>(A.data(), A.data() + static_cast<std::ptrdiff_t>(n) * n);
}

OwnedProblem random_boxed_mlcp(int n, int nub, int friction_contacts, double cond, std::uint64_t seed) {
    OwnedProblem p = OwnedProblem::zeros("random_boxed_mlcp", n);
    const std::vector<double> A = random_spd(n, cond, seed);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) p.a(i, j) = A[static_cast<std::size_t>(i) * n + j];
    Random rng(seed ^ 0x9e3779b97f4a7c15ULL);
    p.nub = nub;
    p.findex.assign(n, -1);
    int row = nub;
    for (int c = 0; c < friction_contacts; ++c, row += 3) {
        p.lo[row] = 0;
        p.hi[row] = kInf;
        p.b[row] = rng.uniform(0.0, 1.0);  // contacts mostly push
        for (int t = 1; t <= 2; ++t) {
            p.findex[row + t] = row;
            p.hi[row + t] = rng.uniform(0.3, 1.0);
            p.lo[row + t] = -p.hi[row + t];
            p.b[row + t] = rng.normal();
        }
    }
    for (; row < n; ++row) {
        const double kind = rng.uniform();
        p.lo[row] = kind < 0.6 ? -rng.uniform(0.05, 0.5) : kind < 0.8 ? 0.0 : -kInf;
        p.hi[row] = kind < 0.6 ? rng.uniform(0.05, 0.5) : kind < 0.8 ? kInf : rng.uniform(0.0, 0.5);
        p.b[row] = rng.normal();
    }
    for (int i = 0; i < nub; ++i) p.b[i] = rng.normal();
    return p;
}

OwnedProblem chain_mlcp(int links, int contacts, double mass_ratio, double cfm) {
    const double h = 1.0 / 60, g = 9.81, len = 0.5, radius = 0.1, mu = 0.8;
    const int joint_rows = 3 * (links - 1), rows = joint_rows + 3 * contacts, dofs = 6 * links;
    OwnedProblem p = OwnedProblem::zeros("chain_mlcp", rows);
    p.nub = joint_rows;
    p.findex.assign(rows, -1);
    Mat J = Mat::Zero(rows, dofs);
    Eigen::VectorXd Minv(dofs), v = Eigen::VectorXd::Zero(dofs), f = Eigen::VectorXd::Zero(dofs);
    std::vector<Eigen::Vector3d> centre(links);
    for (int k = 0; k < links; ++k) {
        const double m = k == links - 1 ? mass_ratio : 1.0;
        centre[k] = Eigen::Vector3d(k * len, 0, radius);
        const Eigen::Vector3d inertia(m * radius * radius / 2, m * len * len / 12, m * len * len / 12);
        Minv.segment<3>(6 * k).setConstant(1 / m);
        Minv.segment<3>(6 * k + 3) = inertia.cwiseInverse();
        v[6 * k] = 0.1 + 0.6 * std::sin(1.3 * k);  // sliding, some links faster than others
        v[6 * k + 1] = 0.3 * std::cos(0.9 * k);
        v[6 * k + 5] = 0.5 * std::sin(0.4 * k);   // and spinning about the vertical
        f[6 * k + 2] = -m * g;
    }
    // ball joint k (k >= 1): bodies k-1 and k meet at the anchor between them (Eq. 1's J)
    for (int k = 1; k < links; ++k) {
        const int row = 3 * (k - 1);
        const Eigen::Vector3d anchor = centre[k] - Eigen::Vector3d(len / 2, 0, 0);
        J.block<3, 3>(row, 6 * k) = Eigen::Matrix3d::Identity();
        J.block<3, 3>(row, 6 * k + 3) = -cross_matrix(anchor - centre[k]);
        J.block<3, 3>(row, 6 * (k - 1)) = -Eigen::Matrix3d::Identity();
        J.block<3, 3>(row, 6 * (k - 1) + 3) = cross_matrix(anchor - centre[k - 1]);
        p.block_row.push_back(row);
        p.block_body.insert(p.block_body.end(), {k - 1, k});
    }
    // ground contacts: normal, then two tangents whose bounds follow the normal (findex)
    const Eigen::Vector3d dirs[3] = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()};
    for (int c = 0; c < contacts; ++c) {
        const int body = contacts > 1 ? static_cast<int>(std::lround(double(c) * (links - 1) / (contacts - 1))) : 0;
        const Eigen::Vector3d r(0, 0, -radius);
        const int row = joint_rows + 3 * c;
        for (int t = 0; t < 3; ++t) {
            J.block<1, 3>(row + t, 6 * body) = dirs[t].transpose();
            J.block<1, 3>(row + t, 6 * body + 3) = r.cross(dirs[t]).transpose();
        }
        p.lo[row] = 0;
        for (int t = 1; t <= 2; ++t) {
            p.findex[row + t] = row;
            p.hi[row + t] = mu;
            p.lo[row + t] = -mu;
        }
        p.block_row.push_back(row);
        p.block_body.insert(p.block_body.end(), {body, -1});
    }
    p.block_row.push_back(rows);
    fill_from_dynamics(J, Minv, v, f, cfm, h, p);
    return p;
}

OwnedProblem capstan_mlcp(int links, double wrap, double mu, double load_ratio, double cfm) {
    const double h = 1.0 / 60, g = 9.81, radius = 1.0, thickness = 0.02;
    const int joint_rows = 2 * (links - 1), rows = joint_rows + 2 * links, dofs = 3 * links;
    OwnedProblem p = OwnedProblem::zeros("capstan_mlcp", rows);
    p.nub = joint_rows;
    p.findex.assign(rows, -1);
    Mat J = Mat::Zero(rows, dofs);
    Eigen::VectorXd Minv(dofs), v = Eigen::VectorXd::Zero(dofs), f = Eigen::VectorXd::Zero(dofs);
    const double step_angle = wrap / links, length = radius * step_angle;
    std::vector<double> angle(links);
    // planar velocity of a point at offset r from a body's centre: v + omega * (-r_y, r_x)
    const auto point_row = [&](int row, int body, const Eigen::Vector2d& dir, const Eigen::Vector2d& r, double sign) {
        J(row, 3 * body) += sign * dir.x();
        J(row, 3 * body + 1) += sign * dir.y();
        J(row, 3 * body + 2) += sign * (r.x() * dir.y() - r.y() * dir.x());
    };
    for (int k = 0; k < links; ++k) {
        angle[k] = std::acos(-1.0) / 2 + wrap / 2 - (k + 0.5) * step_angle;  // from the left over the top
        const double m = k == links - 1 ? load_ratio : 1.0;
        Minv.segment<2>(3 * k).setConstant(1 / m);
        Minv[3 * k + 2] = 12 / (m * length * length);
        const Eigen::Vector2d tangent(std::sin(angle[k]), -std::cos(angle[k]));  // towards the load
        v.segment<2>(3 * k) = 0.5 * tangent;  // sliding towards the load
        f[3 * k + 1] = -m * g;
    }
    const auto centre = [&](int k) -> Eigen::Vector2d { return Eigen::Vector2d(std::cos(angle[k]), std::sin(angle[k])) * (radius + thickness); };
    for (int k = 1; k < links; ++k) {  // planar ball joint between links k-1 and k
        const double a = angle[k] + step_angle / 2;
        const Eigen::Vector2d anchor = Eigen::Vector2d(std::cos(a), std::sin(a)) * (radius + thickness);
        const int row = 2 * (k - 1);
        for (int axis = 0; axis < 2; ++axis) {
            const Eigen::Vector2d dir = Eigen::Vector2d::Unit(axis);
            point_row(row + axis, k, dir, anchor - centre(k), 1.0);
            point_row(row + axis, k - 1, dir, anchor - centre(k - 1), -1.0);
        }
        p.block_row.push_back(row);
        p.block_body.insert(p.block_body.end(), {k - 1, k});
    }
    for (int k = 0; k < links; ++k) {  // contact with the drum: normal, then friction (findex)
        const Eigen::Vector2d normal(std::cos(angle[k]), std::sin(angle[k]));
        const Eigen::Vector2d tangent(-normal.y(), normal.x());
        const Eigen::Vector2d r = -thickness * normal;
        const int row = joint_rows + 2 * k;
        point_row(row, k, normal, r, 1.0);
        point_row(row + 1, k, tangent, r, 1.0);
        p.lo[row] = 0;
        p.findex[row + 1] = row;
        p.hi[row + 1] = mu;
        p.lo[row + 1] = -mu;
        p.block_row.push_back(row);
        p.block_body.insert(p.block_body.end(), {k, -1});
    }
    p.block_row.push_back(rows);
    fill_from_dynamics(J, Minv, v, f, cfm, h, p);
    return p;
}

}  // namespace ode_bpp::problems
