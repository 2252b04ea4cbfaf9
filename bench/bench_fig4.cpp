// The paper's Fig. 4: on random dense SPD matrices with p % of the rows tight, the speed-up of
// copying L0 and deleting the tight rows (Alg. 2) over refactoring A_FF.
//
//   BM_Fig4/<m>/<p>   every iteration gets L_FF three ways, each timed on its own:
//                     delete: restore L0 (columns >= the first tight row, and the tight rows),
//                       then skyline_delete_row for each tight row;
//                     eigen_llt: gather A_FF and factor it with Eigen's dense LLT;
//                     refactor: skyline_cholesky from the first tight column with the tight rows
//                       removed (L0's leading columns reused).
//                     Counters: the medians delete_us, eigen_llt_us, refactor_us and the
//                     speed-ups speedup_vs_eigen, speedup_vs_refactor (> 1: deleting is faster).
//                     The benchmark's own time is the sum of the three.
// The three run interleaved in every iteration, so that their ratios are measured under the
// same machine load (time comparisons only hold as ratios within one run).
// For a table: --benchmark_out=fig4.csv --benchmark_out_format=csv
#include <benchmark/benchmark.h>

#include <Eigen/Cholesky>
#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <random>
#include <string>
#include <vector>

#include "kernel_fixtures.h"
#include "linalg/row_delete.h"
#include "linalg/skyline.h"
#include "linalg/skyline_cholesky.h"

namespace {

using namespace ode_bpp::bench;

const int kTightPercent[] = {1, 2, 5, 10, 15, 20, 30};

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

/// One random choice of tight rows (ascending), as flags, and the kept rows, of n rows.
struct TightSet {
    std::vector<int> rows;
    std::vector<char> flags;
    std::vector<int> kept;
    int n = 0;
    /// The first tight row, n when there is none.
    int first() const { return rows.empty() ? n : rows.front(); }
};

TightSet random_tight_set(int m, int percent, std::mt19937& rng) {
    std::vector<int> indices(static_cast<std::size_t>(m));
    for (int k = 0; k < m; ++k) indices[k] = k;
    std::shuffle(indices.begin(), indices.end(), rng);
    TightSet set;
    set.n = m;
    set.rows.assign(indices.begin(), indices.begin() + std::max(1, m * percent / 100));
    std::sort(set.rows.begin(), set.rows.end());
    set.flags.assign(static_cast<std::size_t>(m), 0);
    for (int t : set.rows) set.flags[t] = 1;
    for (int k = 0; k < m; ++k)
        if (!set.flags[k]) set.kept.push_back(k);
    return set;
}

/// Columns [from, to) of source into L (same shape).
void copy_columns(SkylineMatrix& L, const SkylineMatrix& source, int from, int to) {
    if (from >= to) return;
    const auto& colptr = L.shape().colptr;
    std::copy(source.values().begin() + colptr[from], source.values().begin() + colptr[to],
              L.values().begin() + colptr[from]);
}

constexpr int kTightSets = 16;

/// Fig. 4: the three ways to get L_FF, interleaved in every iteration so that their ratios are
/// measured under the same machine load. Iterations cycle through kTightSets random tight sets;
/// each path first undoes what the previous iteration wrote, as the pivoting loop must.
void figure4(benchmark::State& state, int m, int percent) {
    const Fixture& f = fixture(true, true, m);
    std::mt19937 rng(7 * m + percent);
    std::vector<TightSet> sets;
    for (int s = 0; s < kTightSets; ++s) sets.push_back(random_tight_set(m, percent, rng));
    const MatrixXd A = to_eigen(f.A, m);
    const std::size_t kept = sets.front().kept.size();

    SkylineMatrix L = f.L0, R = f.L0;
    std::vector<double> work(static_cast<std::size_t>(m));
    MatrixXd A_FF(kept, kept);
    Eigen::LLT<MatrixXd> llt(static_cast<Eigen::Index>(kept));
    const TightSet none{{}, {}, {}, m};  // before the first iteration: L and R hold L0
    const TightSet* previous = &none;
    std::vector<double> t_delete, t_eigen, t_refactor;
    for (auto _ : state) {
        const TightSet& set = sets[t_delete.size() % sets.size()];
        const int restore_from = std::min(previous->first(), set.first());

        auto start = std::chrono::steady_clock::now();
        L.copy_tail_from(f.L0, restore_from);
        L.copy_rows_from(f.L0, previous->rows, restore_from);
        for (int t : set.rows) ode_bpp::linalg::skyline_delete_row(L, t, work);
        benchmark::ClobberMemory();
        t_delete.push_back(seconds_since(start));

        start = std::chrono::steady_clock::now();
        for (std::size_t b = 0; b < kept; ++b)
            for (std::size_t a = b; a < kept; ++a) A_FF(a, b) = A(set.kept[a], set.kept[b]);
        llt.compute(A_FF);
        benchmark::DoNotOptimize(llt.matrixLLT().data());
        t_eigen.push_back(seconds_since(start));

        start = std::chrono::steady_clock::now();
        copy_columns(R, f.L0, restore_from, set.first());
        R.copy_tail_from(f.A_lower, set.first());
        R.copy_rows_from(f.L0, previous->rows, restore_from);
        benchmark::DoNotOptimize(ode_bpp::linalg::skyline_cholesky(R, set.first(), set.flags));
        benchmark::ClobberMemory();
        t_refactor.push_back(seconds_since(start));
        previous = &set;
    }
    const double d = median(t_delete), e = median(t_eigen), r = median(t_refactor);
    state.counters["delete_us"] = 1e6 * d;
    state.counters["eigen_llt_us"] = 1e6 * e;
    state.counters["refactor_us"] = 1e6 * r;
    state.counters["speedup_vs_eigen"] = e / d;
    state.counters["speedup_vs_refactor"] = r / d;
}

void register_all() {
    for (int m : kSizes)
        for (int p : kTightPercent)
            benchmark::RegisterBenchmark(("BM_Fig4/" + std::to_string(m) + "/" + std::to_string(p)).c_str(), figure4, m, p)
                ->Unit(benchmark::kMicrosecond);
}

}  // namespace

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    register_all();
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
