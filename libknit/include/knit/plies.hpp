// knit/plies.hpp — plies twisted around the mapped yarns, in object space.
#pragma once
#include <cstdint>
#include <vector>

#include "knit/binding.hpp"
#include "knit/frames.hpp"

namespace knit {

// Yarn held vertical: S strands slant like the middle of "S" (a left-handed helix,
// theta = -2 pi s / pitch with B = T x N), Z strands like the middle of "Z" (right-handed,
// theta = +2 pi s / pitch).
enum class Twist : uint8_t { S, Z };

struct PlyOptions {
    int count = 2;              // plies per yarn
    double yarnRadius = 0.001;  // metres (the pipeline sets it from the pattern)
    // 0 = touching plies that fill the yarn: centre radius R/(1 + sin(pi/n)), ply radius
    // centreRadius * sin(pi/n).
    double centerRadius = 0.0;
    double plyRadius = 0.0;
    double pitch = 0.0;         // length of one full ply turn (metres); 0 = 6 yarn radii
    Twist twist = Twist::S;
    int samplesPerTurn = 12;    // resampling density of the yarn centreline (knee: docs/speed-vs-error.md)
};

struct Plies {
    Polylines curves;
    std::vector<uint32_t> yarnOfCurve;  // source yarn of each ply curve
    std::vector<uint8_t> plyOfCurve;    // ply index i in [0, count)
    double plyRadius = 0.0;
    double centerRadius = 0.0;
    double pitch = 0.0;                 // effective pitch of open yarns
    // Per ply point: the unit radial direction from the yarn centre (the ply's outward normal
    // reference; a renderer derives the ply phase from it).
    std::vector<glm::dvec3> radial;
};

// Resolved option values (auto radii / pitch filled in); throws knit::Error on invalid options.
PlyOptions resolvePlyOptions(const PlyOptions& options);

// Resamples each yarn to `samplesPerTurn` points per ply turn, builds rotation-minimizing
// frames seeded with the surface normal and sweeps the helices
//   c_i(s) = C(s) + R (cos(theta + 2 pi i / n) N + sin(theta + 2 pi i / n) B),
//   theta = +-2 pi s / pitch.
// On closed yarns the number of turns is rounded so the helix closes with no twist jump.
Plies makePlies(const MappedYarns& yarns, const PlyOptions& options);

}  // namespace knit
