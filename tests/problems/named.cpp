#include "problems/named.h"

#include "problems/generators.h"

#include <limits>

namespace ode_bpp::problems {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

OwnedProblem from_rows(std::string name, std::initializer_list<std::initializer_list<double>> rows) {
    OwnedProblem p = OwnedProblem::zeros(std::move(name), static_cast<int>(rows.size()));
    int i = 0;
    for (const auto& row : rows) {
        int j = 0;
        for (double v : row) p.a(i, j++) = v;
        ++i;
    }
    return p;
}

}  // namespace

OwnedProblem dantzig_friction_3x3() {
    OwnedProblem p = from_rows("dantzig_friction_3x3", {{2, .3, .1}, {.3, 1.5, .2}, {.1, .2, 1.8}});
    p.b = {1, .9, -.2};
    p.lo = {0, -0.5, -kInf};
    p.hi = {kInf, 0.5, kInf};
    p.findex = {-1, 0, -1};
    return p;
}

OwnedProblem friction_presses_a_second_contact() {
    OwnedProblem p = from_rows("friction_presses_a_second_contact", {{2, 0, .5}, {0, 1, -.8}, {.5, -.8, 2}});
    p.b = {2, 1, .3};
    p.lo = {0, -1, 0};
    p.hi = {kInf, 1, kInf};
    p.findex = {-1, 0, -1};
    return p;
}

OwnedProblem duplicated_rows() {
    // two identical contact normals on one body plus a friction-free tangent: J has equal rows
    OwnedProblem p = from_rows("duplicated_rows", {{1, 1, .2}, {1, 1, .2}, {.2, .2, 1}});
    p.b = {1, 1, .3};
    p.lo = {0, 0, -kInf};
    p.hi = {kInf, kInf, kInf};
    return p;
}

OwnedProblem opposed_friction_pair() {
    // body (vx, vy, omega), mass 1, inertia 1/6; contacts at (-+0.5, -0.5) with normal +y
    const double J[4][3] = {{0, 1, -0.5}, {1, 0, 0.5}, {0, 1, 0.5}, {1, 0, 0.5}};
    const double inv_mass[3] = {1, 1, 6};
    const double cfm = 2e-9;  // relative to A_ii ~ 2.5
    OwnedProblem p = OwnedProblem::zeros("opposed_friction_pair", 4);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double a = i == j ? cfm : 0;
            for (int k = 0; k < 3; ++k) a += J[i][k] * inv_mass[k] * J[j][k];
            p.a(i, j) = a;
        }
    const double gravity_step = 9.81 / 60;  // b_n = -J v_free: gravity pulls the box into the ground
    p.b = {gravity_step, 0, gravity_step, 0};
    p.lo = {0, -0.5, 0, -0.5};
    p.hi = {kInf, 0.5, kInf, 0.5};
    p.findex = {-1, 0, -1, 2};
    return p;
}

OwnedProblem heavy_internal_impulse() {
    const double a = 1 - 1e-6;
    OwnedProblem p = from_rows("heavy_internal_impulse", {{1, -a, 1}, {-a, 1, -1}, {1, -1, 2}});
    p.nub = 2;
    p.b = {1e-3, 1e-3, 1e-7};
    p.lo = {-kInf, -kInf, 0};
    p.hi = {kInf, kInf, kInf};
    return p;
}

}  // namespace ode_bpp::problems

namespace ode_bpp::problems {

OwnedProblem block_pivoting_cycle() {
    // Found by a seeded search over SPD boxed problems (B B^T + I/2, entries on a grid of 1/4):
    // from all-free, pure block steps revisit the same index sets forever (27 sets, 100 steps).
    OwnedProblem p = from_rows("block_pivoting_cycle", {{4.75, 5, -5.5}, {5, 7, -6.75}, {-5.5, -6.75, 7.75}});
    p.b = {0, 2, 2};
    p.lo = {-0.75, -3.25, -1.5};
    p.hi = {0.75, 0.25, 0.5};
    return p;
}

}  // namespace ode_bpp::problems

namespace ode_bpp::problems {

OwnedProblem never_slipping_chain() {
    OwnedProblem p = chain_mlcp(6, 4, 100, 1e-10);
    p.name = "never_slipping_chain";
    for (int i = 0; i < p.n; ++i)
        if (p.findex[i] >= 0) p.lo[i] = -kInf, p.hi[i] = kInf;  // ODE: lo = -mu, hi = mu
    return p;
}

}  // namespace ode_bpp::problems
