// shared_array.hpp (internal) — an immutable array that either owns its elements (made from a
// std::vector) or views elements another object owns, which it keeps alive by shared ownership:
// a loaded bound scene's largest arrays used in place in the file's memory map
// (scene/bound_scene_file.hpp), so that copies of the scene and its Animators keep the map open
// as long as any of them lives.
#pragma once
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

#include "knit/array_view.hpp"

namespace knit::util {

template <class T>
class SharedArray {
public:
    SharedArray() = default;
    // Owns the elements (moved in).
    SharedArray(std::vector<T> v) {  // NOLINT: implicit, as a vector is assigned to it
        auto owned = std::make_shared<const std::vector<T>>(std::move(v));
        data_ = owned->data();
        size_ = owned->size();
        owner_ = std::move(owned);
    }
    // Views `size` elements at `data`, which `owner` keeps valid (and unchanged).
    SharedArray(std::shared_ptr<const void> owner, const T* data, size_t size)
        : owner_(std::move(owner)), data_(data), size_(size), view_(true) {}

    const T* data() const { return data_; }
    size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    const T& operator[](size_t i) const { return data_[i]; }
    const T* begin() const { return data_; }
    const T* end() const { return data_ + size_; }
    operator ArrayView<T>() const { return {data_, size_}; }  // NOLINT: implicit by design
    // True when the elements belong to another owner (e.g. a file's memory map).
    bool isView() const { return view_; }

    friend bool operator==(const SharedArray& a, const SharedArray& b) {
        if (a.size_ != b.size_) return false;
        for (size_t i = 0; i < a.size_; ++i)
            if (!(a.data_[i] == b.data_[i])) return false;
        return true;
    }
    friend bool operator!=(const SharedArray& a, const SharedArray& b) { return !(a == b); }

private:
    std::shared_ptr<const void> owner_;
    const T* data_ = nullptr;
    size_t size_ = 0;
    bool view_ = false;
};

}  // namespace knit::util
