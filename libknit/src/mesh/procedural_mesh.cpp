// procedural_mesh.cpp — the built-in base meshes: plane, cylinder, sphere, drape.
//
// Conventions shared by all four:
//  * +Y up (glTF's convention): each mesh is built in a z-up frame (the formulas below) and then
//    rotated rigidly by -90 degrees about +x, (x, y, z) -> (x, z, -y) (step `toYUp`). UVs, faces
//    and hence the knit on them are those of the z-up construction; only positions turn.
//  * UVs lie in [0,1]^2; every UV triangle is counter-clockwise, and its 3D normal
//    (p1-p0) x (p2-p0) points outward (cylinder, sphere) or up (+y: plane, drape), i.e. the
//    UV chart and the 3D surface have the same orientation.
//  * A quad (i,j)-(i+1,j)-(i+1,j+1)-(i,j+1) is split into (a,b,c) and (a,c,d).
//  * Closed directions share positions: the cylinder's and sphere's seam column at u = 0 and
//    u = 1 is one column of positions with two columns of UV vertices, so the 3D topology is
//    closed and vertex normals are continuous across the seam.
//  * Options are validated first (knit::Error): resolutions >= 1 (cylinder/sphere: resU >= 3,
//    sphere: resV >= 2), at most 1e8 quads, and size/radius/height finite and > 0.
#include "knit/base_mesh.hpp"
#include "knit/error.hpp"
#include "util/checks.hpp"
#include "util/math.hpp"

#include <cmath>

