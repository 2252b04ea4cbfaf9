#include "linalg/skyline.h"

#include <algorithm>
#include <cassert>
#include <utility>

namespace ode_bpp::linalg {

namespace {

std::vector<std::ptrdiff_t> packed_column_pointers(const std::vector<int>& sky) {
    const int n = static_cast<int>(sky.size());
    std::vector<std::ptrdiff_t> colptr(static_cast<std::size_t>(n) + 1, 0);
    for (int k = 0; k < n; ++k) colptr[k + 1] = colptr[k] + (sky[k] - k + 1);
    return colptr;
}


/// The column profile of a row envelope: sky[k] = max{ i : first[i] <= k } (every row i >= k with
/// first[i] <= k reaches column k), the running maximum of the last row starting at each column.
std::vector<int> column_profile(const std::vector<int>& first) {
    const int n = static_cast<int>(first.size());
    std::vector<int> last_row_starting(first.size(), -1);
    for (int i = 0; i < n; ++i) {
        assert(0 <= first[i] && first[i] <= i);
        last_row_starting[first[i]] = i;
    }
    int reach = -1;
    for (int k = 0; k < n; ++k) {
        reach = std::max({reach, last_row_starting[k], k});
        last_row_starting[k] = reach;
    }
    return last_row_starting;
}

}  // namespace

SkylineShape SkylineShape::from_row_profile(const std::vector<int>& first) {
    SkylineShape shape;
    shape.n = static_cast<int>(first.size());
    shape.sky = column_profile(first);
    shape.colptr = packed_column_pointers(shape.sky);
    shape.index_first_columns();
    return shape;
}

std::ptrdiff_t SkylineShape::size_of_row_profile(const std::vector<int>& first) {
    const std::vector<int> sky = column_profile(first);
    std::ptrdiff_t size = 0;
    for (int k = 0; k < static_cast<int>(sky.size()); ++k) size += sky[k] - k + 1;
    return size;
}

SkylineShape SkylineShape::dense(int n) {
    SkylineShape shape;
    shape.n = n;
    shape.sky.assign(static_cast<std::size_t>(n), n - 1);
    shape.colptr = packed_column_pointers(shape.sky);
    shape.index_first_columns();
    return shape;
}

int SkylineShape::search_first_column(int r) const {
    return static_cast<int>(std::lower_bound(sky.begin(), sky.end(), r) - sky.begin());
}

void SkylineShape::index_first_columns() {
    first_column.resize(static_cast<std::size_t>(n));
    int j = 0;  // sky is non-decreasing, so the first column reaching r never moves back
    for (int r = 0; r < n; ++r) {
        while (sky[j] < r) ++j;
        first_column[r] = j;
    }
}

bool SkylineShape::valid() const {
    if (n < 0 || static_cast<int>(sky.size()) != n || static_cast<int>(colptr.size()) != n + 1) return false;
    if (colptr[0] < 0) return false;
    for (int k = 0; k < n; ++k) {
        if (sky[k] < k || sky[k] > n - 1) return false;
        if (k > 0 && sky[k] < sky[k - 1]) return false;
        if (colptr[k + 1] - colptr[k] < height(k)) return false;
    }
    if (!first_column.empty()) {
        if (static_cast<int>(first_column.size()) != n) return false;
        for (int r = 0; r < n; ++r)
            if (first_column[r] != search_first_column(r)) return false;
    }
    return true;
}

SkylineMatrix::SkylineMatrix(SkylineShape shape) : shape_(std::move(shape)) {
    assert(shape_.valid());
    values_.assign(static_cast<std::size_t>(shape_.size()), 0.0);
}

void SkylineMatrix::reset(const SkylineShape& shape) {
    reshape(shape);
    std::fill(values_.begin(), values_.end(), 0.0);
}

void SkylineMatrix::reshape(const SkylineShape& shape) {
    assert(shape.valid());
    shape_.n = shape.n;
    shape_.sky = shape.sky;
    shape_.colptr = shape.colptr;
    shape_.first_column = shape.first_column;
    values_.resize(static_cast<std::size_t>(shape_.size()));
}

void SkylineMatrix::copy_tail_from(const SkylineMatrix& other, int k0) {
    assert(other.shape_.colptr == shape_.colptr);
    if (k0 >= n()) return;
    const std::ptrdiff_t begin = shape_.colptr[k0];
    std::copy(other.values_.begin() + begin, other.values_.end(), values_.begin() + begin);
}

void SkylineMatrix::copy_head_from(const SkylineMatrix& other, int k1) {
    assert(other.shape_.colptr == shape_.colptr);
    if (k1 <= 0) return;
    const std::ptrdiff_t end = shape_.colptr[std::min(k1, n())];
    std::copy(other.values_.begin(), other.values_.begin() + end, values_.begin());
}

void SkylineMatrix::copy_rows_from(const SkylineMatrix& other, const std::vector<int>& rows, int k_end) {
    assert(other.shape_.colptr == shape_.colptr);
    for (int r : rows) {
        const int end = std::min(r, k_end);
        for (int j = shape_.first_column_holding(r); j < end; ++j) at(r, j) = other.at(r, j);
    }
}

}  // namespace ode_bpp::linalg
