// BCC, pbrt-v4 curves and binary PLY, each read back by a small independent reader.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

#include "export/test_curves.hpp"
#include "knit/error.hpp"
#include "knit/export.hpp"

namespace knit {
namespace {

ExportStats write(const Polylines& c, double radius, ExportOptions o) {
    ExportInput in;
    in.curves = &c;
    in.radius = radius;
    return exportCurves(in, o);
}

// ---- BCC reader (from the format description: 64-byte header, int32 count, float32 xyz) ----
struct BccCurve {
    bool closed;
    std::vector<glm::vec3> points;
};

std::vector<BccCurve> readBcc(const std::string& path) {
    const std::vector<unsigned char> b = test::readBytes(path);
    EXPECT_GE(b.size(), 64u);
    EXPECT_EQ(std::string(b.begin(), b.begin() + 3), "BCC");
    EXPECT_EQ(b[3], 0x44);
    EXPECT_EQ(b[4], 'C');
    EXPECT_EQ(b[5], '0');
    EXPECT_EQ(b[6], 3);
    uint64_t curves, points;
    std::memcpy(&curves, &b[8], 8);
    std::memcpy(&points, &b[16], 8);
    std::vector<BccCurve> out;
    size_t at = 64, total = 0;
    for (uint64_t c = 0; c < curves; ++c) {
        int32_t count;
        std::memcpy(&count, &b[at], 4);
        at += 4;
        BccCurve curve{count < 0, {}};
        const size_t n = size_t(count < 0 ? -count : count);
        for (size_t i = 0; i < n; ++i, at += 12) {
            glm::vec3 p;
            std::memcpy(&p, &b[at], 12);
            curve.points.push_back(p);
        }
        total += n;
        out.push_back(curve);
    }
    EXPECT_EQ(total, points);
    EXPECT_EQ(at, b.size()) << "trailing bytes";
    return out;
}

TEST(BccExport, closedCurvesHaveNegativeCountsAndPointsRoundTrip) {
    const std::string dir = test::scratchDir("bcc");
    Polylines c = test::mixedCurves(glm::dvec3(1.5, -0.5, 2.0));
    const glm::dvec3 single(9, 9, 9);
    c.addCurve(&single, 1, false);  // fewer than 2 points: not written
    ExportOptions o;
    o.path = dir + "/yarns.bcc";
    o.what = ExportWhat::Yarns;
    const ExportStats s = write(c, 0.001, o);
    EXPECT_EQ(s.curves, 3u);
    const auto curves = readBcc(o.path);
    ASSERT_EQ(curves.size(), 3u);
    for (size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(curves[k].closed, c.isClosed(k)) << k;
        ASSERT_EQ(curves[k].points.size(), c.size(k));
        for (size_t i = 0; i < c.size(k); ++i)
            EXPECT_EQ(curves[k].points[i], glm::vec3(c.points[c.begin(k) + i])) << k << "/" << i;
    }
}

TEST(BccExport, tubesToBccAreRefusedWithoutFile) {
    const std::string dir = test::scratchDir("bcc_tubes");
    ExportOptions o;
    o.path = dir + "/t.bcc";
    o.what = ExportWhat::Tubes;
    EXPECT_THROW(write(test::mixedCurves(), 0.001, o), Error);
    EXPECT_TRUE(test::listDir(dir).empty());
}

// ---- pbrt reader: Shape "curve" statements with their parameter lists ----
struct PbrtCurve {
    std::map<std::string, std::string> strings;
    std::map<std::string, double> numbers;
    std::vector<glm::dvec3> P;
};

std::vector<PbrtCurve> readPbrtCurves(const std::string& text) {
    std::vector<PbrtCurve> out;
    std::istringstream in(text);
    std::string tok;
    PbrtCurve* cur = nullptr;
    auto next = [&](std::string& t) { return static_cast<bool>(in >> t); };
    while (next(tok)) {
        if (tok[0] == '#') {
            std::getline(in, tok);
            continue;
        }
        if (tok == "Shape") {
            next(tok);
            if (tok == "\"curve\"") {
                out.emplace_back();
                cur = &out.back();
            } else {
                cur = nullptr;
            }
            continue;
        }
        if (!cur || tok[0] != '"') continue;
        // "type name" value | [ values ]
        std::string name;
        next(name);
        const std::string type = tok.substr(1);
        name = name.substr(0, name.size() - 1);
        std::string v;
        next(v);
        std::vector<std::string> values;
        if (v == "[") {
            while (next(v) && v != "]") values.push_back(v);
        } else {
            values.push_back(v);
        }
        if (type == "string") cur->strings[name] = values.at(0).substr(1, values[0].size() - 2);
        else if (type == "point3")
            for (size_t i = 0; i + 2 < values.size(); i += 3)
                cur->P.emplace_back(std::stod(values[i]), std::stod(values[i + 1]), std::stod(values[i + 2]));
        else cur->numbers[name] = std::stod(values.at(0));
    }
    return out;
}

TEST(PbrtExport, curvesAreCylinderBeziersConvertedFromCatmullRom) {
    const std::string dir = test::scratchDir("pbrt");
    const Polylines c = test::mixedCurves(glm::dvec3(0.25, 0, 0));
    ExportOptions o;
    o.path = dir + "/plies.pbrt";
    o.what = ExportWhat::Plies;
    write(c, 0.0004, o);
    const auto curves = readPbrtCurves(test::readText(o.path));
    ASSERT_EQ(curves.size(), 3u);
    for (size_t k = 0; k < 3; ++k) {
        const PbrtCurve& s = curves[k];
        EXPECT_EQ(s.strings.at("type"), "cylinder");
        EXPECT_EQ(s.strings.at("basis"), "bezier");
        EXPECT_EQ(s.numbers.at("degree"), 3);
        EXPECT_DOUBLE_EQ(s.numbers.at("width"), 0.0008);
        const size_t n = c.size(k);
        const bool closed = c.isClosed(k);
        const size_t segments = closed ? n : n - 1;
        ASSERT_EQ(s.P.size(), 3 * segments + 1) << "curve " << k;
        // Catmull-Rom control point i (with phantom ends / wrap) and the Bezier it implies.
        auto cr = [&](long i) {
            if (closed) return c.points[c.begin(k) + size_t((i % long(n) + long(n)) % long(n))];
            if (i < 0) return 2.0 * c.points[c.begin(k)] - c.points[c.begin(k) + 1];
            if (i >= long(n)) return 2.0 * c.points[c.end(k) - 1] - c.points[c.end(k) - 2];
            return c.points[c.begin(k) + size_t(i)];
        };
        for (size_t seg = 0; seg < segments; ++seg) {
            const glm::dvec3 p0 = cr(long(seg) - 1), p1 = cr(long(seg)), p2 = cr(long(seg) + 1), p3 = cr(long(seg) + 2);
            EXPECT_LT(glm::length(s.P[3 * seg] - p1), 1e-12);
            EXPECT_LT(glm::length(s.P[3 * seg + 1] - (p1 + (p2 - p0) / 6.0)), 1e-12);
            EXPECT_LT(glm::length(s.P[3 * seg + 2] - (p2 - (p3 - p1) / 6.0)), 1e-12);
            EXPECT_LT(glm::length(s.P[3 * seg + 3] - p2), 1e-12);
        }
        // The Bezier through these points passes through every Catmull-Rom point; at t = 1/2 it
        // equals the Catmull-Rom midpoint (-p0 + 9 p1 + 9 p2 - p3) / 16.
        const glm::dvec3 p0 = cr(0), p1 = cr(1), p2 = cr(2), p3 = cr(3);
        const glm::dvec3 mid = (s.P[3] + 3.0 * s.P[4] + 3.0 * s.P[5] + s.P[6]) / 8.0;
        EXPECT_LT(glm::length(mid - (-p0 + 9.0 * p1 + 9.0 * p2 - p3) / 16.0), 1e-12);
    }
    if (c.isClosed(1)) {
        EXPECT_LT(glm::length(curves[1].P.back() - curves[1].P.front()), 1e-15) << "closed curve ends at its start";
    }
}

TEST(PbrtExport, tubesAreTriangleMeshesWithMatchingCounts) {
    const std::string dir = test::scratchDir("pbrt_tubes");
    const Polylines c = test::mixedCurves();
    ExportOptions o;
    o.path = dir + "/tubes.pbrt";
    o.what = ExportWhat::Tubes;
    o.sides = 5;
    const ExportStats s = write(c, 0.001, o);
    const std::string text = test::readText(o.path);
    std::istringstream in(text);
    std::string tok;
    size_t P = 0, N = 0, uv = 0, idx = 0, meshes = 0;
    std::string current;
    while (in >> tok) {
        if (tok == "\"trianglemesh\"") ++meshes;
        if (tok == "\"point3" || tok == "\"normal" || tok == "\"point2" || tok == "\"integer") {
            in >> current >> tok;  // name, "["
            size_t count = 0;
            while (in >> tok && tok != "]") ++count;
            if (current == "P\"") P += count;
            if (current == "N\"") N += count;
            if (current == "uv\"") uv += count;
            if (current == "indices\"") idx += count;
        }
    }
    EXPECT_EQ(meshes, s.chunks);
    EXPECT_EQ(P, 3 * s.vertices);
    EXPECT_EQ(N, 3 * s.vertices);
    EXPECT_EQ(uv, 2 * s.vertices);
    EXPECT_EQ(idx, 3 * s.triangles);
}

// ---- binary PLY reader (header + little-endian elements) ----
struct PlyFile {
    std::vector<std::pair<std::string, size_t>> elements;
    std::map<std::string, std::vector<std::string>> properties;
    size_t dataStart = 0;
    std::vector<unsigned char> bytes;
};

PlyFile readPlyHeader(const std::string& path) {
    PlyFile f;
    f.bytes = test::readBytes(path);
    const std::string text(f.bytes.begin(), f.bytes.end());
    const size_t end = text.find("end_header\n");
    EXPECT_NE(end, std::string::npos);
    f.dataStart = end + 11;
    std::istringstream in(text.substr(0, end));
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "ply");
    std::getline(in, line);
    EXPECT_EQ(line, "format binary_little_endian 1.0");
    while (std::getline(in, line)) {
        std::istringstream ls(line);
        std::string kw;
        ls >> kw;
        if (kw == "element") {
            std::string name;
            size_t n;
            ls >> name >> n;
            f.elements.emplace_back(name, n);
        } else if (kw == "property") {
            f.properties[f.elements.back().first].push_back(line.substr(9));
        }
    }
    return f;
}

TEST(PlyExport, curvesAreVerticesAndEdgesIncludingClosingEdge) {
    const std::string dir = test::scratchDir("ply_curves");
    const Polylines c = test::mixedCurves(glm::dvec3(-1, 2, 3));
    ExportOptions o;
    o.path = dir + "/c.ply";
    o.what = ExportWhat::Yarns;
    write(c, 0.001, o);
    const PlyFile f = readPlyHeader(o.path);
    ASSERT_EQ(f.elements.size(), 2u);
    EXPECT_EQ(f.elements[0], std::make_pair(std::string("vertex"), c.pointCount()));
    const size_t edges = 39 + 32 + 24;
    EXPECT_EQ(f.elements[1], std::make_pair(std::string("edge"), edges));
    ASSERT_EQ(f.bytes.size(), f.dataStart + c.pointCount() * 24 + edges * 8);
    for (size_t i = 0; i < c.pointCount(); ++i) {
        glm::dvec3 p;
        std::memcpy(&p, &f.bytes[f.dataStart + i * 24], 24);
        EXPECT_EQ(p, c.points[i]);
    }
    // Edge 39 + 31 is the closing edge of the circle: last point -> first point.
    int32_t e[2];
    std::memcpy(e, &f.bytes[f.dataStart + c.pointCount() * 24 + (39 + 31) * 8], 8);
    EXPECT_EQ(e[0], int32_t(c.begin(1) + 31));
    EXPECT_EQ(e[1], int32_t(c.begin(1)));
}

TEST(PlyExport, tubeMeshStreamsChunksWithGlobalIndices) {
    const std::string dir = test::scratchDir("ply_tubes");
    const Polylines c = test::mixedCurves();
    ExportOptions o;
    o.path = dir + "/t.ply";
    o.what = ExportWhat::Tubes;
    o.sides = 6;
    o.chunkVertices = 250;
    const ExportStats s = write(c, 0.001, o);
    EXPECT_EQ(s.chunks, 3u);
    const PlyFile f = readPlyHeader(o.path);
    ASSERT_EQ(f.elements.size(), 2u);
    EXPECT_EQ(f.elements[0].second, s.vertices);
    EXPECT_EQ(f.elements[1].second, s.triangles);
    const size_t vsize = 3 * 8 + 5 * 4;
    ASSERT_EQ(f.bytes.size(), f.dataStart + s.vertices * vsize + s.triangles * 13);
    std::vector<int> used(s.vertices, 0);
    for (size_t t = 0; t < s.triangles; ++t) {
        const unsigned char* p = &f.bytes[f.dataStart + s.vertices * vsize + t * 13];
        ASSERT_EQ(p[0], 3);
        uint32_t idx[3];
        std::memcpy(idx, p + 1, 12);
        for (uint32_t i : idx) {
            ASSERT_LT(i, s.vertices);
            used[i] = 1;
        }
    }
    // Every vertex (ring, seam column, cap centre and rim) is referenced by some triangle.
    EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
    // Normals are unit.
    for (size_t i = 0; i < s.vertices; ++i) {
        float n[3];
        std::memcpy(n, &f.bytes[f.dataStart + i * vsize + 24], 12);
        ASSERT_NEAR(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0, 1e-6);
    }
}

}  // namespace
}  // namespace knit
