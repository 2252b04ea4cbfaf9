// Updates of a few consecutive entries as straight-line code, for the short columns of a sparse
// island's envelope (the crane's hold 5 entries on average). A loop over them is vectorized by the
// compiler, and its alias checks and remainder then cost more than the arithmetic: on the crane's
// 420-row island the factorization spent 320 instructions per column. Each entry is updated
// alone, in the same operation as the loop's, so the bits are the loop's.
#pragma once

namespace ode_bpp::linalg {

/// Longest run the helpers below take.
constexpr int kShortRun = 8;

/// y[0 .. length) -= a * x[0 .. length), 0 <= length <= kShortRun. y and x do not overlap.
[[gnu::always_inline]] inline void subtract_multiple_short(double* y, const double* x, double a, int length) {
    switch (length) {
        case 8: y[7] -= a * x[7]; [[fallthrough]];
        case 7: y[6] -= a * x[6]; [[fallthrough]];
        case 6: y[5] -= a * x[5]; [[fallthrough]];
        case 5: y[4] -= a * x[4]; [[fallthrough]];
        case 4: y[3] -= a * x[3]; [[fallthrough]];
        case 3: y[2] -= a * x[2]; [[fallthrough]];
        case 2: y[1] -= a * x[1]; [[fallthrough]];
        case 1: y[0] -= a * x[0]; [[fallthrough]];
        default: break;
    }
}

/// y[0 .. length) *= a, 0 <= length <= kShortRun.
[[gnu::always_inline]] inline void scale_short(double* y, double a, int length) {
    switch (length) {
        case 8: y[7] *= a; [[fallthrough]];
        case 7: y[6] *= a; [[fallthrough]];
        case 6: y[5] *= a; [[fallthrough]];
        case 5: y[4] *= a; [[fallthrough]];
        case 4: y[3] *= a; [[fallthrough]];
        case 3: y[2] *= a; [[fallthrough]];
        case 2: y[1] *= a; [[fallthrough]];
        case 1: y[0] *= a; [[fallthrough]];
        default: break;
    }
}

}  // namespace ode_bpp::linalg
