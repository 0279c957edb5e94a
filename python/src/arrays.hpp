// python/src/arrays.hpp — numpy arrays in and out of the module.
//
// Out: read-only views of the library's flat vectors (no copy); `owner` is the Python object that
// owns the vector and is kept alive by the view. In: float32 or float64 (n, 3) / (n, 2) arrays and
// integer (n, 3) index arrays, converted to the library's types with the argument name in errors.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

namespace knitpy {

namespace py = pybind11;

// (n, 3) float64 view of dvec3s.
py::array viewVec3(const std::vector<glm::dvec3>& v, py::handle owner);
// (n, 2) float64 view of dvec2s.
py::array viewVec2(const std::vector<glm::dvec2>& v, py::handle owner);
// (n, 3) uint32 view of uvec3s.
py::array viewUvec3(const std::vector<glm::uvec3>& v, py::handle owner);
// (n,) views of scalars.
template <class T>
py::array viewScalars(const std::vector<T>& v, py::handle owner);

// Every array argument of the module goes through these conversions, so each function checks its
// arrays as knit.Mesh does, with the argument's name and the row in the message.
//
// An (n, 3) float array (float32 or float64, any strides) as dvec3s; throws knit::Error naming
// `what` on a wrong shape, a non-float dtype, or a row holding a value that is not finite or
// beyond the float32 range (what every mesh file can hold; the mesh readers refuse it too).
std::vector<glm::dvec3> toVec3(const py::array& a, const std::string& what);
// The same for (n, 2).
std::vector<glm::dvec2> toVec2(const py::array& a, const std::string& what);
// An (n, 3) integer array as uvec3s; throws knit::Error on a wrong shape, a non-integer dtype or
// a negative / too large index.
std::vector<glm::uvec3> toUvec3(const py::array& a, const std::string& what);
// Throws knit::Error naming `what` and the row when an index is not below `count` (the rows of
// the array `of` it indexes).
void requireIndicesBelow(const std::vector<glm::uvec3>& indices, size_t count, const std::string& what,
                         const std::string& of);

}  // namespace knitpy