namespace knit {
namespace {

void checkOptions(const char* what, const ProceduralMeshOptions& o, int minU, int minV, bool size, bool radius,
                  bool height) {
    const std::string w = what;
    if (o.resU < minU || o.resV < minV)
        throw Error(w + ": the mesh resolution " + std::to_string(o.resU) + " x " + std::to_string(o.resV) +
                    " quads is too small (at least " + std::to_string(minU) + " x " + std::to_string(minV) + ")");
    if (double(o.resU) * double(o.resV) > 1e8)
        throw Error(w + ": the mesh resolution " + std::to_string(o.resU) + " x " + std::to_string(o.resV) +
                    " quads is too large (at most 1e8 quads)");
    auto positive = [&](bool used, double v, const char* name) {
        if (used && !util::positiveFinite(v))
            throw Error(w + ": " + name + " must be a finite number > 0 (got " + std::to_string(v) + ")");
    };
    positive(size, o.size, "size");
    positive(radius, o.radius, "radius");
    positive(height, o.height, "height");
}

// The rigid rotation from the z-up construction frame to +Y up: (x, y, z) -> (x, z, -y), a
// -90 degree turn about +x (determinant +1, so windings and outward normals are kept).
BaseMesh toYUp(BaseMesh m) {
    for (glm::dvec3& p : m.positions) p = glm::dvec3(p.x, p.z, -p.y);
    return m;
}

// Quads over a (nu+1) x (nv+1) UV lattice; posIndex maps a lattice point to its position.
template <class PosIndex>
void addQuads(BaseMesh& m, int nu, int jBegin, int jEnd, PosIndex posIndex) {
    auto uvIndex = [nu](int i, int j) { return uint32_t(j * (nu + 1) + i); };
    for (int j = jBegin; j < jEnd; ++j)
        for (int i = 0; i < nu; ++i) {
            const glm::uvec3 pa(posIndex(i, j), posIndex(i + 1, j), posIndex(i + 1, j + 1));
            const glm::uvec3 pb(posIndex(i, j), posIndex(i + 1, j + 1), posIndex(i, j + 1));
            m.faces.push_back(pa);
            m.faces.push_back(pb);
            m.faceUvs.emplace_back(uvIndex(i, j), uvIndex(i + 1, j), uvIndex(i + 1, j + 1));
            m.faceUvs.emplace_back(uvIndex(i, j), uvIndex(i + 1, j + 1), uvIndex(i, j + 1));
        }
}

// A flat (resU+1) x (resV+1) lattice over [0,1]^2, positions indexed like UVs.
BaseMesh flatSheet(const ProceduralMeshOptions& o, const char* name, double (*heightAt)(double, double, double)) {
    BaseMesh m;
    m.name = name;
    for (int j = 0; j <= o.resV; ++j)
        for (int i = 0; i <= o.resU; ++i) {
            const glm::dvec2 uv(double(i) / o.resU, double(j) / o.resV);
            const double x = (uv.x - 0.5) * o.size, y = (uv.y - 0.5) * o.size;
            m.uvs.push_back(uv);
            m.positions.emplace_back(x, y, heightAt ? heightAt(x, y, o.size) : 0.0);
        }
    addQuads(m, o.resU, 0, o.resV, [&](int i, int j) { return uint32_t(j * (o.resU + 1) + i); });
    return m;
}

// The drape's height field (see makeDrape).
double drapeHeight(double x, double y, double size) {
    const double R = size / 3.0;                     // sphere radius, centre at the origin
    const double a = R * std::sin(util::kPi / 4.0);  // the sheet leaves the sphere at polar angle 45°
    const double ha = std::sqrt(R * R - a * a);
    const double slope = -a / ha;  // dh/dr of the sphere at r = a
    const double L = R / 2.0;      // fall-off length
    const double r = std::hypot(x, y);
    if (r <= a) return std::sqrt(R * R - r * r);
    return ha + slope * L * (1.0 - std::exp(-(r - a) / L));
}

}  // namespace

// Plane: y = 0 (+y up), x in [-size/2, size/2] with u = x/size + 0.5, z in [-size/2, size/2] with
// v = 0.5 - z/size (built as z = 0 with uv = (x, y)/size + 0.5, then toYUp).
BaseMesh makePlane(const ProceduralMeshOptions& o) {
    checkOptions("plane", o, 1, 1, true, false, false);
    return toYUp(flatSheet(o, "plane", nullptr));
}

// Cylinder of `radius` around +y, y in [0, height]: built around +z as (R cos 2πu, R sin 2πu, v·height),
// then toYUp: position (R cos 2πu, v·height, -R sin 2πu).
// resU columns of positions (closed around), resU+1 columns of UVs (u = 0 and u = 1 both exist).
BaseMesh makeCylinder(const ProceduralMeshOptions& o) {
    checkOptions("cylinder", o, 3, 1, false, true, true);
    BaseMesh m;
    m.name = "cylinder";
    for (int j = 0; j <= o.resV; ++j) {
        const double v = double(j) / o.resV;
        for (int i = 0; i < o.resU; ++i) {
            const double t = util::kTwoPi * i / o.resU;
            m.positions.emplace_back(o.radius * std::cos(t), o.radius * std::sin(t), v * o.height);
        }
        for (int i = 0; i <= o.resU; ++i) m.uvs.emplace_back(double(i) / o.resU, v);
    }
    addQuads(m, o.resU, 0, o.resV, [&](int i, int j) { return uint32_t(j * o.resU + i % o.resU); });
    return toYUp(std::move(m));
}

// Sphere of `radius` at the origin, latitude-longitude: θ = 2πu, polar angle φ = πv from the
// south pole, built as R (sin φ cos θ, sin φ sin θ, -cos φ) and then toYUp: R (sin φ cos θ, -cos φ,
// -sin φ sin θ), the south pole at -y. Rings j = 1..resV-1 have resU
// positions (closed around) and resU+1 UVs. Each pole is ONE position with resU UV vertices at
// u = (i + 1/2)/resU (v = 0 or 1), so the pole rows are triangles (pole, ring) whose UV and 3D
// shapes are both non-degenerate; the UV corners left of/right of each pole UV are not covered.
BaseMesh makeSphere(const ProceduralMeshOptions& o) {
    checkOptions("sphere", o, 3, 2, false, true, false);
    const int nu = o.resU, nv = o.resV;
    BaseMesh m;
    m.name = "sphere";
    // Positions: south pole, rings, north pole.
    m.positions.emplace_back(0.0, 0.0, -o.radius);
    for (int j = 1; j < nv; ++j) {
        const double phi = util::kPi * j / nv;
        for (int i = 0; i < nu; ++i) {
            const double t = util::kTwoPi * i / nu;
            m.positions.emplace_back(o.radius * std::sin(phi) * std::cos(t), o.radius * std::sin(phi) * std::sin(t),
                                     -o.radius * std::cos(phi));
        }
    }
    m.positions.emplace_back(0.0, 0.0, o.radius);
    const uint32_t north = uint32_t(m.positions.size() - 1);
    auto ringPos = [nu](int i, int j) { return uint32_t(1 + (j - 1) * nu + i % nu); };
    // UVs: the full (nu+1) x (nv+1) lattice (rows 0 and nv unused), then the pole UVs.
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) m.uvs.emplace_back(double(i) / nu, double(j) / nv);
    const uint32_t southUv = uint32_t(m.uvs.size());
    for (int i = 0; i < nu; ++i) m.uvs.emplace_back((i + 0.5) / nu, 0.0);
    const uint32_t northUv = uint32_t(m.uvs.size());
    for (int i = 0; i < nu; ++i) m.uvs.emplace_back((i + 0.5) / nu, 1.0);
    auto latticeUv = [nu](int i, int j) { return uint32_t(j * (nu + 1) + i); };
    // South cap: (pole, (i+1,1), (i,1)); middle quads; north cap: ((i,nv-1), (i+1,nv-1), pole).
    for (int i = 0; i < nu; ++i) {
        m.faces.emplace_back(0u, ringPos(i + 1, 1), ringPos(i, 1));
        m.faceUvs.emplace_back(southUv + i, latticeUv(i + 1, 1), latticeUv(i, 1));
    }
    addQuads(m, nu, 1, nv - 1, ringPos);
    for (int i = 0; i < nu; ++i) {
        m.faces.emplace_back(ringPos(i, nv - 1), ringPos(i + 1, nv - 1), north);
        m.faceUvs.emplace_back(latticeUv(i, nv - 1), latticeUv(i + 1, nv - 1), northUv + i);
    }
    // Drop the unused lattice rows v = 0 and v = 1 so every UV vertex is referenced.
    std::vector<uint32_t> remap(m.uvs.size(), 0);
    std::vector<glm::dvec2> used;
    for (uint32_t k = 0; k < m.uvs.size(); ++k) {
        const bool poleRow = k < southUv && (k < uint32_t(nu + 1) || k >= uint32_t(nv * (nu + 1)));
        if (!poleRow) {
            remap[k] = uint32_t(used.size());
            used.push_back(m.uvs[k]);
        }
    }
    for (glm::uvec3& f : m.faceUvs) f = glm::uvec3(remap[f.x], remap[f.y], remap[f.z]);
    m.uvs = std::move(used);
    return toYUp(std::move(m));
}

// Drape: a square sheet of side `size` (regular resU x resV grid, uv = (x, y)/size + 0.5) laid
// over a sphere of radius R = size/3 centred at the origin, as a height field z = h(r) over the
// flat sheet's (x, y), r = |(x, y)| (then toYUp: the height is +y, the sheet hangs down):
//   r <= a = R sin 45°:  h = sqrt(R² - r²)                        (on the sphere's cap)
//   r >  a:              h = h(a) + h'(a) L (1 - exp(-(r - a)/L)),  L = R/2
// The fall-off continues the cap with the same value and slope (C1, so normals are continuous)
// and decreases monotonically. Being a graph over a regular grid it cannot self-intersect and
// no triangle is degenerate (its xy projection has area size²/(2 resU resV)); normals face +z
// before toYUp, +y after.
BaseMesh makeDrape(const ProceduralMeshOptions& o) {
    checkOptions("drape", o, 1, 1, true, false, false);
    return toYUp(flatSheet(o, "drape", &drapeHeight));
}

}  // namespace knit
