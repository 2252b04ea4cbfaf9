#include "ordering/ordering_choice.h"

#include <algorithm>
#include <numeric>

#include "linalg/cost_model.h"
#include "linalg/skyline.h"
#include "ordering/graph.h"
#include "ordering/order_rows.h"
#include "linalg/step_cost.h"

namespace ode_bpp::ordering {

using linalg::deletion_price;
using linalg::kRefactorUnit;
using linalg::refactor_price;

namespace {

std::vector<int> identity(int n) {
    std::vector<int> perm(static_cast<std::size_t>(n));
    std::iota(perm.begin(), perm.end(), 0);
    return perm;
}

/// Both Cuthill-McKee numberings from one ordering of the graph; the identity for either that is
/// not a permutation.
ordering::OrderPair order_pair(const Problem& p, const linalg::SymmetricRows& A) {
    const auto row_graph = [&A] { return ordering::graph_from_rows(A); };
    ordering::OrderPair pair = ordering::cuthill_mckee_pair(p.n, row_graph, p.num_blocks, p.block_row, p.block_body);
    if (!ordering::is_permutation(pair.forward, p.n)) pair.forward = identity(p.n);
    if (!ordering::is_permutation(pair.reverse, p.n)) pair.reverse = identity(p.n);
    return pair;
}

/// Rows tight in the warm start (original space), or empty when none is.
std::vector<char> warm_tight(const std::vector<RowState>& warm_start) {
    std::vector<char> tight(warm_start.size(), 0);
    bool any = false;
    for (std::size_t i = 0; i < warm_start.size(); ++i) {
        tight[i] = warm_start[i] != RowState::Free;
        any = any || tight[i];
    }
    return any ? tight : std::vector<char>{};
}

/// Instructions that numbering the graph costs per vertex and per edge: the two Cuthill-McKee
/// numberings and their envelope comparison (callgrind, ODE's 6-row demo_motors island: ~6k
/// instructions for 6 vertices and 15 edges), in units comparable to CostModel's multiply-adds.
constexpr double kOrderingCostPerEntry = 300;

/// The cheaper of deleting the rows flagged in `tight` (original space) from L0 and refactoring
/// from the first of them, in the shape of perm; 0 when none is flagged.
double step_price(const linalg::CostModel& cost, const linalg::SkylineShape& shape, const std::vector<int>& perm,
                  const std::vector<char>& tight) {
    std::vector<int> tight_rows;
    if (!tight.empty())
        for (int i = 0; i < shape.n; ++i)
            if (tight[perm[i]]) tight_rows.push_back(i);
    if (tight_rows.empty()) return 0;
    const int copy_from = shape.first_column_holding(tight_rows.front());
    return std::min(deletion_price(cost, tight_rows, copy_from), refactor_price(cost, tight_rows, copy_from));
}

/// The warm start's tight rows with every friction row added (FirstSolve::FrictionRowsTight),
/// or empty when the first solve holds nothing more than the warm start.
std::vector<char> first_solve_tight(const Problem& p, const std::vector<char>& warm, FirstSolve first) {
    if (first != FirstSolve::FrictionRowsTight || p.findex == nullptr) return {};
    std::vector<char> tight = warm.empty() ? std::vector<char>(static_cast<std::size_t>(p.n), 0) : warm;
    bool any = false;
    for (int i = 0; i < p.n; ++i)
        if (p.findex[i] >= 0) {
            tight[i] = 1;
            any = true;
        }
    return any ? tight : std::vector<char>{};
}

/// warm_solve_price in the shape of A under perm (from A.row_profile_under(perm)).
double price_in_shape(const linalg::SkylineShape& shape, const std::vector<int>& perm, const std::vector<char>& tight,
                      const std::vector<char>& first_tight) {
    const linalg::CostModel cost(shape);
    const double factor = kRefactorUnit * cost.refactor_cost(0);
    const double step = step_price(cost, shape, perm, tight);
    const double first = first_tight.empty() ? step : step_price(cost, shape, perm, first_tight);
    return factor + first + (kStepsPerWarmSolve - 1) * step;
}

/// True when the rows `moved` (original space) alone, where perm puts them, make the factor cost
/// at least `price` (flagged_rows_factor_bound, summed no further than that): the candidate
/// cannot win and is not priced in full.
bool priced_out_by_moved_rows(const linalg::SymmetricRows& A, const std::vector<int>& perm,
                              const std::vector<char>& moved, double price) {
    return kRefactorUnit * flagged_rows_factor_bound(A, perm, moved, price / kRefactorUnit) >= price;
}

/// The normal rows of p's friction rows flagged in `rows` (findex targets), or empty when none is.
std::vector<char> normals_of(const Problem& p, const std::vector<char>& rows) {
    if (p.findex == nullptr) return {};
    std::vector<char> normals(static_cast<std::size_t>(p.n), 0);
    bool any = false;
    for (int i = 0; i < p.n; ++i)
        if (rows[i] && p.findex[i] >= 0 && !rows[p.findex[i]]) {
            normals[p.findex[i]] = 1;
            any = true;
        }
    return any ? normals : std::vector<char>{};
}

/// The caller's order with the rows of rank 1, then those of rank 2, moved last, each group in
/// its order: perm[new] = old.
std::vector<int> ranked_order(const std::vector<unsigned char>& rank) {
    std::vector<int> perm = identity(static_cast<int>(rank.size()));
    std::stable_sort(perm.begin(), perm.end(), [&rank](int a, int b) { return rank[a] < rank[b]; });
    return perm;
}

/// The caller's own order, that order with the first solve's tight rows moved last, or with the
/// normals of its friction rows moved last just before them, whichever prices lowest
/// (warm_solve_price): numbering no graph, each candidate costs O(n + its moved rows' entries),
/// its profile read off the caller's (SymmetricRows::row_profile_ranked).
/// ODE lists a contact's friction rows beside its normal; Frozen friction's first solve holds them
/// at 0 and its second frees them, so with them last one factor of the leading rows serves both.
/// A normal left among the joints keeps its body's columns reaching from there to the friction
/// rows at the end: where the joints are one dense block (parkour's hull), moving the normals
/// too saves more than their longer rows cost, on a chain not (docs/tuning.md).
std::vector<int> caller_order(const Problem& problem, const linalg::SymmetricRows& A,
                              const std::vector<RowState>& warm_start, FirstSolve first) {
    std::vector<int> best = identity(problem.n);
    const std::vector<char> tight = warm_tight(warm_start);
    const std::vector<char> first_tight = first_solve_tight(problem, tight, first);
    if (first_tight.empty()) return best;
    const std::vector<int> profile = A.row_profile();
    double best_price = price_in_shape(linalg::SkylineShape::from_row_profile(profile), best, tight, first_tight);
    std::vector<int> tried;  // the candidate priced last
    const auto consider = [&](const std::vector<unsigned char>& rank) {
        std::vector<int> candidate = ranked_order(rank);
        if (candidate == best || candidate == tried) return;  // ODE's contacts after all joints: one order
        tried = candidate;
        // where the moved rows alone make its factor dearer (a box stack's contacts: 100 times), a
        // few of them say so without pricing the whole shape
        if (priced_out_by_moved_rows(A, candidate, first_tight, best_price)) return;
        const linalg::SkylineShape shape =
            linalg::SkylineShape::from_row_profile(A.row_profile_ranked(candidate, rank, profile));
        const double price = price_in_shape(shape, candidate, tight, first_tight);
        if (price < best_price) {
            best_price = price;
            best = std::move(candidate);
        }
    };
    std::vector<unsigned char> rank(first_tight.begin(), first_tight.end());
    consider(rank);
    const std::vector<char> normals = normals_of(problem, first_tight);
    if (normals.empty()) return best;
    for (int i = 0; i < problem.n; ++i) rank[i] = first_tight[i] ? 2 : normals[i] ? 1 : 0;
    consider(rank);
    return best;
}

}  // namespace

// small islands (every one of up to ~20 rows) and dense ones, where the orderings made bpp slower
// than a factorization in the caller's order
bool ordering_cannot_pay(const linalg::SymmetricRows& A) {
    const double identity = linalg::full_refactor_cost(linalg::SkylineShape::from_row_profile(A.row_profile()));
    const double nnz = A.n() > 0 ? A.row_end(A.n() - 1) : 0;
    return kStepsPerWarmSolve * identity <= kOrderingCostPerEntry * (A.n() + nnz);
}

double warm_solve_price(const linalg::SymmetricRows& A, const std::vector<int>& perm, const std::vector<char>& tight,
                        const std::vector<char>& first_tight) {
    return price_in_shape(linalg::SkylineShape::from_row_profile(A.row_profile_under(perm)), perm, tight, first_tight);
}

double flagged_rows_factor_bound(const linalg::SymmetricRows& A, const std::vector<int>& perm,
                                 const std::vector<char>& rows, double limit) {
    // row i of width w = i - first[i] + 1 is one of the rows r summed over for every pair
    // first[i] <= j <= k <= i: column j reaches row i (sky[j] >= i), so it holds w (w + 1) / 2
    // of refactor_cost(0)'s terms
    const std::vector<int> to_new = linalg::inverse_permutation(perm);
    double bound = 0;
    for (int i = 0; i < A.n(); ++i) {
        if (!rows[perm[i]]) continue;
        const double width = i - A.first_under(perm[i], to_new) + 1;
        bound += width * (width + 1) / 2;
        if (bound >= limit) break;
    }
    return bound;
}

std::vector<int> block_ordering(Method method, const Problem& problem) {
    if (method != Method::Bpp && method != Method::BppSky) return identity(problem.n);
    ordering::OrderPair pair =
        ordering::cuthill_mckee_pair(problem.n, nullptr, problem.num_blocks, problem.block_row, problem.block_body);
    return std::move(method == Method::BppSky ? pair.forward : pair.reverse);
}

std::vector<int> choose_ordering(Method method, const Problem& problem, const linalg::SymmetricRows& A,
                                 const std::vector<RowState>& warm_start, FirstSolve first, bool price_reorderings) {
    if (method == Method::BppSky) return order_pair(problem, A).forward;
    if (method != Method::Bpp) return identity(problem.n);
    if (ordering_cannot_pay(A)) return caller_order(problem, A, warm_start, first);
    const ordering::OrderPair pair = order_pair(problem, A);
    const std::vector<int>& cm = pair.forward;
    const std::vector<int>& rcm = pair.reverse;
    // reverse Cuthill-McKee (Sec. 3.4): reversing never enlarges the envelope (Liu & Sherman;
    // numbered by blocks too: on the 6,200 islands of the eight corpora never larger, equal on a
    // fifth), so Cuthill-McKee's own profile is not computed to compare
    std::vector<int> best = rcm;
    if (!price_reorderings) return best;
    const std::vector<char> tight = warm_tight(warm_start);
    const std::vector<char> first_tight = first_solve_tight(problem, tight, first);
    if (tight.empty() && first_tight.empty()) return best;
    // Moving likely-tight rows last makes deleting them cheap but can widen the envelope a lot
    // (contact rows couple bodies spread along the order): keep whichever prices lower.
    double best_price = warm_solve_price(A, best, tight, first_tight);
    for (const std::vector<char>* moved : {&tight, &first_tight}) {
        if (moved->empty()) continue;
        for (const std::vector<int>* base : {&cm, &rcm}) {
            std::vector<int> candidate = *base;
            ordering::move_flagged_last(candidate, *moved);
            // its factorization alone, price_in_shape's first term, already prices most candidates
            // out (on the winch and the forwarder, 100 % and 87 %): bound it from the moved rows,
            // then from the whole shape, before building a cost model
            if (priced_out_by_moved_rows(A, candidate, *moved, best_price)) continue;
            const linalg::SkylineShape shape = linalg::SkylineShape::from_row_profile(A.row_profile_under(candidate));
            if (kRefactorUnit * linalg::full_refactor_cost(shape) >= best_price) continue;
            const double price = price_in_shape(shape, candidate, tight, first_tight);
            if (price < best_price) {
                best_price = price;
                best = std::move(candidate);
            }
        }
    }
    return best;
}

}  // namespace ode_bpp::ordering
