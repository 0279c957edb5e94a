// python/src/curves.cpp — curve sets as numpy views (knit.Curves, knit.Yarns, knit.Plies) and
// make_plies, the ply stage on evaluated yarns.
#include "arrays.hpp"
#include "bindings.hpp"
#include "knit/error.hpp"
#include "knit/plies.hpp"
#include "ply_options.hpp"

namespace knitpy {

knit::PlyOptions toPlyOptions(const PlyArgs& args, double yarnRadius) {
    knit::PlyOptions o;
    o.count = args.count;
    o.yarnRadius = yarnRadius;
    o.pitch = args.pitch;
    o.plyRadius = args.plyRadius;
    o.centerRadius = args.centerRadius;
    o.samplesPerTurn = args.samplesPerTurn;
    if (args.twist == "S" || args.twist == "s") o.twist = knit::Twist::S;
    else if (args.twist == "Z" || args.twist == "z") o.twist = knit::Twist::Z;
    else throw knit::Error("twist: expected 'S' or 'Z', got '" + args.twist + "'");
    return o;
}

namespace {

using namespace pybind11::literals;

// The curve views every curve set has, read from the Polylines member `curves` of T.
template <class Class, class Get>
void addCurveViews(Class& c, Get curvesOf) {
    c.def_property_readonly(
         "points", [curvesOf](py::object self) { return viewVec3(curvesOf(self).points, self); },
         "(n, 3) float64 read-only view of all points, curve after curve")
        .def_property_readonly(
            "offsets", [curvesOf](py::object self) { return viewScalars(curvesOf(self).offsets, self); },
            "(curves + 1,) uint32: curve c owns points[offsets[c]:offsets[c + 1]]")
        .def_property_readonly(
            "closed", [curvesOf](py::object self) { return viewScalars(curvesOf(self).closed, self); },
            "(curves,) uint8: 1 when the segment last -> first is implied")
        .def_property_readonly("curve_count", [curvesOf](py::object self) { return curvesOf(self).curveCount(); })
        .def_property_readonly("point_count", [curvesOf](py::object self) { return curvesOf(self).pointCount(); });
}

void registerCurveClasses(py::module_& m) {
    py::class_<knit::Polylines> curves(m, "Curves", "Curves stored back to back (points, offsets, closed).");
    addCurveViews(curves,
                  [](py::object& self) -> const knit::Polylines& { return self.cast<const knit::Polylines&>(); });

    py::class_<knit::MappedYarns> yarns(m, "Yarns",
                                        "Yarn centrelines in object space with the surface normal per point.");
    addCurveViews(
        yarns, [](py::object& self) -> const knit::Polylines& { return self.cast<const knit::MappedYarns&>().curves; });
    yarns.def_property_readonly(
        "normals", [](py::object self) { return viewVec3(self.cast<const knit::MappedYarns&>().normals, self); },
        "(n, 3) float64 read-only view: interpolated surface normal per point");

    py::class_<knit::Plies> plies(m, "Plies", "Ply curves twisted around the yarns, with their radii.");
    addCurveViews(plies,
                  [](py::object& self) -> const knit::Polylines& { return self.cast<const knit::Plies&>().curves; });
    plies
        .def_property_readonly(
            "yarn_of_curve",
            [](py::object self) { return viewScalars(self.cast<const knit::Plies&>().yarnOfCurve, self); },
            "(curves,) uint32: source yarn of each ply curve")
        .def_property_readonly(
            "ply_of_curve",
            [](py::object self) { return viewScalars(self.cast<const knit::Plies&>().plyOfCurve, self); },
            "(curves,) uint8: ply index in [0, count)")
        .def_property_readonly(
            "radial", [](py::object self) { return viewVec3(self.cast<const knit::Plies&>().radial, self); },
            "(n, 3) float64: unit direction from the yarn centre per point")
        .def_readonly("ply_radius", &knit::Plies::plyRadius)
        .def_readonly("center_radius", &knit::Plies::centerRadius)
        .def_readonly("pitch", &knit::Plies::pitch);
}

}  // namespace

void registerCurves(py::module_& m) {
    registerCurveClasses(m);
    m.def(
        "make_plies",
        [](const knit::MappedYarns& yarns, double yarnRadius, int count, double pitch, const std::string& twist,
           double plyRadius, double centerRadius, int samplesPerTurn) {
            const knit::PlyOptions o =
                toPlyOptions({count, pitch, twist, plyRadius, centerRadius, samplesPerTurn}, yarnRadius);
            py::gil_scoped_release release;
            return knit::makePlies(yarns, o);
        },
        "yarns"_a, "yarn_radius"_a, "count"_a = 2, "pitch"_a = 0.0, "twist"_a = "S", "ply_radius"_a = 0.0,
        "center_radius"_a = 0.0, "samples_per_turn"_a = 12,
        "The plies of evaluated yarns (Scene.evaluate): pitch 0 = 6 yarn radii, radii 0 = touching "
        "plies that fill the yarn, twist 'S' or 'Z'. Raises knit.Error.");
}

}  // namespace knitpy
