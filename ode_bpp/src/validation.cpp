#include "ode_bpp/validation.h"

#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Core>

#include "linalg/symmetric_rows.h"
#include "structure_rules.h"

namespace ode_bpp {

namespace {

ValidationResult invalid(const std::string& message) { return {false, message}; }

ValidationResult invalid_row(int row, const std::string& reason) {
    std::ostringstream out;
    out << "row " << row << ": " << reason;
    return invalid(out.str());
}

std::string describe(const char* name, double value) {
    std::ostringstream out;
    out << name << " (" << value << ")";
    return out.str();
}

/// n, b, lo, hi and nub: what every form of a problem has.
ValidationResult check_vector_sizes(const Problem& p) {
    if (p.n <= 0) return invalid("n = " + std::to_string(p.n) + ": the problem must have at least one row");
    if (p.b.data == nullptr || p.lo.data == nullptr || p.hi.data == nullptr) return invalid("b, lo or hi is null");
    if (p.b.stride < 1 || p.lo.stride < 1 || p.hi.stride < 1) return invalid("b, lo or hi has a stride < 1");
    if (p.nub < 0 || p.nub > p.n)
        return invalid("nub = " + std::to_string(p.nub) + " outside [0, n = " + std::to_string(p.n) + "]");
    return {};
}

ValidationResult check_sizes(const Problem& p) {
    if (p.n <= 0) return invalid("n = " + std::to_string(p.n) + ": the problem must have at least one row");
    if (p.sparse != nullptr) {
        if (p.sparse->n() != p.n)
            return invalid("the sparse A has " + std::to_string(p.sparse->n()) + " rows, n = " + std::to_string(p.n));
    } else {
        if (p.A == nullptr) return invalid("A is null");
        if (p.lda < p.n) return invalid("lda = " + std::to_string(p.lda) + " < n = " + std::to_string(p.n));
    }
    return check_vector_sizes(p);
}

ValidationResult not_finite(int i, int j) {
    return invalid_row(i, "A(" + std::to_string(i) + "," + std::to_string(j) + ") is not finite");
}

/// The cheap test of a diagonal entry that check_diagonal explains (the scans below build no
/// ValidationResult per row: on islands of a few rows that cost as much as the scan).
bool good_diagonal(double a_ii) { return std::isfinite(a_ii) && a_ii > 0; }

ValidationResult check_diagonal(int i, double a_ii) {
    if (!std::isfinite(a_ii)) return not_finite(i, i);
    if (!(a_ii > 0)) return invalid_row(i, describe("diagonal A(i,i)", a_ii) + " is not positive");
    return {};
}

/// True only where check_dense_matrix passes: each row tested whole, without a branch per entry
/// (0 * v is 0 for every finite v, NaN for an infinity or a NaN).
bool dense_matrix_passes(const Problem& p) {
    for (int i = 0; i < p.n; ++i) {
        const double* row = p.A + static_cast<std::ptrdiff_t>(i) * p.lda;
        double probe = 0;
        for (int j = 0; j < i; ++j) probe += 0.0 * row[j];
        if (!(probe == 0) || !good_diagonal(row[i])) return false;
    }
    return true;
}

ValidationResult check_dense_matrix(const Problem& p) {
    if (dense_matrix_passes(p)) return {};
    for (int i = 0; i < p.n; ++i) {
        const double* row = p.A + static_cast<std::ptrdiff_t>(i) * p.lda;
        for (int j = 0; j < i; ++j)
            if (!std::isfinite(row[j])) return not_finite(i, j);
        if (!good_diagonal(row[i])) return check_diagonal(i, row[i]);
    }
    return {};
}

ValidationResult check_matrix(const Problem& p) {
    return p.sparse != nullptr ? validate_matrix(*p.sparse) : check_dense_matrix(p);
}

bool is_friction_row(const Problem& p, int i) { return p.findex != nullptr && p.findex[i] >= 0; }

ValidationResult check_bounds(const Problem& p) {
    for (int i = 0; i < p.n; ++i) {
        if (!std::isfinite(p.b[i])) return invalid_row(i, describe("b", p.b[i]) + " is not finite");
        const double lo = p.lo[i], hi = p.hi[i];
        if (std::isnan(lo) || std::isnan(hi)) return invalid_row(i, "lo or hi is NaN");
        if (is_friction_row(p, i)) continue;  // its bounds come from mu and the normal
        if (i < p.nub) continue;              // unbounded whatever lo/hi say
        if (lo > hi) return invalid_row(i, describe("lo", lo) + " > " + describe("hi", hi));
        if (lo > 0) return invalid_row(i, describe("lo", lo) + " > 0 (ODE requires lo <= 0 <= hi)");
        if (hi < 0) return invalid_row(i, describe("hi", hi) + " < 0 (ODE requires lo <= 0 <= hi)");
    }
    return {};
}

/// structure_rules.h's findex rules (shared with the file format), then the ones that need the
/// values: no friction row inside the first nub rows, and mu = hi_i >= 0.
ValidationResult check_findex(const Problem& p) {
    if (p.findex == nullptr) return {};
    if (auto issue = ode_bpp::check_findex(p.findex, p.n)) return invalid_row(static_cast<int>(issue->index), issue->reason);
    for (int i = 0; i < p.n; ++i) {
        if (p.findex[i] < 0) continue;
        if (i < p.nub) return invalid_row(i, "friction row inside the first nub rows");
        if (!(p.hi[i] >= 0)) return invalid_row(i, describe("friction coefficient mu = hi", p.hi[i]) + " is not >= 0");
    }
    return {};
}

/// structure_rules.h's block rules (shared with the file format); bodies only need to be >= -1,
/// as a Problem does not say how many there are.
ValidationResult check_blocks(const Problem& p) {
    if (p.num_blocks < 0) return invalid("num_blocks = " + std::to_string(p.num_blocks) + " < 0");
    if (p.num_blocks == 0) return {};
    if (p.block_row == nullptr || p.block_body == nullptr) return invalid("num_blocks > 0 but block_row or block_body is null");
    if (auto issue = check_block_row(p.block_row, p.num_blocks, p.n)) return invalid(issue->reason);
    if (auto issue = check_block_body(p.block_body, p.num_blocks, std::numeric_limits<int>::max()))
        return invalid(issue->reason);
    return {};
}

/// The rules of check_findex and check_bounds for row i, as one test that names nothing.
bool row_passes(const Problem& p, int i) {
    const double lo = p.lo[i], hi = p.hi[i];
    if (!std::isfinite(p.b[i]) || std::isnan(lo) || std::isnan(hi)) return false;
    const int f = p.findex != nullptr ? p.findex[i] : -1;
    if (f != -1) return f >= 0 && f < p.n && f != i && p.findex[f] == -1 && i >= p.nub && hi >= 0;
    return i < p.nub || (lo <= hi && lo <= 0 && hi >= 0);
}

/// The rules of check_blocks, as one test that names nothing.
bool blocks_pass(const Problem& p) {
    if (p.num_blocks == 0) return true;
    if (!blocks_tile_rows(p.n, p.num_blocks, p.block_row, p.block_body)) return false;
    for (int k = 0; k < 2 * p.num_blocks; ++k)
        if (p.block_body[k] < -1 || p.block_body[k] == std::numeric_limits<int>::max()) return false;
    return true;
}

/// The tests of check_sizes (with_matrix) or check_vector_sizes, as one test that names nothing.
bool sizes_pass(const Problem& p, bool with_matrix) {
    if (p.n <= 0 || p.b.data == nullptr || p.lo.data == nullptr || p.hi.data == nullptr) return false;
    if (p.b.stride < 1 || p.lo.stride < 1 || p.hi.stride < 1 || p.nub < 0 || p.nub > p.n) return false;
    if (!with_matrix) return true;
    return p.sparse != nullptr ? p.sparse->n() == p.n : p.A != nullptr && p.lda >= p.n;
}

/// True only where check_sizes, check_findex, check_bounds and check_blocks all pass, in one
/// pass that builds no result or message: on islands of a few rows the four checks' results
/// cost a tenth of the solve. A false sends the caller to those checks, which name the defect.
bool structure_passes(const Problem& p, bool with_matrix) {
    if (!sizes_pass(p, with_matrix)) return false;
    for (int i = 0; i < p.n; ++i)
        if (!row_passes(p, i)) return false;
    return blocks_pass(p);
}

/// validate_structure, with A's presence among its checks or not.
ValidationResult structure_verdict(const Problem& problem, bool with_matrix) {
    if (structure_passes(problem, with_matrix)) return {};
    for (auto check : {with_matrix ? check_sizes : check_vector_sizes, check_findex, check_bounds, check_blocks}) {
        ValidationResult r = check(problem);
        if (!r.valid) return r;
    }
    return {};
}

}  // namespace

ValidationResult validate_structure(const Problem& problem) { return structure_verdict(problem, true); }

ValidationResult validate_rows(const Problem& problem) { return structure_verdict(problem, false); }

namespace {

/// True when every stored entry is finite and every diagonal entry positive: one pass over the
/// values as stored, without the built order (both triangles hold each entry, so an entry is
/// finite exactly where its mirror is). 0 * a is 0 for finite a and NaN otherwise, so the sum is 0
/// only when every entry is finite; Eigen sums it in vector registers, with no branch or chain
/// of dependent additions per entry.
bool rows_pass(const linalg::SymmetricRows& A) {
    const Eigen::Map<const Eigen::ArrayXd> values(A.values(), A.off_diagonal_entries());
    if (!((values * 0.0).sum() == 0)) return false;
    for (int i = 0; i < A.n(); ++i)
        if (!good_diagonal(A.diag(i))) return false;
    return true;
}

}  // namespace

// A valid matrix passes rows_pass. Otherwise row by row as stored, each row's entries left of the
// diagonal in the order the matrix was built in (a row's entries come by increasing built column,
// symmetric_rows.h), then the diagonal; the message names the row and column as built
// (SymmetricRows::built_row): the caller's, whatever order the rows are stored in.
ValidationResult validate_matrix(const linalg::SymmetricRows& A) {
    if (rows_pass(A)) return {};
    for (int i = 0; i < A.n(); ++i) {
        const int row = A.built_row(i);
        for (int k = A.row_begin(i); k < A.row_end(i); ++k) {
            const int col = A.built_row(A.col(k));
            if (col > row) break;
            if (!std::isfinite(A.val(k))) return not_finite(row, col);
        }
        if (!good_diagonal(A.diag(i))) return check_diagonal(row, A.diag(i));
    }
    return {};
}

ValidationResult validate_matrix(const Problem& problem) { return check_matrix(problem); }

ValidationResult validate(const Problem& problem) {
    ValidationResult r = check_sizes(problem);
    if (r.valid) r = check_findex(problem);
    if (r.valid) r = check_bounds(problem);
    if (r.valid) r = check_matrix(problem);
    if (r.valid) r = check_blocks(problem);
    return r;
}

ValidationResult validate_warm_start(const Problem& problem, const std::vector<RowState>& warm_start) {
    if (warm_start.empty() || static_cast<int>(warm_start.size()) == problem.n) return {};
    return invalid("warm start has " + std::to_string(warm_start.size()) + " entries, n = " + std::to_string(problem.n));
}

}  // namespace ode_bpp
