// libFuzzer target: bytes -> read_mlcp_bytes (with the checksum fixed up) -> solve() with
// every method and both friction modes, on small budgets. Invariants: no crash, no sanitizer
// report, no exception, x always finite, and a rejected input leaves x zero.
#include <cmath>
#include <string>

#include "fuzz_common.h"

namespace {

/// Larger problems only slow the fuzzer down; the structure it explores is all there at 48.
constexpr int kMaxRows = 48;

void check_solve(const ode_bpp::Problem& problem, ode_bpp::Method method, ode_bpp::FrictionMode friction) {
    ode_bpp::Options options;
    options.method = method;
    options.friction = friction;
    options.max_pivots = 12;
    options.pgs_iterations = 8;
    options.tuning.max_friction_rounds = 4;
    std::vector<double> x(static_cast<std::size_t>(problem.n) + 1, 0.0);
    const ode_bpp::Result r = ode_bpp::solve(problem, options, x.data());
    for (int i = 0; i < problem.n; ++i) fuzz::require(std::isfinite(x[i]));
    if (r.status == ode_bpp::Status::InvalidInput)
        for (int i = 0; i < problem.n; ++i) fuzz::require(x[i] == 0.0);
    if (r.status != ode_bpp::Status::Converged) fuzz::require(!r.message.empty());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::vector<std::uint8_t> bytes = fuzz::resealed(data, size);
    const ode_bpp::ReadResult read = ode_bpp::read_mlcp_bytes(bytes.data(), bytes.size(), "fuzz.mlcp");
    if (!read.ok || read.file.n > kMaxRows) return 0;
    const ode_bpp::Problem problem = read.file.view();
    for (const std::string& name : ode_bpp::method_names()) {
        const auto method = ode_bpp::method_from_string(name);
        fuzz::require(method.has_value());
        check_solve(problem, *method, ode_bpp::FrictionMode::Frozen);
        check_solve(problem, *method, ode_bpp::FrictionMode::Consistent);
    }
    return 0;
}
