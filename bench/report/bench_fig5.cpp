// bench_fig5: the paper's Fig. 5 for one island. The sparsity pattern of A before and after
// the Cuthill-McKee ordering (Sec. 3.4, ordering/order_rows.h, on the constraint graph when the
// file carries joint blocks), and the skyline (envelope) each order gives the factor.
//
//   bench_fig5 FILE.mlcp OUT_PREFIX
//
// Writes, in the index space named by the file (original order, or the permuted order
// perm[new] = old):
//   OUT_PREFIX-before.dat, -after.dat: "column row" of every non-zero of the full symmetric A;
//   OUT_PREFIX-sky-before.dat, -sky-after.dat: "row first" with first = the first column of the
//     row's envelope (the lower triangle's first non-zero), the skyline's left edge;
// and prints one CSV line on stdout:
//   n,nonzeros,envelope_original,envelope_cm,envelope_rcm,bandwidth_original,bandwidth_cm
// with envelope = stored entries of the lower skyline (diagonal included), bandwidth = max(i - first_i).
#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "linalg/skyline.h"
#include "ode_bpp/io.h"
#include "ordering/ordering.h"

namespace {

using ode_bpp::MlcpFile;

/// A(perm[i], perm[j]) of the file's full symmetric A (lda = n); perm[new] = old.
double permuted(const MlcpFile& file, const std::vector<int>& perm, int i, int j) {
    return file.A[static_cast<std::size_t>(perm[i]) * file.n + perm[j]];
}

/// first[i] = smallest j <= i with A(i, j) != 0 in the order perm (the row profile).
std::vector<int> row_profile(const MlcpFile& file, const std::vector<int>& perm) {
    std::vector<int> first(static_cast<std::size_t>(file.n));
    for (int i = 0; i < file.n; ++i) {
        int j = 0;
        while (j < i && permuted(file, perm, i, j) == 0.0) ++j;
        first[i] = j;
    }
    return first;
}

std::ptrdiff_t envelope_size(const std::vector<int>& first) {
    return ode_bpp::linalg::SkylineShape::from_row_profile(first).size();
}

int bandwidth(const std::vector<int>& first) {
    int width = 0;
    for (int i = 0; i < static_cast<int>(first.size()); ++i) width = std::max(width, i - first[i]);
    return width;
}

std::vector<int> ordering(const MlcpFile& file, ode_bpp::ordering::OrderingKind kind) {
    return ode_bpp::ordering::order_rows(file.n, file.A.data(), file.n, file.num_blocks(),
                                         file.block_row.empty() ? nullptr : file.block_row.data(),
                                         file.block_body.empty() ? nullptr : file.block_body.data(), kind, nullptr);
}

/// Writes the pattern and the skyline edge of A in the order perm; false when a file fails.
bool write_order(const MlcpFile& file, const std::vector<int>& perm, const std::string& prefix, const std::string& tag) {
    std::ofstream pattern(prefix + "-" + tag + ".dat"), sky(prefix + "-sky-" + tag + ".dat");
    for (int i = 0; i < file.n; ++i)
        for (int j = 0; j < file.n; ++j)
            if (permuted(file, perm, i, j) != 0.0) pattern << j << ' ' << i << '\n';
    const std::vector<int> first = row_profile(file, perm);
    for (int i = 0; i < file.n; ++i) sky << i << ' ' << first[i] << '\n';
    return static_cast<bool>(pattern) && static_cast<bool>(sky);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::cerr << "usage: bench_fig5 FILE.mlcp OUT_PREFIX\n";
        return 2;
    }
    const ode_bpp::ReadResult read = ode_bpp::read_mlcp(argv[1]);
    if (!read.ok) {
        std::cerr << "bench_fig5: " << read.error << "\n";
        return 1;
    }
    const MlcpFile& file = read.file;
    std::vector<int> identity(static_cast<std::size_t>(file.n));
    for (int i = 0; i < file.n; ++i) identity[i] = i;
    const std::vector<int> cm = ordering(file, ode_bpp::ordering::OrderingKind::CuthillMcKee);
    const std::vector<int> rcm = ordering(file, ode_bpp::ordering::OrderingKind::ReverseCuthillMcKee);
    if (!write_order(file, identity, argv[2], "before") || !write_order(file, cm, argv[2], "after")) {
        std::cerr << "bench_fig5: cannot write " << argv[2] << "-*.dat\n";
        return 1;
    }
    const std::vector<int> first_original = row_profile(file, identity), first_cm = row_profile(file, cm);
    const long nonzeros = std::count_if(file.A.begin(), file.A.end(), [](double a) { return a != 0.0; });
    std::cout << file.n << ',' << nonzeros << ',' << envelope_size(first_original) << ',' << envelope_size(first_cm) << ','
              << envelope_size(row_profile(file, rcm)) << ',' << bandwidth(first_original) << ',' << bandwidth(first_cm)
              << '\n';
    return 0;
}
