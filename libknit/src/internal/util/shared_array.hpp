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

// An ArrayView (its accessors; it converts to one for a function taking an ArrayView) that owns
// or shares ownership of what it views.
template <class T>
class SharedArray : public ArrayView<T> {
public:
    SharedArray() = default;
    // Owns the elements (moved in).
    SharedArray(std::vector<T> v) {  // NOLINT: implicit, as a vector is assigned to it
        auto owned = std::make_shared<const std::vector<T>>(std::move(v));
        static_cast<ArrayView<T>&>(*this) = ArrayView<T>(owned->data(), owned->size());
        owner_ = std::move(owned);
    }
    // Views `size` elements at `data`, which `owner` keeps valid (and unchanged).
    SharedArray(std::shared_ptr<const void> owner, const T* data, size_t size)
        : ArrayView<T>(data, size), owner_(std::move(owner)), view_(true) {}

    // The elements as a plain view (for a function taking an ArrayView; valid while this lives).
    ArrayView<T> view() const { return ArrayView<T>(this->data(), this->size()); }

    // True when the elements belong to another owner (e.g. a file's memory map).
    bool isView() const { return view_; }

    friend bool operator==(const SharedArray& a, const SharedArray& b) {
        if (a.size() != b.size()) return false;
        for (size_t i = 0; i < a.size(); ++i)
            if (!(a[i] == b[i])) return false;
        return true;
    }
    friend bool operator!=(const SharedArray& a, const SharedArray& b) { return !(a == b); }

private:
    std::shared_ptr<const void> owner_;
    bool view_ = false;
};

}  // namespace knit::util
