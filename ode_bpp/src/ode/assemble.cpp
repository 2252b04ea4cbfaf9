#include "ode/assemble.h"

#include <algorithm>
#include <cassert>
#include <vector>

#include "ode_bpp/ode.h"

namespace ode_bpp::ode {

namespace {

void build_incidence(const dMLCP& p, Incidence& inc) {
    inc.first.assign(static_cast<std::size_t>(p.nb) + 1, 0);
    for (int k = 0; k < p.nj; ++k)
        for (int body : p.joints[k].body)
            if (body >= 0) ++inc.first[body + 1];
    for (int b = 0; b < p.nb; ++b) inc.first[b + 1] += inc.first[b];
    inc.joints.resize(static_cast<std::size_t>(inc.first[p.nb]));
    std::vector<int>& next = inc.next;
    next.assign(inc.first.begin(), inc.first.end() - 1);
    for (int k = 0; k < p.nj; ++k)
        for (int body : p.joints[k].body)
            if (body >= 0) inc.joints[next[body]++] = k;
}

/// Joints q < p that share a body with joint p, increasing.
void earlier_neighbours(const dMLCP& p, const Incidence& inc, int joint, std::vector<int>& out) {
    out.clear();
    for (int body : p.joints[joint].body) {
        if (body < 0) continue;
        for (int k = inc.first[body]; k < inc.first[body + 1] && inc.joints[k] < joint; ++k) out.push_back(inc.joints[k]);
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
}

/// The six entries of a row of J M^-1 that meet J's six for one body (ODE pads each half to four).
struct JinvMEntries {
    double m0, m1, m2, m4, m5, m6;
};

JinvMEntries entries_of(const dReal* jinvm) { return {jinvm[0], jinvm[1], jinvm[2], jinvm[4], jinvm[5], jinvm[6]}; }

/// JinvM_i . J_j over one body, summed as ODE's MultiplyAddJinvMxJToA does.
double body_term(const JinvMEntries& m, const dReal* j) {
    double sum = m.m0 * j[0];
    sum += m.m1 * j[1];
    sum += m.m2 * j[2];
    sum += m.m4 * j[3];
    sum += m.m5 * j[4];
    sum += m.m6 * j[5];
    return sum;
}

SharedSides shared_sides(const dMLCPJoint& p, const dMLCPJoint& q) {
    SharedSides shared;
    for (int side = 0; side < 2; ++side) {
        const int body = p.body[side];
        if (body < 0) continue;
        const int other = q.body[1] == body ? 1 : q.body[0] == body ? 0 : -1;
        if (other < 0) continue;
        shared.p_side[shared.count] = side;
        shared.q_side[shared.count++] = other;
    }
    return shared;
}

/// Row i's J M^-1 (m0, m1) against consecutive rows of J (from j0, j1) over `count` shared bodies,
/// in shared_sides' order (body[0] of p first, as ODE sums): emit(j, A(i,j)) for j in
/// [j_begin, j_end), each summed from 0; j0 and j1 move on past those rows (m1 and j1 are not
/// read when count is 1).
template <typename Emit>
[[gnu::always_inline]] inline void emit_entries(int count, const JinvMEntries& m0, const JinvMEntries& m1, const dReal*& j0,
                                                const dReal*& j1, int j_begin, int j_end, Emit&& emit) {
    if (count == 1) {  // most pairs share one body
        for (int j = j_begin; j < j_end; ++j, j0 += dMLCP_J_ROW) emit(j, 0.0 + body_term(m0, j0));
        return;
    }
    for (int j = j_begin; j < j_end; ++j, j0 += dMLCP_J_ROW, j1 += dMLCP_J_ROW) {
        double a = 0.0 + body_term(m0, j0);
        a += body_term(m1, j1);
        emit(j, a);
    }
}

/// Row i of joint p against the rows j of an earlier joint q before j_end: the entries
/// sum over the shared bodies of (row i of J M^-1) . (row j of J) (emit_entries), with row i's
/// entries held in registers; 0 where they share no body. Calls emit(j, value) for each j in
/// turn. Inlined: it is called once per row and coupled joint, mostly for two to six entries,
/// and GCC kept it out of line.
template <typename Emit>
[[gnu::always_inline]] inline void row_against_joint(const dMLCP& island, const dMLCPJoint& p, int i, const dMLCPJoint& q, int j_end,
                       const SharedSides& shared, Emit&& emit) {
    if (shared.count == 0) {
        for (int j = q.row; j < j_end; ++j) emit(j, 0.0);
        return;
    }
    const JinvMEntries m0 = entries_of(side_row(island.JinvM, dMLCP_JINVM_ROW, p, shared.p_side[0], i));
    const dReal* j0 = side_row(island.J, dMLCP_J_ROW, q, shared.q_side[0], q.row);
    if (shared.count == 1) {
        emit_entries(1, m0, m0, j0, j0, q.row, j_end, emit);
        return;
    }
    const JinvMEntries m1 = entries_of(side_row(island.JinvM, dMLCP_JINVM_ROW, p, shared.p_side[1], i));
    const dReal* j1 = side_row(island.J, dMLCP_J_ROW, q, shared.q_side[1], q.row);
    emit_entries(2, m0, m1, j0, j1, q.row, j_end, emit);
}

/// Row i of joint p against its own earlier rows, emit(j, value) for j = p.row .. i-1; returns
/// A(i,i): cfm_i, then each of p's bodies (body[0] first), as ODE adds them onto its diagonal.
/// Row i's J M^-1 is loaded once for both, and J read on from row p.row down to row i.
template <typename Emit>
[[gnu::always_inline]] inline double own_rows(const dMLCP& island, const dMLCPJoint& p, int i, const SharedSides& own,
                                            Emit&& emit) {
    if (own.count == 0) {
        for (int j = p.row; j < i; ++j) emit(j, 0.0);
        return island.cfm[i];
    }
    const JinvMEntries m0 = entries_of(side_row(island.JinvM, dMLCP_JINVM_ROW, p, own.p_side[0], i));
    const dReal* j0 = side_row(island.J, dMLCP_J_ROW, p, own.q_side[0], p.row);
    if (own.count == 1) {
        emit_entries(1, m0, m0, j0, j0, p.row, i, emit);
        return island.cfm[i] + body_term(m0, j0);
    }
    const JinvMEntries m1 = entries_of(side_row(island.JinvM, dMLCP_JINVM_ROW, p, own.p_side[1], i));
    const dReal* j1 = side_row(island.J, dMLCP_J_ROW, p, own.q_side[1], p.row);
    emit_entries(2, m0, m1, j0, j1, p.row, i, emit);
    double a = island.cfm[i];
    a += body_term(m0, j0);
    a += body_term(m1, j1);
    return a;
}

/// Each joint's couplings: the earlier joints it shares a body with, increasing, and the sides
/// they share (shared_sides). O(joints + incidences).
void find_couplings(const dMLCP& island, AssemblyBuffers& buffers, Couplings& out) {
    build_incidence(island, buffers.incidence);
    out.first.assign(1, 0);
    out.joint.clear();
    out.sides.clear();
    for (int pj = 0; pj < island.nj; ++pj) {
        earlier_neighbours(island, buffers.incidence, pj, buffers.neighbours);
        for (int qj : buffers.neighbours) {
            out.joint.push_back(qj);
            out.sides.push_back(shared_sides(island.joints[pj], island.joints[qj]));
        }
        out.first.push_back(static_cast<int>(out.joint.size()));
    }
}

/// Every joint's rows in turn, row by row with increasing columns: keep_lower(i, j, a) for each
/// lower entry (j < i: the coupled joints' rows, then the joint's own earlier rows), then
/// keep_diagonal(i, a).
template <typename KeepLower, typename KeepDiagonal>
void assemble_joints(const dMLCP& island, const Couplings& couplings, KeepLower keep_lower, KeepDiagonal keep_diagonal) {
    for (int pj = 0; pj < island.nj; ++pj) {
        const dMLCPJoint& p = island.joints[pj];
        const SharedSides own = shared_sides(p, p);
        for (int i = p.row; i < p.row + p.m; ++i) {
            const auto keep_row_i = [&keep_lower, i](int j, double a) { keep_lower(i, j, a); };
            for (int k = couplings.first[pj]; k < couplings.first[pj + 1]; ++k) {
                const dMLCPJoint& q = island.joints[couplings.joint[k]];
                row_against_joint(island, p, i, q, q.row + q.m, couplings.sides[k], keep_row_i);
            }
            keep_diagonal(i, own_rows(island, p, i, own, keep_row_i));
        }
    }
}

void describe_structure(const dMLCP& island, std::vector<int>& structure) {
    structure.clear();
    structure.push_back(island.m);
    structure.push_back(island.nb);
    structure.push_back(island.nj);
    for (int k = 0; k < island.nj; ++k) {
        const dMLCPJoint& joint = island.joints[k];
        structure.insert(structure.end(), {joint.row, joint.m, joint.body[0], joint.body[1]});
    }
}

bool matches_pattern(const AssemblyPattern& pattern, const linalg::SymmetricRows& out,
                     const std::vector<int>& structure, const std::vector<int>& order) {
    return pattern.rows == &out && pattern.structure == structure && pattern.order == order;
}

/// The pattern of out as the full assembly just built it: where each formed entry is stored
/// (linalg::SymmetricRows::entry_positions).
void remember_pattern(const linalg::SymmetricRows& out, const std::vector<int>& order, AssemblyBuffers& buffers) {
    AssemblyPattern& pattern = buffers.pattern;
    pattern.rows = &out;
    pattern.structure = buffers.structure;
    pattern.order = order;
    pattern.to_stored.resize(static_cast<std::size_t>(out.n()));
    for (int i = 0; i < out.n(); ++i) pattern.to_stored[out.built_row(i)] = i;
    pattern.slots = out.entry_positions();
    pattern.couplings.first.swap(buffers.couplings.first);
    pattern.couplings.joint.swap(buffers.couplings.joint);
    pattern.couplings.sides.swap(buffers.couplings.sides);
}

/// A of an island with the remembered pattern's structure, written into out's stored values: the
/// same assemble_joints forms the same entries in the same order, so the k-th goes where the k-th
/// went.
void refill_values(const dMLCP& island, linalg::SymmetricRows& out, const AssemblyPattern& pattern) {
    const linalg::SymmetricRows::Values values = out.values_in_place();
    const int* slot = pattern.slots.data();
    const auto keep_lower = [&values, &slot](int, int, double a) {
        values.values[slot[0]] = values.values[slot[1]] = a;
        slot += 2;
    };
    const auto keep_diagonal = [&values, &pattern](int i, double a) { values.diagonal[pattern.to_stored[i]] = a; };
    assemble_joints(island, pattern.couplings, keep_lower, keep_diagonal);
    assert(slot == pattern.slots.data() + pattern.slots.size());
}

}  // namespace

bool has_sparse_form(const dMLCP& p) {
    return p.A == nullptr && p.J != nullptr && p.JinvM != nullptr && p.cfm != nullptr && p.joints != nullptr &&
           p.m > 0;
}

void assemble_rows(const dMLCP& island, linalg::SymmetricRows& out, AssemblyBuffers& buffers,
                   const std::vector<int>& order) {
    describe_structure(island, buffers.structure);
    if (matches_pattern(buffers.pattern, out, buffers.structure, order)) {
        refill_values(island, out, buffers.pattern);
        return;
    }
    find_couplings(island, buffers, buffers.couplings);
    std::vector<linalg::LowerEntry>& lower = buffers.lower;
    lower.clear();
    std::vector<double>& diagonal = buffers.diagonal;
    diagonal.resize(static_cast<std::size_t>(island.m));
    // an exact zero is kept too: the pattern is the joints' (see assemble.h)
    // the fields written in place: a braced temporary was stored field by field and read back
    // whole, a store-to-load forwarding stall per entry (a quarter of this function's time on parkour)
    const auto keep_lower = [&lower](int i, int j, double a) {
        linalg::LowerEntry& entry = lower.emplace_back();
        entry.row = i;
        entry.col = j;
        entry.value = a;
    };
    const auto keep_diagonal = [&diagonal](int i, double a) { diagonal[i] = a; };
    assemble_joints(island, buffers.couplings, keep_lower, keep_diagonal);
    if (order.empty()) out.assign_lower(diagonal, lower);
    else out.assign_lower(diagonal, lower, order);
    remember_pattern(out, order, buffers);
}

void assemble_dense_lower(const dMLCP& island, double* A, int lda, AssemblyBuffers& /*buffers: not needed*/) {
    for (int i = 0; i < island.m; ++i) {
        double* row = A + static_cast<std::ptrdiff_t>(i) * lda;
        std::fill(row, row + i, 0.0);
    }
    // the entries as assemble_rows forms them (row_against_joint, own_rows), written in place
    const auto block = [&island, A, lda](const dMLCPJoint& p, const dMLCPJoint& q, const SharedSides& shared, bool own) {
        for (int i = p.row; i < p.row + p.m; ++i) {
            double* out = A + static_cast<std::ptrdiff_t>(i) * lda;
            const auto write = [out](int j, double a) { out[j] = a; };
            if (own) out[i] = own_rows(island, p, i, shared, write);
            else row_against_joint(island, p, i, q, q.row + q.m, shared, write);
        }
    };
    // the earlier joints that share a body, by a scan of all pairs (O(nj^2) <= O(m^2), the cost
    // of clearing A): on a small island incidence lists cost more than the scan
    for (int pj = 0; pj < island.nj; ++pj) {
        const dMLCPJoint& p = island.joints[pj];
        for (int qj = 0; qj < pj; ++qj) {
            const SharedSides shared = shared_sides(p, island.joints[qj]);
            if (shared.count > 0) block(p, island.joints[qj], shared, false);
        }
        block(p, p, shared_sides(p, p), true);
    }
}

}  // namespace ode_bpp::ode

namespace ode_bpp {

void island_matrix_lower(const dMLCP& island, std::vector<double>& A) {
    const auto m = static_cast<std::size_t>(std::max(island.m, 0));
    A.assign(m * m, 0.0);
    if (ode::has_sparse_form(island)) {
        ode::AssemblyBuffers buffers;
        ode::assemble_dense_lower(island, A.data(), island.m, buffers);
        return;
    }
    if (island.A == nullptr) return;
    for (std::size_t i = 0; i < m; ++i)
        for (std::size_t j = 0; j <= i; ++j) A[i * m + j] = island.A[i * static_cast<std::size_t>(island.skip) + j];
}

}  // namespace ode_bpp
