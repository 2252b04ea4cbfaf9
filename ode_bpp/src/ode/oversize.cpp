#include "ode/oversize.h"

#include "linalg/skyline.h"
#include "ode/assemble.h"
#include "ode/island_view.h"
#include "ode/jacobian_pgs.h"
#include "ordering/graph.h"
#include "ordering/order_rows.h"
#include "ordering/ordering_choice.h"
#include "pivoting/bpp_driver.h"

namespace ode_bpp::ode {

namespace {

/// The envelope of the solve's factor (pivoting::planned_factor_entries' count on the assembled
/// A), in `order`, or in the joint graph's order, which `order` then becomes.
std::int64_t factor_entries(const Problem& problem, const Options& options, std::vector<int>& order) {
    const Method strategy = pivoting::strategy_of(problem, options);
    if (!pivoting::strategy_orders(strategy)) return pivoting::dense_triangle_entries(problem.n);
    if (!ordering::is_permutation(order, problem.n)) order = ordering::block_ordering(strategy, problem);
    const std::vector<int> first =
        ordering::block_row_profile(problem.num_blocks, problem.block_row, problem.block_body, order);
    return static_cast<std::int64_t>(linalg::SkylineShape::size_of_row_profile(first));
}

}  // namespace

Oversize oversize(const dMLCP& island, const Problem& problem, const Options& options, std::vector<int>& order,
                  std::vector<std::int64_t>& rows_on_body) {
    if (!has_sparse_form(island) || !pivoting::factor_may_be_too_large(island.m, options)) return {};
    if (!structure_defect(island).empty()) return {};
    if (const std::int64_t entries = coupled_entries_lower_bound(island, rows_on_body);
        entries > options.max_factor_entries)
        return {Oversize::Measure::MatrixEntries, entries};
    if (const std::int64_t entries = factor_entries(problem, options, order); entries > options.max_factor_entries)
        return {Oversize::Measure::FactorEntries, entries};
    return {};
}

}  // namespace ode_bpp::ode
