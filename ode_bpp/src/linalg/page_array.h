// An array of doubles whose storage, when it is large, is an anonymous memory mapping of its own,
// so that release() gives the pages back to the system at once.
//
// Why: a scratch buffer sized for the largest island met so far (the active set's factor, up to
// 8 n² bytes on a dense envelope: 7 MB at 940 rows) would otherwise stay resident for the rest of the run once freed,
// because malloc keeps freed memory in the process (glibc returns only the top of its heap, past
// a threshold that grows with the blocks it has mapped). A stage that runs now and then on one
// large island then raises the process's memory for good (docs/architecture.md, conventions: memory).
// Small arrays come from the heap as usual.
#pragma once

#include <cstddef>

namespace ode_bpp::linalg {

class PageArray {
public:
    /// Arrays of at least this many bytes are mapped; smaller ones come from the heap.
    static constexpr std::size_t kMappedBytes = std::size_t{128} << 10;

    PageArray() = default;
    ~PageArray() { release(); }
    PageArray(const PageArray&) = delete;
    PageArray& operator=(const PageArray&) = delete;
    PageArray(PageArray&& other) noexcept;
    PageArray& operator=(PageArray&& other) noexcept;

    /// Room for at least `size` doubles. Growing does not keep the contents; fresh storage is
    /// uninitialised (zero when mapped). Throws std::bad_alloc when no memory is left.
    void reserve(std::size_t size);
    /// Gives the storage back (mapped pages to the system, heap storage to malloc); capacity 0.
    void release();

    double* data() { return data_; }
    const double* data() const { return data_; }
    std::size_t capacity() const { return capacity_; }
    /// True when the storage is a mapping of its own (capacity() * 8 >= kMappedBytes).
    bool mapped() const { return mapped_; }

private:
    double* data_ = nullptr;
    std::size_t capacity_ = 0;
    bool mapped_ = false;
};

}  // namespace ode_bpp::linalg
