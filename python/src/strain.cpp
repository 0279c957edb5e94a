// python/src/strain.cpp — knit.StrainTable, strain_table (make one) and load_strain_table
// (knit/strain.hpp; the file format in docs/deformation.md).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "input_files.hpp"
#include "knit/error.hpp"
#include "knit/file_kind.hpp"
#include "knit/generator.hpp"
#include "knit/strain.hpp"

namespace knitpy {

namespace {

using namespace pybind11::literals;
using TablePtr = std::shared_ptr<knit::StrainTable>;

std::array<double, 2> range(const std::pair<double, double>& r) { return {r.first, r.second}; }

}  // namespace

void registerStrain(py::module_& m) {
    py::class_<knit::StrainTable, TablePtr>(
        m, "StrainTable",
        "A pattern's strain table: per cell vertex and strain sample (sx, sa, sy), the displacement (dx, dy, dz, "
        "dtwist) in the pattern's units (docs/deformation.md).")
        .def_property_readonly("source", [](const knit::StrainTable& t) { return t.source; })
        .def_property_readonly("vertex_count", [](const knit::StrainTable& t) { return t.vertexCount; })
        .def_property_readonly(
            "axes", [](const knit::StrainTable& t) { return t.axes; }, "(sx, sa, sy) sample values, three lists")
        .def_property_readonly(
            "data",
            [](const knit::StrainTable& t) {
                py::array_t<float> a({py::ssize_t(t.data.size() / 4), py::ssize_t(4)});
                std::copy(t.data.begin(), t.data.end(), a.mutable_data());
                return a;
            },
            "(rows, 4) float32 copy; row isx + Nx isa + Nx Na isy + Nx Na Ny vertex")
        .def(
            "save",
            [](const knit::StrainTable& t, const std::string& path) {
                // A table made from a pattern file names it as its source: saving there replaced the pattern
                // (a loaded table's source is its own .npy, which it may write again).
                if (knit::fileKind(t.source).rfind("a strain table", 0) != 0) {
                    refuseWritingOverInputs("path", path, {{"the pattern file", t.source}});
                    refuseWritingOverInputs("path", knit::strainAxesPath(path), {{"the pattern file", t.source}});
                }
                knit::writeStrainTable(t, path);
            },
            "path"_a, "Writes path (.npy) and its axes file (.axes.txt) beside it, atomically.")
        .def("__repr__", [](const knit::StrainTable& t) {
            return "<knit.StrainTable '" + t.source + "': " + std::to_string(t.vertexCount) + " vertices, " +
                   std::to_string(t.axes[0].size()) + " x " + std::to_string(t.axes[1].size()) + " x " +
                   std::to_string(t.axes[2].size()) + " samples>";
        });
    m.def(
        "strain_table",
        [](const py::object& pattern, const py::object& path, std::tuple<int, int, int> samples,
           std::pair<double, double> sxRange, std::pair<double, double> saRange, std::pair<double, double> syRange,
           int iterations) {
            const knit::Pattern p = py::isinstance<py::str>(pattern)
                                        ? knit::loadPatternFileOrName(pattern.cast<std::string>())
                                        : castArg<knit::Pattern>(pattern, "pattern", kPatternArg);
            if (!path.is_none()) {  // before the long work
                const std::string out = castArg<std::string>(path, "path", "None or a .npy path (str)");
                refuseWritingOverInputs("path", out, {{"the pattern file", p.name}});
                refuseWritingOverInputs("path", knit::strainAxesPath(out), {{"the pattern file", p.name}});
            }
            knit::StrainTableOptions o;
            o.samples = {std::get<0>(samples), std::get<1>(samples), std::get<2>(samples)};
            o.sxRange = range(sxRange);
            o.saRange = range(saRange);
            o.syRange = range(syRange);
            o.maxIterations = iterations;
            TablePtr t;
            {
                py::gil_scoped_release release;
                t = std::make_shared<knit::StrainTable>(knit::makeStrainTable(p, o));
            }
            if (!path.is_none()) knit::writeStrainTable(*t, path.cast<std::string>());
            return t;
        },
        "pattern"_a = "stockinette", "path"_a = py::none(), "samples"_a = std::make_tuple(9, 9, 9),
        "sx_range"_a = std::make_pair(-0.2, 1.0), "sa_range"_a = std::make_pair(-0.7, 0.7),
        "sy_range"_a = std::make_pair(-0.2, 1.0), "iterations"_a = 600,
        "Makes a pattern's strain table (its cell relaxed under each sampled strain; `knit strain-table`), written to "
        "path (.npy + .axes.txt) when given. Raises knit.Error.");
    m.def(
        "strain_table_at_hand",
        [](const py::object& pattern) {
            const knit::Pattern p = py::isinstance<py::str>(pattern)
                                        ? knit::loadPatternFileOrName(pattern.cast<std::string>())
                                        : castArg<knit::Pattern>(pattern, "pattern", kPatternArg);
            const bool cached = static_cast<bool>(knit::findCachedStrainTable(p).table);
            double seconds = 0;
            if (!cached) {
                py::gil_scoped_release release;
                seconds = knit::estimateStrainTableSeconds(p, {});
            }
            return py::dict("cached"_a = cached, "quick"_a = cached || knit::strainTableIsQuick(p),
                            "seconds"_a = seconds);
        },
        "pattern"_a,
        "Whether deform='strain' finds the pattern's strain table in the cache, else whether making it is quick "
        "(what deform='' makes on first use) and the seconds it is estimated to take: {'cached', 'quick', "
        "'seconds'}. Raises knit.Error for a pattern no table can be made for.");
    m.def(
        "load_strain_table",
        [](const std::string& path) { return std::make_shared<knit::StrainTable>(knit::loadStrainTable(path)); },
        "path"_a, "Reads a table file (T.npy with T.axes.txt) or a MADYPG sxsasy/ folder. Raises knit.Error.");
}

}  // namespace knitpy
