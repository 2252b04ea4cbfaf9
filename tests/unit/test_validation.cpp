// validate() and solve() on malformed problems: InvalidInput, a message naming the defect,
// x zeroed and finite, no crash.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "linalg/symmetric_rows.h"
#include "ode_bpp/solver.h"
#include "ode_bpp/validation.h"
#include "problems/generators.h"
#include "problems/named.h"

namespace ode_bpp {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

problems::OwnedProblem good_problem() { return problems::random_boxed_mlcp(9, 1, 2, 1e3, 7); }

/// Runs every method on p and checks the invalid-input contract; returns the message.
std::string expect_invalid(const Problem& p) {
    const ValidationResult v = validate(p);
    EXPECT_FALSE(v.valid);
    EXPECT_FALSE(v.message.empty());
    for (const std::string& name : method_names()) {
        Options o;
        o.method = *method_from_string(name);
        std::vector<double> x(static_cast<std::size_t>(std::max(p.n, 1)) + 4, 123.0);
        const Result r = solve(p, o, x.data());
        EXPECT_EQ(r.status, Status::InvalidInput) << name;
        EXPECT_EQ(r.message, v.message) << name;
        EXPECT_FALSE(is_usable(r.status));
        for (int i = 0; i < p.n; ++i) EXPECT_EQ(x[i], 0.0) << name << " row " << i;
        for (std::size_t i = static_cast<std::size_t>(std::max(p.n, 0)); i < x.size(); ++i)
            EXPECT_EQ(x[i], 123.0) << "wrote past n";
    }
    return v.message;
}

TEST(Validation, GeneratedProblemsAreValid) {
    EXPECT_TRUE(validate(good_problem()).valid);
    EXPECT_TRUE(validate(problems::chain_mlcp(5, 3)).valid);
    EXPECT_TRUE(validate(problems::dantzig_friction_3x3()).valid);
}

TEST(Validation, NaNInLowerTriangleNamesTheEntry) {
    auto p = good_problem();
    p.a(5, 2) = kNaN;
    EXPECT_NE(expect_invalid(p).find("A(5,2)"), std::string::npos);
}

TEST(Validation, InfInAIsRejected) {
    auto p = good_problem();
    p.a(3, 3) = kInf;
    EXPECT_NE(expect_invalid(p).find("row 3"), std::string::npos);
}

TEST(Validation, RowsStoredInAnotherOrderAreNamedAsTheCallerBuiltThem) {
    // built rows 0, 1, 2 stored as 2, 0, 1: stored row 2 (built row 1) holds A(1,0), then the
    // NaN A(2,1) among its entries right of the diagonal as built
    std::vector<double> diagonal{1.0, 1.0, 1.0};
    const std::vector<linalg::LowerEntry> lower{{1, 0, 0.1}, {2, 1, kNaN}};
    linalg::SymmetricRows A;
    A.assign_lower(diagonal, lower, {2, 0, 1});
    const std::string message = validate_matrix(A).message;
    EXPECT_NE(message.find("row 2: A(2,1)"), std::string::npos) << message;

    diagonal = {1.0, 0.0, 1.0};
    A.assign_lower(diagonal, {{1, 0, 0.1}}, {2, 0, 1});
    EXPECT_NE(validate_matrix(A).message.find("row 1:"), std::string::npos) << validate_matrix(A).message;
}

TEST(Validation, CompressedRowsFindEveryNonFiniteEntryAndPassHugeFiniteOnes) {
    // a path of 8 rows (7 lower entries, 14 stored): each position in turn, so that the vectorized
    // pass is checked at the start, middle and odd tail of its packets
    const int n = 8;
    const std::vector<double> diagonal(n, 4.0);
    for (double bad : {kNaN, kInf, -kInf}) {
        for (int k = 1; k < n; ++k) {
            std::vector<linalg::LowerEntry> lower;
            for (int i = 1; i < n; ++i) lower.push_back({i, i - 1, i == k ? bad : 0.5});
            std::vector<double> d = diagonal;  // assign_lower takes it over
            linalg::SymmetricRows A;
            A.assign_lower(d, lower);
            const ValidationResult v = validate_matrix(A);
            EXPECT_FALSE(v.valid) << "entry " << k << " = " << bad;
            EXPECT_NE(v.message.find("A(" + std::to_string(k) + "," + std::to_string(k - 1) + ")"), std::string::npos)
                << v.message;
        }
    }
    std::vector<linalg::LowerEntry> lower;
    for (int i = 1; i < n; ++i) lower.push_back({i, i - 1, i % 2 ? 1e308 : -1e308});  // 0 * 1e308 is 0
    std::vector<double> d = diagonal;
    linalg::SymmetricRows A;
    A.assign_lower(d, lower);
    EXPECT_TRUE(validate_matrix(A).valid);
}

TEST(Validation, UpperTriangleIsNotRead) {
    auto p = good_problem();
    p.a(2, 5) = kNaN;  // ODE leaves the strict upper triangle unset
    EXPECT_TRUE(validate(p).valid);
}

TEST(Validation, NonPositiveDiagonal) {
    auto p = good_problem();
    p.a(4, 4) = 0;
    EXPECT_NE(expect_invalid(p).find("row 4"), std::string::npos);
}

TEST(Validation, NonFiniteB) {
    auto p = good_problem();
    p.b[6] = kInf;
    EXPECT_NE(expect_invalid(p).find("row 6"), std::string::npos);
}

TEST(Validation, NaNBound) {
    auto p = good_problem();
    p.lo[8] = kNaN;
    EXPECT_NE(expect_invalid(p).find("row 8"), std::string::npos);
}

TEST(Validation, InfiniteBoundsAreAllowed) {
    auto p = good_problem();
    p.lo[8] = -kInf;
    p.hi[8] = kInf;
    EXPECT_TRUE(validate(p).valid);
}

TEST(Validation, LoAboveHi) {
    auto p = good_problem();
    p.lo[8] = -0.1;
    p.hi[8] = -0.2;
    EXPECT_NE(expect_invalid(p).find("row 8"), std::string::npos);
}

TEST(Validation, PositiveLowerBoundBreaksOdesContract) {
    auto p = good_problem();
    p.lo[8] = 0.1;
    p.hi[8] = 0.2;
    EXPECT_NE(expect_invalid(p).find("lo <= 0 <= hi"), std::string::npos);
}

TEST(Validation, FindexOutOfRange) {
    auto p = good_problem();
    p.findex[8] = 9;
    EXPECT_NE(expect_invalid(p).find("row 8"), std::string::npos);
    p.findex[8] = -2;
    expect_invalid(p);
}

TEST(Validation, FindexPointingAtItself) {
    auto p = good_problem();
    p.findex[8] = 8;
    EXPECT_NE(expect_invalid(p).find("its own row"), std::string::npos);
}

TEST(Validation, FindexPointingAtAFrictionRow) {
    auto p = good_problem();  // rows 1-3 and 4-6 are contacts: 2 and 3 are friction rows of 1
    ASSERT_EQ(p.findex[2], 1);
    p.findex[8] = 2;
    EXPECT_NE(expect_invalid(p).find("friction row"), std::string::npos);
}

TEST(Validation, NegativeFrictionCoefficient) {
    auto p = good_problem();
    p.hi[2] = -0.5;
    EXPECT_NE(expect_invalid(p).find("row 2"), std::string::npos);
}

TEST(Validation, FrictionRowInsideNub) {
    auto p = good_problem();
    p.findex[0] = 1;
    EXPECT_NE(expect_invalid(p).find("nub"), std::string::npos);
}

TEST(Validation, EmptyProblem) {
    Problem p;
    expect_invalid(p);
}

TEST(Validation, NullMatrix) {
    auto owned = good_problem();
    Problem p = owned.view();
    p.A = nullptr;
    expect_invalid(p);
}

TEST(Validation, StrideSmallerThanN) {
    auto owned = good_problem();
    Problem p = owned.view();
    p.lda = p.n - 1;
    expect_invalid(p);
}

TEST(Validation, NubOutOfRange) {
    auto owned = good_problem();
    Problem p = owned.view();
    p.nub = p.n + 1;
    expect_invalid(p);
}

TEST(Validation, BadBlockStructure) {
    auto p = problems::chain_mlcp(4, 2);
    p.block_row.back() = p.n - 1;
    expect_invalid(p);
}

TEST(Validation, WarmStartOfWrongSizeIsInvalidInput) {
    auto p = good_problem();
    Start start;
    start.states.assign(3, RowState::Free);
    std::vector<double> x(p.n, 5.0);
    const Result r = solve(p, Options{}, x.data(), start);
    EXPECT_EQ(r.status, Status::InvalidInput);
    for (double v : x) EXPECT_EQ(v, 0.0);
}

TEST(Validation, NonFiniteToleranceIsInvalidInput) {
    auto p = good_problem();
    Options o;
    o.tolerance = kNaN;
    std::vector<double> x(p.n, 5.0);
    EXPECT_EQ(solve(p, o, x.data()).status, Status::InvalidInput);
}

TEST(Validation, FrictionDampingOutsideZeroToOneIsInvalidInput) {
    auto p = good_problem();
    for (double d : {0.0, -0.5, 1.5, kNaN}) {
        Options o;
        o.tuning.friction_damping = d;
        std::vector<double> x(p.n, 5.0);
        const Result r = solve(p, o, x.data());
        EXPECT_EQ(r.status, Status::InvalidInput) << d;
        EXPECT_NE(r.message.find("friction_damping"), std::string::npos) << r.message;
        for (double v : x) EXPECT_EQ(v, 0.0);
    }
    Options o;
    o.tuning.friction_damping = 1.0;  // no damping: valid
    std::vector<double> x(p.n);
    EXPECT_NE(solve(p, o, x.data()).status, Status::InvalidInput);
}

TEST(Validation, NullXIsInvalidInputWithoutCrash) {
    auto p = good_problem();
    EXPECT_EQ(solve(p, Options{}, static_cast<double*>(nullptr)).status, Status::InvalidInput);
}

}  // namespace
}  // namespace ode_bpp
