// PageArray: large arrays live in pages of their own that release() hands back to the system
// (the process's resident memory falls at once), small ones on the heap; and the incremental
// factor that keeps its storage there solves correctly after a release.
#include <gtest/gtest.h>

#include <unistd.h>

#include <fstream>
#include <random>
#include <utility>
#include <vector>

#include "linalg/incremental_cholesky.h"
#include "linalg/page_array.h"
#include "test_linalg_support.h"

namespace ode_bpp::test {
namespace {

/// Resident memory of this process in bytes (/proc/self/statm, second field in pages).
long resident_bytes() {
    std::ifstream statm("/proc/self/statm");
    long size = 0, resident = 0;
    statm >> size >> resident;
    return resident * sysconf(_SC_PAGESIZE);
}

TEST(LinalgPageArray, SmallArraysComeFromTheHeapLargeOnesAreMapped) {
    linalg::PageArray small, large;
    small.reserve(16);
    large.reserve(linalg::PageArray::kMappedBytes / sizeof(double));
    EXPECT_FALSE(small.mapped());
    EXPECT_TRUE(large.mapped());
    EXPECT_GE(small.capacity(), 16u);
    for (std::size_t i = 0; i < large.capacity(); ++i) large.data()[i] = static_cast<double>(i);
    EXPECT_EQ(large.data()[large.capacity() - 1], static_cast<double>(large.capacity() - 1));
}

TEST(LinalgPageArray, ReserveGrowsOnlyAndReleaseEmpties) {
    linalg::PageArray a;
    a.reserve(1000);
    const double* first = a.data();
    a.reserve(10);
    EXPECT_EQ(a.data(), first);
    EXPECT_EQ(a.capacity(), 1000u);
    a.release();
    EXPECT_EQ(a.capacity(), 0u);
    EXPECT_EQ(a.data(), nullptr);
    a.release();  // twice is harmless
}

TEST(LinalgPageArray, MovingTransfersTheStorage) {
    linalg::PageArray a;
    a.reserve(1 << 16);
    a.data()[7] = 3.5;
    linalg::PageArray b(std::move(a));
    EXPECT_EQ(a.data(), nullptr);
    EXPECT_EQ(b.data()[7], 3.5);
    linalg::PageArray c;
    c.reserve(4);
    c = std::move(b);
    EXPECT_TRUE(c.mapped());
    EXPECT_EQ(c.data()[7], 3.5);
}

/// Resident bytes a run under AddressSanitizer keeps after `bytes` were mapped, touched and
/// unmapped: its shadow of the range, one byte per eight, which stays resident (measured on the
/// test machine: 1.09 MB after 8 MB). None otherwise. A range that stayed resident itself still
/// fails the test by far. (The sanitizer build is GCC's, which defines __SANITIZE_ADDRESS__, as
/// tests/integration/test_memory_limit.cpp checks too.)
constexpr std::size_t sanitizer_shadow([[maybe_unused]] std::size_t bytes) {
#if defined(__SANITIZE_ADDRESS__)
    return bytes / 8;
#else
    return 0;
#endif
}

/// Allocates and frees `bytes` through malloc: glibc then serves blocks up to that size from its
/// heap, which it keeps resident after they are freed (its mmap threshold follows freed blocks).
/// Returns the byte it wrote (1); the block's address escapes through a volatile pointer, so the
/// allocation cannot be elided.
char raise_malloc_threshold(std::size_t bytes) {
    std::vector<char> block(bytes);
    char* volatile escaped = block.data();
    escaped[bytes / 2] = 1;
    return escaped[bytes / 2];
}

TEST(LinalgPageArray, ReleaseReturnsTheResidentMemory) {
    constexpr std::size_t kBytes = std::size_t{8} << 20;
    ASSERT_EQ(raise_malloc_threshold(2 * kBytes), 1);  // as after a larger island: a plain heap block would stay
    linalg::PageArray a;
    const long before = resident_bytes();
    a.reserve(kBytes / sizeof(double));
    for (std::size_t i = 0; i < a.capacity(); i += 512) a.data()[i] = 1.0;  // touch every page
    const long touched = resident_bytes();
    a.release();
    const long after = resident_bytes();
    EXPECT_GT(touched - before, static_cast<long>(kBytes * 9 / 10));
    EXPECT_LT(after - before, static_cast<long>(kBytes / 10 + sanitizer_shadow(kBytes))) << "the pages stayed resident";
}

TEST(LinalgIncrementalCholesky, SolvesAfterItsStorageWasReleased) {
    std::mt19937 rng(5);
    const int n = 200;  // 160 kB of factor (every row from column 0): mapped
    const MatrixXd M = random_envelope_spd(n, n, rng, 0.5, 1.0);
    linalg::IncrementalCholesky f;
    for (int round = 0; round < 2; ++round) {
        f.reset(n);
        std::vector<double> column;
        for (int j = 0; j < n; ++j) {
            column.assign(static_cast<std::size_t>(j), 0.0);
            for (int i = 0; i < j; ++i) column[i] = M(i, j);
            ASSERT_TRUE(f.append(column.data(), 0, M(j, j)));
        }
        Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(n, -1, 1);
        const Eigen::VectorXd expected = M.llt().solve(rhs);
        f.solve(rhs.data());
        EXPECT_LT((rhs - expected).cwiseAbs().maxCoeff(), 1e-9 * condition_number(M));
        f.release();
        EXPECT_EQ(f.size(), 0);
    }
}

}  // namespace
}  // namespace ode_bpp::test
