// ode_bpp_core without ODE: this executable links the core and nothing of ODE's (checked by
// tests/shell/core_without_ode.sh). Every BPP method and PGS solve ODE-like problems; the file
// format round-trips; Dantzig, which only the ODE glue provides, is reported missing, and a
// Dantzig installed into the core's slot (baselines/dantzig.h) is the one the fallback chain uses.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "baselines/dantzig.h"
#include "ode_bpp/io.h"
#include "ode_bpp/solver.h"
#include "problems/generators.h"

namespace ode_bpp::test {
namespace {

TEST(CoreWithoutOde, EveryBppMethodAndPgsSolveAChainWithContacts) {
    const problems::OwnedProblem chain = problems::chain_mlcp(12, 4);
    for (Method m : {Method::Bpp, Method::BppSky, Method::BppDown, Method::BppChol}) {
        Options o;
        o.method = m;
        o.friction = FrictionMode::Consistent;  // the natural residual takes the bounds from x's own normals
        std::vector<double> x(static_cast<std::size_t>(chain.n));
        const Result r = solve(chain, o, x.data());
        EXPECT_EQ(r.status, Status::Converged) << to_string(m) << ": " << r.message;
        EXPECT_LT(r.residuals.relative_natural, 1e-8) << to_string(m);
    }
    // PGS's default 35 sweeps stop short on this chain (mass ratio 100); 2,000 reach the answer
    Options pgs;
    pgs.method = Method::Pgs;
    pgs.friction = FrictionMode::Consistent;
    pgs.pgs_iterations = 2000;
    std::vector<double> x(static_cast<std::size_t>(chain.n));
    const Result r = solve(chain, pgs, x.data());
    EXPECT_EQ(r.status, Status::Converged) << r.message;
    EXPECT_LT(r.residuals.relative_natural, 1e-6);
    for (double v : x) EXPECT_TRUE(std::isfinite(v));
}

TEST(CoreWithoutOde, DantzigIsReportedMissing) {
    const problems::OwnedProblem p = problems::random_boxed_mlcp(9, 3, 1, 1e3, 7);
    Options o;
    o.method = Method::Dantzig;
    std::vector<double> x(static_cast<std::size_t>(p.n), 1.0);
    const Result r = solve(p, o, x.data());
    EXPECT_EQ(r.status, Status::InvalidInput);
    EXPECT_NE(r.message.find("libode_bpp"), std::string::npos) << r.message;
}

/// A 2 x 2 matrix with a positive diagonal that is not positive definite: BPP breaks down even
/// after regularization.
problems::OwnedProblem indefinite() {
    problems::OwnedProblem p = problems::OwnedProblem::zeros("indefinite", 2);
    p.a(0, 0) = 1, p.a(1, 1) = 1, p.a(0, 1) = p.a(1, 0) = 2;  // eigenvalues 3 and -1
    p.b = {1, 1};
    return p;
}

bool unit_answer(const Problem& problem, const linalg::SymmetricRows&, std::vector<double>& x) {
    x.assign(static_cast<std::size_t>(problem.n), 0.5);
    return true;
}

TEST(CoreWithoutOde, TheFallbackChainUsesTheInstalledDantzigOrStopsWithoutOne) {
    const problems::OwnedProblem p = indefinite();
    std::vector<double> x(2, 7.0);
    Result r = solve(p, Options{}, x.data());
    EXPECT_EQ(r.status, Status::NotSpd);
    EXPECT_NE(r.message.find("no Dantzig to fall back on"), std::string::npos) << r.message;
    EXPECT_EQ(x, std::vector<double>(2, 0.0));

    baselines::install_dantzig(&unit_answer);
    r = solve(p, Options{}, x.data());
    baselines::install_dantzig(nullptr);
    EXPECT_EQ(r.status, Status::FallbackUsed);
    EXPECT_TRUE(r.fallback == Fallback::Dantzig || r.fallback == Fallback::RegularizedDantzig) << to_string(r.fallback);
    EXPECT_EQ(x, std::vector<double>(2, 0.5));
}

TEST(CoreWithoutOde, TheFileFormatRoundTrips) {
    const problems::OwnedProblem p = problems::chain_mlcp(5, 2);
    std::string error;
    const auto file = copy_problem(p, {}, nullptr, &error);
    ASSERT_TRUE(file) << error;
    std::vector<std::uint8_t> bytes;
    ASSERT_TRUE(encode_mlcp(*file, &bytes, &error)) << error;
    const ReadResult back = read_mlcp_bytes(bytes.data(), bytes.size(), "memory");
    ASSERT_TRUE(back.ok) << back.error;
    EXPECT_EQ(back.file.A, file->A);
    EXPECT_EQ(back.file.b, file->b);
    EXPECT_EQ(back.file.block_row, file->block_row);
}

}  // namespace
}  // namespace ode_bpp::test
