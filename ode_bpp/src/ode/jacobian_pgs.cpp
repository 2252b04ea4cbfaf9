#include "ode/jacobian_pgs.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "ode/assemble.h"
#include "ode/island_view.h"
#include "ode_bpp/residuals.h"
#include "ode_bpp/validation.h"
#include "row_bounds.h"

namespace ode_bpp::ode {

namespace {

constexpr int kBodyDofs = 6;

/// JinvM_i . v over one body: J M^-1 pads each half of its row to four entries (<ode/mlcp.h>).
double jinvm_dot(const dReal* jinvm, const double* v) {
    return jinvm[0] * v[0] + jinvm[1] * v[1] + jinvm[2] * v[2] + jinvm[4] * v[3] + jinvm[5] * v[4] + jinvm[6] * v[5];
}

/// |JinvM_i| . v over one body (v: a body's |J|^T |x|): the row scale's bound.
double abs_jinvm_dot(const dReal* jinvm, const double* v) {
    return std::abs(jinvm[0]) * v[0] + std::abs(jinvm[1]) * v[1] + std::abs(jinvm[2]) * v[2] +
           std::abs(jinvm[4]) * v[3] + std::abs(jinvm[5]) * v[4] + std::abs(jinvm[6]) * v[5];
}

/// JinvM_i . J_i over one body, summed from 0 in ODE's order (lx .. az) as the assembly sums a
/// diagonal entry, so that A_ii is the assembled A's bit for bit.
double jacobian_dot(const dReal* j, const dReal* jinvm) {
    double sum = 0;
    for (int k = 0; k < kBodyDofs; ++k) sum += jinvm[k < 3 ? k : k + 1] * j[k];
    return sum;
}

/// One row's two sides: the bodies it acts on (-1: none) and its rows of J and J M^-1 for each.
struct RowSides {
    int body[2];
    const dReal* j[2];
    const dReal* jinvm[2];
};

RowSides sides_of(const dMLCP& island, const dMLCPJoint& joint, int i) {
    RowSides s{};
    for (int side = 0; side < 2; ++side) {
        s.body[side] = joint.body[side];
        s.j[side] = side_row(island.J, dMLCP_J_ROW, joint, side, i);
        s.jinvm[side] = side_row(island.JinvM, dMLCP_JINVM_ROW, joint, side, i);
    }
    return s;
}

/// (A x)_i = sum over the row's bodies of JinvM_i . (J^T x)(body) + cfm_i x_i.
double row_product(const RowSides& s, const std::vector<double>& impulse, double cfm_x) {
    double sum = cfm_x;
    for (int side = 0; side < 2; ++side)
        if (s.body[side] >= 0) sum += jinvm_dot(s.jinvm[side], &impulse[static_cast<std::size_t>(s.body[side]) * kBodyDofs]);
    return sum;
}

/// J^T x on the row's bodies after x_i moved by delta.
void add_row_impulse(const RowSides& s, double delta, std::vector<double>& impulse) {
    for (int side = 0; side < 2; ++side) {
        if (s.body[side] < 0) continue;
        double* f = &impulse[static_cast<std::size_t>(s.body[side]) * kBodyDofs];
        for (int k = 0; k < kBodyDofs; ++k) f[k] += delta * s.j[side][k];
    }
}

/// A_ii = cfm_i + sum over the row's bodies of JinvM_i . J_i, as the assembly sums it.
double diagonal_entry(const RowSides& s, double cfm) {
    double a = cfm;
    for (int side = 0; side < 2; ++side)
        if (s.body[side] >= 0) a += jacobian_dot(s.j[side], s.jinvm[side]);
    return a;
}

bool row_is_finite(const RowSides& s, double cfm) {
    if (!std::isfinite(cfm)) return false;
    for (int side = 0; side < 2; ++side) {
        if (s.body[side] < 0) continue;
        for (int k = 0; k < kBodyDofs; ++k)
            if (!std::isfinite(s.j[side][k])) return false;
        for (int k = 0; k < dMLCP_JINVM_ROW; ++k)
            if (k % 4 != 3 && !std::isfinite(s.jinvm[side][k])) return false;
    }
    return true;
}

/// Calls visit(i, sides) for every row in order.
template <typename Visit>
void for_each_row(const dMLCP& island, Visit&& visit) {
    for (int k = 0; k < island.nj; ++k) {
        const dMLCPJoint& joint = island.joints[k];
        for (int i = joint.row; i < joint.row + joint.m; ++i) visit(i, sides_of(island, joint, i));
    }
}

/// A's diagonal into diagonal (m entries); an empty message, or the first row whose J, J M^-1 or
/// cfm is not finite or whose A_ii is not positive.
std::string diagonal_of(const dMLCP& island, std::vector<double>& diagonal) {
    diagonal.assign(static_cast<std::size_t>(island.m), 0.0);
    int bad = -1;        // the first defective row: its message is built only then
    bool finite = true;  // whether that row's J, J M^-1 and cfm are finite
    for_each_row(island, [&](int i, const RowSides& s) {
        if (bad >= 0) return;
        finite = row_is_finite(s, island.cfm[i]);
        if (finite) diagonal[i] = diagonal_entry(s, island.cfm[i]);
        if (!finite || !(diagonal[i] > 0)) bad = i;
    });
    if (bad < 0) return {};
    std::ostringstream m;
    m << "row " << bad << ": ";
    if (!finite) m << "J, J M^-1 or cfm is not finite";
    else m << "A(" << bad << "," << bad << ") = " << diagonal[bad] << " is not > 0";
    return m.str();
}

void sweep(const dMLCP& island, const Problem& p, const std::vector<double>& diagonal, JacobianPgsBuffers& ws) {
    std::vector<double>& x = ws.x;
    const ConstStrided xs{x.data(), 1};
    for_each_row(island, [&](int i, const RowSides& s) {
        const double w = row_product(s, ws.impulse, island.cfm[i] * x[i]) - p.b[i];
        const auto [lo, hi] = bounds_at(p, xs, i);
        const double next = std::clamp(x[i] - w / diagonal[i], lo, hi);
        add_row_impulse(s, next - x[i], ws.impulse);
        x[i] = next;
    });
}

/// w = A x - b and the scale bound at ws.x, from J^T x and |J|^T |x| (solve_by_jacobian_pgs).
void residual_vectors_at_answer(const dMLCP& island, const Problem& p, JacobianPgsBuffers& ws) {
    const std::vector<double>& x = ws.x;
    ws.magnitude.assign(static_cast<std::size_t>(island.nb) * kBodyDofs, 0.0);
    for_each_row(island, [&](int i, const RowSides& s) {
        for (int side = 0; side < 2; ++side) {
            if (s.body[side] < 0) continue;
            double* g = &ws.magnitude[static_cast<std::size_t>(s.body[side]) * kBodyDofs];
            for (int k = 0; k < kBodyDofs; ++k) g[k] += std::abs(x[i]) * std::abs(s.j[side][k]);
        }
    });
    ws.vectors.w.resize(x.size());
    ws.vectors.scale.resize(x.size());
    for_each_row(island, [&](int i, const RowSides& s) {
        ws.vectors.w[i] = row_product(s, ws.impulse, island.cfm[i] * x[i]) - p.b[i];
        double scale = std::abs(island.cfm[i] * x[i]) + std::abs(p.b[i]);
        for (int side = 0; side < 2; ++side)
            if (s.body[side] >= 0)
                scale += abs_jinvm_dot(s.jinvm[side], &ws.magnitude[static_cast<std::size_t>(s.body[side]) * kBodyDofs]);
        ws.vectors.scale[i] = scale;
    });
}

Result failed(const Options& o, Status status, const std::string& message, int m, Strided x) {
    Result r;
    r.method = o.method;
    r.friction = o.friction;
    r.status = status;
    r.message = message;
    for (int i = 0; i < m; ++i) x[i] = 0;
    return r;
}

std::string why(const Options& o, const Oversize& oversize) {
    std::ostringstream m;
    if (oversize.measure == Oversize::Measure::FactorEntries) m << "the Cholesky factor would hold ";
    else m << "A would hold at least ";
    m << oversize.entries << " entries, more than max_factor_entries = " << o.max_factor_entries
      << "; answered by " << std::max(0, o.pgs_iterations) << " sweeps of projected Gauss-Seidel on J and J M^-1, without forming A";
    return m.str();
}

}  // namespace

std::int64_t coupled_entries_lower_bound(const dMLCP& island, std::vector<std::int64_t>& rows_on_body) {
    rows_on_body.assign(static_cast<std::size_t>(std::max(0, island.nb)), 0);
    for (int k = 0; k < island.nj; ++k)
        for (int body : island.joints[k].body)
            if (body >= 0 && body < island.nb) rows_on_body[body] += island.joints[k].m;
    std::int64_t largest = 0, sum = 0;
    for (std::int64_t r : rows_on_body) {
        const std::int64_t pairs = r * (r + 1) / 2;
        largest = std::max(largest, pairs);
        sum += pairs;
    }
    return std::max(largest, sum / 2);
}

Result solve_by_jacobian_pgs(const dMLCP& island, const Problem& problem, const Options& options,
                             const Oversize& oversize, Strided x, JacobianPgsBuffers& ws) {
    const int m = island.m;
    if (const ValidationResult v = validate_rows(problem); !v.valid) return failed(options, Status::InvalidInput, v.message, m, x);
    if (const std::string defect = structure_defect(island); !defect.empty())
        return failed(options, Status::InvalidInput, defect, m, x);
    if (const std::string defect = diagonal_of(island, ws.vectors.diagonal); !defect.empty())
        return failed(options, Status::InvalidInput, defect, m, x);
    ws.x.assign(static_cast<std::size_t>(m), 0.0);
    ws.impulse.assign(static_cast<std::size_t>(island.nb) * kBodyDofs, 0.0);
    const int sweeps = std::max(0, options.pgs_iterations);
    for (int k = 0; k < sweeps; ++k) sweep(island, problem, ws.vectors.diagonal, ws);
    if (!std::all_of(ws.x.begin(), ws.x.end(), [](double v) { return std::isfinite(v); }))
        return failed(options, Status::NotSpd, "projected Gauss-Seidel on J ended with an answer that is not finite", m, x);
    residual_vectors_at_answer(island, problem, ws);
    Result r;
    r.method = options.method;
    r.friction = options.friction;
    r.status = Status::FallbackUsed;
    r.fallback = Fallback::Pgs;
    r.message = why(options, oversize);
    r.pivoting.pivots = sweeps;  // sweeps: PGS has no pivot steps
    r.states = states_of(problem, ws.x);
    r.tight = count_tight(r.states);
    r.residuals = residuals_from_vectors(problem, ConstStrided{ws.x.data(), 1}, ws.vectors, &r.states);
    for (int i = 0; i < m; ++i) x[i] = ws.x[i];
    return r;
}

}  // namespace ode_bpp::ode
