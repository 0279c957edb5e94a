// python/src/arrays.cpp — zero-copy views out, checked conversions in (arrays.hpp).
#include "arrays.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "knit/error.hpp"

namespace knitpy {

namespace {

// A read-only view of `count` rows of `columns` Ts at `data`, kept alive by `owner`.
template <class T>
py::array readOnlyView(const T* data, size_t count, size_t columns, py::handle owner) {
    std::vector<py::ssize_t> shape{py::ssize_t(count)}, strides{py::ssize_t(columns * sizeof(T))};
    if (columns > 1) {
        shape.push_back(py::ssize_t(columns));
        strides.push_back(py::ssize_t(sizeof(T)));
    }
    // numpy refuses a null data pointer with a base; an empty vector may have none.
    static const T empty{};
    py::array a(py::dtype::of<T>(), shape, strides, count ? data : &empty, owner);
    py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return a;
}

std::string shapeText(const py::array& a) {
    std::string s = "(";
    for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
    return s + (a.ndim() == 1 ? ",)" : ")");
}

// Checks the shape (n, columns) of `a`; throws naming `what`.
void requireRows(const py::array& a, py::ssize_t columns, const std::string& what) {
    if (a.ndim() != 2 || a.shape(1) != columns)
        throw knit::Error(what + ": expected an array of shape (n, " + std::to_string(columns) + "), got " +
                          shapeText(a));
}

// Copies an (n, columns) float array into `out` (n * columns doubles), float32 or float64.
void copyFloats(const py::array& a, py::ssize_t columns, const std::string& what, double* out) {
    requireRows(a, columns, what);
    const auto copyAs = [&](auto tag) {
        using T = decltype(tag);
        const auto r = a.unchecked<T, 2>();
        for (py::ssize_t i = 0; i < r.shape(0); ++i)
            for (py::ssize_t j = 0; j < columns; ++j) out[i * columns + j] = double(r(i, j));
    };
    if (py::isinstance<py::array_t<double>>(a)) copyAs(double{});
    else if (py::isinstance<py::array_t<float>>(a)) copyAs(float{});
    else throw knit::Error(what + ": expected float32 or float64 values, got dtype " + std::string(py::str(a.dtype())));
}

// The float32 range every mesh format holds (the mesh readers refuse coordinates beyond it).
constexpr double kFloat32Max = double(std::numeric_limits<float>::max());

std::string number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", x);
    return buf;
}

// Refuses a row of `columns` values that is not finite or beyond float32, naming the argument and row.
void requireFiniteRows(const double* values, size_t rows, size_t columns, const std::string& what) {
    for (size_t i = 0; i < rows; ++i)
        for (size_t j = 0; j < columns; ++j) {
            const double x = values[i * columns + j];
            if (std::isfinite(x) && std::abs(x) <= kFloat32Max) continue;
            std::string row;
            for (size_t k = 0; k < columns; ++k) row += (k ? ", " : "") + number(values[i * columns + k]);
            throw knit::Error(what + ": row " + std::to_string(i) + " (" + row + ") " +
                              (std::isfinite(x)
                                   ? "holds " + number(x) + ", beyond the float32 range (3.4e38) of mesh values"
                                   : std::string("is not finite")));
        }
}

}  // namespace

py::array viewVec3(const std::vector<glm::dvec3>& v, py::handle owner) {
    return readOnlyView(v.empty() ? nullptr : &v[0].x, v.size(), 3, owner);
}

py::array viewVec2(const std::vector<glm::dvec2>& v, py::handle owner) {
    return readOnlyView(v.empty() ? nullptr : &v[0].x, v.size(), 2, owner);
}

py::array viewUvec3(const std::vector<glm::uvec3>& v, py::handle owner) {
    return readOnlyView(v.empty() ? nullptr : &v[0].x, v.size(), 3, owner);
}

template <class T>
py::array viewScalars(const std::vector<T>& v, py::handle owner) {
    return readOnlyView(v.data(), v.size(), 1, owner);
}
template py::array viewScalars(const std::vector<double>&, py::handle);
template py::array viewScalars(const std::vector<uint32_t>&, py::handle);
template py::array viewScalars(const std::vector<uint8_t>&, py::handle);

std::vector<glm::dvec3> toVec3(const py::array& a, const std::string& what) {
    requireRows(a, 3, what);
    std::vector<glm::dvec3> out(size_t(a.shape(0)));
    copyFloats(a, 3, what, out.empty() ? nullptr : &out[0].x);
    requireFiniteRows(out.empty() ? nullptr : &out[0].x, out.size(), 3, what);
    return out;
}

std::vector<glm::dvec2> toVec2(const py::array& a, const std::string& what) {
    requireRows(a, 2, what);
    std::vector<glm::dvec2> out(size_t(a.shape(0)));
    copyFloats(a, 2, what, out.empty() ? nullptr : &out[0].x);
    requireFiniteRows(out.empty() ? nullptr : &out[0].x, out.size(), 2, what);
    return out;
}

std::vector<glm::uvec3> toUvec3(const py::array& a, const std::string& what) {
    requireRows(a, 3, what);
    const char kind = a.dtype().kind();
    if (kind != 'i' && kind != 'u')
        throw knit::Error(what + ": expected integer indices, got dtype " + std::string(py::str(a.dtype())));
    std::vector<glm::uvec3> out(size_t(a.shape(0)));
    const auto copyAs = [&](auto tag) {
        using T = decltype(tag);
        const auto ints = py::array_t<T, py::array::forcecast>::ensure(a);
        const auto r = ints.template unchecked<2>();
        for (py::ssize_t i = 0; i < r.shape(0); ++i)
            for (py::ssize_t j = 0; j < 3; ++j) {
                const T x = r(i, j);
                if (x < 0 || uint64_t(x) > uint64_t(std::numeric_limits<uint32_t>::max()))
                    throw knit::Error(what + ": row " + std::to_string(i) + " has the index " + std::to_string(x) +
                                      " (indices are 0 .. 2^32-1)");
                out[size_t(i)][int(j)] = uint32_t(x);
            }
    };
    if (kind == 'u') copyAs(uint64_t{});  // uint64 beyond 2^63 is not read as negative
    else copyAs(int64_t{});
    return out;
}

void requireIndicesBelow(const std::vector<glm::uvec3>& indices, size_t count, const std::string& what,
                         const std::string& of) {
    for (size_t i = 0; i < indices.size(); ++i)
        for (int j = 0; j < 3; ++j)
            if (indices[i][j] >= count)
                throw knit::Error(what + ": row " + std::to_string(i) + " has the index " +
                                  std::to_string(indices[i][j]) + " but " + of + " has " + std::to_string(count) +
                                  " rows");
}

}  // namespace knitpy
