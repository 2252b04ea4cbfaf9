#include "linalg/page_array.h"

#include <sys/mman.h>

#include <new>
#include <utility>

namespace ode_bpp::linalg {

PageArray::PageArray(PageArray&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)),
      capacity_(std::exchange(other.capacity_, 0)),
      mapped_(std::exchange(other.mapped_, false)) {}

PageArray& PageArray::operator=(PageArray&& other) noexcept {
    if (this != &other) {
        release();
        data_ = std::exchange(other.data_, nullptr);
        capacity_ = std::exchange(other.capacity_, 0);
        mapped_ = std::exchange(other.mapped_, false);
    }
    return *this;
}

void PageArray::reserve(std::size_t size) {
    if (size <= capacity_) return;
    release();
    const std::size_t bytes = size * sizeof(double);
    if (bytes >= kMappedBytes) {
        void* pages = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (pages == MAP_FAILED) throw std::bad_alloc();
        data_ = static_cast<double*>(pages);
        mapped_ = true;
    } else {
        data_ = static_cast<double*>(::operator new(bytes));
        mapped_ = false;
    }
    capacity_ = size;
}

void PageArray::release() {
    if (data_ == nullptr) return;
    if (mapped_) munmap(data_, capacity_ * sizeof(double));
    else ::operator delete(data_);
    data_ = nullptr;
    capacity_ = 0;
    mapped_ = false;
}

}  // namespace ode_bpp::linalg
