// The paper's Fig. 4: on random dense SPD matrices with p % of the rows tight, the speed-up of
// copying L0 and deleting the tight rows (Alg. 2) over refactoring A_FF.
//
//   BM_Fig4/<m>/<p>   the benchmark's time is the deletion path: restore L0 (columns >= the first
//                     tight row, and the tight rows), then skyline_delete_row for each tight row.
//                     Each iteration also refactors A_FF with Eigen's dense LLT (gathering A_FF
//                     included) and with skyline_cholesky from the first tight column (removed set,
//                     L0's leading columns reused). Counters: their medians in µs and
//                     speedup_vs_eigen, speedup_vs_refactor (> 1: deleting is faster).
// The three run interleaved in every iteration, so that their ratios are measured under the
// same machine load (NOTES: time comparisons only hold as ratios within one run).
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

/// Fig. 4: the three ways to get L_FF, interleaved in every iteration so that their ratio is
/// measured under the same machine load. The benchmark's own time is the deletion path's.
void figure4(benchmark::State& state, int m, int percent) {
    const Fixture& f = fixture(true, true, m);
    std::mt19937 rng(7 * m + percent);
    std::vector<int> indices(static_cast<std::size_t>(m));
    for (int k = 0; k < m; ++k) indices[k] = k;
    std::shuffle(indices.begin(), indices.end(), rng);
    std::vector<int> tight(indices.begin(), indices.begin() + std::max(1, m * percent / 100));
    std::sort(tight.begin(), tight.end());
    std::vector<char> removed(static_cast<std::size_t>(m), 0);
    for (int t : tight) removed[t] = 1;
    std::vector<int> kept;
    for (int k = 0; k < m; ++k)
        if (!removed[k]) kept.push_back(k);
    const MatrixXd A = to_eigen(f.A, m);
    const int first_tight = tight.front();

    SkylineMatrix L = f.L0, R = f.L0;
    std::vector<double> work(static_cast<std::size_t>(m));
    MatrixXd A_FF(kept.size(), kept.size());
    Eigen::LLT<MatrixXd> llt(static_cast<Eigen::Index>(kept.size()));
    std::vector<double> t_delete, t_eigen, t_refactor;
    for (auto _ : state) {
        auto start = std::chrono::steady_clock::now();
        L.copy_tail_from(f.L0, first_tight);
        L.copy_rows_from(f.L0, tight, first_tight);
        for (int t : tight) ode_bpp::linalg::skyline_delete_row(L, t, work);
        benchmark::ClobberMemory();
        t_delete.push_back(seconds_since(start));
        state.SetIterationTime(t_delete.back());

        start = std::chrono::steady_clock::now();
        for (std::size_t b = 0; b < kept.size(); ++b)
            for (std::size_t a = b; a < kept.size(); ++a) A_FF(a, b) = A(kept[a], kept[b]);
        llt.compute(A_FF);
        benchmark::DoNotOptimize(llt.matrixLLT().data());
        t_eigen.push_back(seconds_since(start));

        start = std::chrono::steady_clock::now();
        R.copy_tail_from(f.A_lower, first_tight);
        R.copy_rows_from(f.L0, tight, first_tight);
        benchmark::DoNotOptimize(ode_bpp::linalg::skyline_cholesky(R, first_tight, removed));
        benchmark::ClobberMemory();
        t_refactor.push_back(seconds_since(start));
    }
    const double d = median(t_delete), e = median(t_eigen), r = median(t_refactor);
    state.counters["delete_us"] = 1e6 * d;
    state.counters["eigen_llt_us"] = 1e6 * e;
    state.counters["refactor_us"] = 1e6 * r;
    state.counters["speedup_vs_eigen"] = e / d;
    state.counters["speedup_vs_refactor"] = r / d;
}

/// Each Fig. 4 iteration also runs both refactorizations (about m³/3 flops), so the iteration
/// count is fixed (about 2e9 / m³, at least 5) rather than grown until the deletion path alone
/// has run for the minimum time; this keeps the whole figure near half a minute.
int figure4_iterations(int m) {
    const double per_cube = 2e9 / (static_cast<double>(m) * m * m);
    return static_cast<int>(std::clamp(per_cube, 5.0, 1000.0));
}

void register_all() {
    for (int m : kSizes)
        for (int p : kTightPercent)
            benchmark::RegisterBenchmark(("BM_Fig4/" + std::to_string(m) + "/" + std::to_string(p)).c_str(), figure4, m, p)
                ->Iterations(figure4_iterations(m))
                ->UseManualTime()
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
