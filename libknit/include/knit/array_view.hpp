// knit/array_view.hpp — a read-only view of contiguous elements (pointer and count; C++17 has no
// std::span), so that a function can take a std::vector or an array held elsewhere, such as a
// bound scene's stored arrays used in place in the file's memory map (knit/bound_scene.hpp).
#pragma once
#include <cstddef>
#include <vector>

namespace knit {

template <class T>
class ArrayView {
public:
    ArrayView() = default;
    ArrayView(const T* data, size_t size) : data_(data), size_(size) {}
    ArrayView(const std::vector<T>& v) : data_(v.data()), size_(v.size()) {}  // NOLINT: implicit by design

    const T* data() const { return data_; }
    size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    const T& operator[](size_t i) const { return data_[i]; }
    const T* begin() const { return data_; }
    const T* end() const { return data_ + size_; }

private:
    const T* data_ = nullptr;
    size_t size_ = 0;
};

}  // namespace knit
