// mesh_ply.cpp — the PLY reader (ascii, binary little/big endian).
//
// One pass over the file (readPly): the header line by line, then every element against the
// declared properties — ASCII: one element per line, exactly the declared tokens, every token a
// finite number, list counts non-negative integers; binary: list counts in range and every
// element inside the file — recording positions, per-vertex UVs and the faces' vertex index
// lists as it goes; topology is rebuilt by welding (buildPolygonMesh).
//
// The reader is libknit's own: OpenMesh 9.0's PLY reader, which parsed the file a second time
// after this walk until issue 24, crashes on some malformed headers (a property before any
// element), sizes buffers from list counts it has not checked (a count of -4 allocated ~20 GB)
// and turns a non-numeric ASCII token (e.g. "nan") into zeros and empty faces without reporting
// failure — and the walk already read every value. A file loads exactly as OpenMesh's reader
// delivered it: positions and u,v / s,t (or only one of them; the other is 0) as float32;
// texture_u,texture_v / texture_s,texture_t (custom properties to OpenMesh, used when there is
// no u,v or s,t pair) as their declared float or double; faces as listed, fewer than 3 indices
// included (buildPolygonMesh names them); only the elements up to the first 'face' element are
// read, the rest only checked. Files OpenMesh read differently from their declared layout (a
// list it skipped as one value, a header it parsed out of place, a token it read in part) are
// refused naming the line or element (`refuse`): they loaded as garbage or failed before.
#include "mesh_reader.hpp"

#include "knit/error.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

namespace knit::impl {
namespace {

// What a property's values are recorded as.
enum class Slot { None, X, Y, Z, U, V, TexU, TexV };
// How OpenMesh 9.0's reader consumed a property (the layout a file is read with): as a float
// (positions, normals, u,v/s,t, float colours), an int (other colours), the face's index list,
// a custom property read by its type (beside texture_u/texture_v only), or skipped as one value.
enum class Read { Float, Int, Indices, Custom, Skip };

// A scalar type as the binary walk reads it: its size and whether it is a float, a signed
// integer or an unsigned one (set once per property by assignReads, not per value).
struct PlyScalar {
    int size = 0;
    bool isFloat = false, isSigned = false;
};
struct PlyProperty {
    bool list = false;
    std::string countType, type, name;
    Read read = Read::Skip;
    Slot slot = Slot::None;
    PlyScalar value, count;  // the binary layout of `type` and `countType`
};
struct PlyElement {
    std::string name;
    size_t count = 0;
    std::vector<PlyProperty> props;
    bool recorded = false;  // up to and including the first 'face' element
};
struct PlyHeader {
    bool ascii = false, bigEndian = false;
    std::vector<PlyElement> elements;
    bool hasTextureUV = false;  // texture_u/texture_v or texture_s/texture_t on the vertex element
    std::string textureU, textureV;
    bool vertexTexcoord = false;  // any of u, v, s, t on the vertex element
};

// What the walk recorded.
struct PlyData {
    std::vector<glm::dvec3> points;
    std::vector<glm::dvec2> uv;
    Polygons polys;
    // The first layout OpenMesh read differently, reported after the walk: one it failed on
    // (before the UV checks, as its failure was) or one it read wrongly (after them).
    std::string failed, refusal;
    void fail(const std::string& message) {
        if (failed.empty()) failed = message;
    }
    void refuse(const std::string& message) {
        if (refusal.empty()) refusal = message;
    }
};

int plyTypeSize(const std::string& t) {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32") return 4;
    if (t == "double" || t == "float64") return 8;
    return 0;
}
bool plyFloatType(const std::string& t) { return t == "float" || t == "float32" || t == "double" || t == "float64"; }
bool plySignedType(const std::string& t) {
    return t == "char" || t == "int8" || t == "short" || t == "int16" || t == "int" || t == "int32";
}

PlyScalar plyScalar(const std::string& type) {
    return {plyTypeSize(type), type == "float" || type == "float32", plySignedType(type)};
}

// A binary scalar at `at` as a double (integers exactly up to 2^53).
double plyBinaryValue(const std::string& body, size_t at, const PlyScalar& type, bool bigEndian) {
    const int n = type.size;
    unsigned char b[8];
    for (int i = 0; i < n; ++i) b[i] = static_cast<unsigned char>(body[at + (bigEndian ? n - 1 - i : i)]);
    uint64_t u = 0;
    for (int i = n - 1; i >= 0; --i) u = (u << 8) | b[i];
    if (type.isFloat) {
        float f;
        const uint32_t u32 = uint32_t(u);
        std::memcpy(&f, &u32, 4);
        return f;
    }
    if (n == 8) {
        double d;
        std::memcpy(&d, &u, 8);
        return d;
    }
    if (type.isSigned) {
        const uint64_t sign = uint64_t(1) << (8 * n - 1);
        return double(int64_t(u ^ sign) - int64_t(sign));
    }
    return double(u);
}

// OpenMesh 9.0's binary PLY reader converts only float/double data to its float-valued vertex
// properties (positions, normals, texture coordinates), only integer or float data to colours,
// and only integer data to face indices; a property of any other type is skipped without
// consuming its bytes, which desynchronises the rest of the file (garbage values, or minutes
// spent reading a misread list count: tests/fuzz_corpus/ply/timeout-*). Refused up front.
void checkPlyConvertible(const PlyHeader& h, const std::string& path) {
    static const char* kFloatValued[] = {"x", "y", "z", "nx", "ny", "nz", "u", "v", "s", "t"};
    static const char* kColours[] = {"red", "green", "blue", "alpha", "diffuse_red", "diffuse_green", "diffuse_blue"};
    for (const PlyElement& e : h.elements)
        for (const PlyProperty& p : e.props) {
            const bool isDouble = p.type == "double" || p.type == "float64";
            std::string need;
            if (p.list && (p.name == "vertex_indices" || p.name == "vertex_index") && plyFloatType(p.type))
                need = "an integer type";
            else if (!p.list && e.name == "vertex" &&
                     std::any_of(std::begin(kFloatValued), std::end(kFloatValued),
                                 [&](const char* n) { return p.name == n; }) &&
                     !plyFloatType(p.type))
                need = "float or double";
            else if (!p.list && isDouble &&
                     std::any_of(std::begin(kColours), std::end(kColours), [&](const char* n) { return p.name == n; }))
                need = "an integer type or float";
            if (!need.empty())
                failMesh(path, "binary PLY property '" + p.type + " " + p.name + "' of element '" + e.name +
                                   "' is not supported (its type must be " + need + ")");
        }
}

// "file:line: what" as failMeshLine words it, for a refusal reported after the walk.
std::string lineMessage(const std::string& path, size_t lineNo, const std::string& what) {
    return path + ":" + std::to_string(lineNo) + ": " + what;
}

// OpenMesh read ASCII values with `std::istream >> T`, which stops inside a token it cannot read
// whole ("2.0" as an index reads 2 and leaves ".0" for the next value) or fails; the walk accepts
// a token only where that read takes all of it, as these say (the token is a finite number).
bool plainInteger(const std::string& t) {
    const size_t s = !t.empty() && (t[0] == '+' || t[0] == '-') ? 1 : 0;
    return t.size() > s && t.find_first_not_of("0123456789", s) == std::string::npos;
}
// `>> unsigned` (and unsigned short): a sign is allowed and wraps ("-1" is 4294967295).
bool wholeUnsigned(const std::string& t, unsigned long long max, int& value) {
    if (!plainInteger(t)) return false;
    const bool negative = t[0] == '-';
    const size_t digits = t[0] == '+' || negative ? 1 : 0;
    errno = 0;
    const unsigned long long m = std::strtoull(t.c_str() + digits, nullptr, 10);
    if (errno == ERANGE || m > max) return false;
    const uint32_t u = negative ? uint32_t(0u - uint32_t(m)) : uint32_t(m);
    value = static_cast<int>(u);  // OpenMesh's VertexHandle(int(idx))
    return true;
}
bool wholeSigned(const std::string& t, long long lo, long long hi) {
    if (!plainInteger(t)) return false;
    errno = 0;
    const long long v = std::strtoll(t.c_str(), nullptr, 10);
    return errno != ERANGE && v >= lo && v <= hi;
}
// `>> float` / `>> double` take a decimal number whole; a hexadecimal one ("0x1p3") only to the 'x'.
bool wholeDecimal(const std::string& t) { return t.find_first_of("xX") == std::string::npos; }
// A custom property read by its declared type (char types as one character).
bool wholeOfType(const std::string& type, const std::string& t) {
    int ignored = 0;
    if (plyFloatType(type)) return wholeDecimal(t);
    if (plyTypeSize(type) == 1) return t.size() == 1;
    if (type == "short" || type == "int16") return wholeSigned(t, SHRT_MIN, SHRT_MAX);
    if (type == "ushort" || type == "uint16") return wholeUnsigned(t, USHRT_MAX, ignored);
    if (type == "int" || type == "int32") return wholeSigned(t, INT_MIN, INT_MAX);
    return wholeUnsigned(t, UINT_MAX, ignored);
}

// A float-valued slot as recorded: positions and u,v in float32, texture_u,... as declared.
void record(Slot slot, double value, bool asFloat, glm::dvec3& p, glm::dvec2& uv) {
    const double v = asFloat ? double(float(value)) : value;
    switch (slot) {
        case Slot::X: p.x = v; break;
        case Slot::Y: p.y = v; break;
        case Slot::Z: p.z = v; break;
        case Slot::U:
        case Slot::TexU: uv.x = v; break;
        case Slot::V:
        case Slot::TexV: uv.y = v; break;
        case Slot::None: break;
    }
}
bool slotAsFloat(const PlyProperty& p) {
    return (p.slot != Slot::TexU && p.slot != Slot::TexV) || p.type == "float" || p.type == "float32";
}
Read readOf(const PlyProperty& p, const PlyHeader& h) {
    return p.read == Read::Custom && !h.hasTextureUV ? Read::Skip : p.read;  // customs only beside texture_u
}

// `>> unsigned` on a token it stops inside: the leading [+-]digits (none: 0), as an index.
int prefixUnsigned(const std::string& t) {
    const size_t s = t[0] == '+' || t[0] == '-' ? 1 : 0;
    const size_t e = t.find_first_not_of("0123456789", s);
    int value = 0;
    if (e == s || !wholeUnsigned(t.substr(0, e), UINT_MAX, value)) value = e == s ? 0 : -1;  // overflow: UINT_MAX
    return value;
}

// One ASCII element line (its tokens and their values), read as OpenMesh read it. `lastRead`: the
// last line OpenMesh read (the last face), whose last token it may have read in part.
void recordAscii(const std::string& path, size_t lineNo, const PlyElement& e, const PlyHeader& h,
                 const std::vector<std::string>& toks, const std::vector<double>& values, bool lastRead, PlyData& d) {
    const bool vertex = e.name == "vertex";
    glm::dvec3 p(0.0);
    glm::dvec2 uv(0.0);
    size_t at = 0;
    bool indicesRead = false;  // on the last line, nothing read after the indices is recorded
    auto refuse = [&](const PlyProperty& prop, const std::string& tok, const char* need) {
        if (lastRead && indicesRead) return;
        d.refuse(lineMessage(
            path, lineNo, "'" + tok + "' in property '" + prop.name + "' of element '" + e.name + "' must be " + need));
    };
    for (const PlyProperty& prop : e.props) {
        const Read read = readOf(prop, h);
        if (!prop.list) {
            const std::string& tok = toks[at];
            if (read == Read::Float || (read == Read::Custom && plyFloatType(prop.type))) {
                if (!wholeDecimal(tok)) refuse(prop, tok, "a decimal number");
                const bool asFloat = read == Read::Float || slotAsFloat(prop);
                record(prop.slot, asFloat ? double(std::strtof(tok.c_str(), nullptr)) : values[at], asFloat, p, uv);
            } else if (read == Read::Int) {
                if (!wholeSigned(tok, INT_MIN, INT_MAX)) refuse(prop, tok, "an integer");
            } else if (read == Read::Custom) {
                if (!wholeOfType(prop.type, tok))
                    refuse(prop, tok, plyTypeSize(prop.type) == 1 ? "one character" : "an integer in its type's range");
            }
            ++at;
            continue;
        }
        const size_t count = size_t(values[at]);
        int index = 0;
        if (read == Read::Skip) {
            // OpenMesh skipped a list it did not read as one value: only an empty one stays in step.
            if (count != 0 && !(lastRead && indicesRead))
                d.refuse(
                    lineMessage(path, lineNo,
                                "list '" + prop.name + "' of element '" + e.name +
                                    "' must be empty: lists other than the face's vertex_indices are read only beside "
                                    "texture_u/texture_v, and a non-empty one was misread"));
            at += 1 + count;
            continue;
        }
        if (!wholeUnsigned(toks[at], UINT_MAX, index)) refuse(prop, toks[at], "a plain integer count");
        ++at;
        for (size_t c = 0; c < count; ++c, ++at) {
            if (read == Read::Indices) {
                if (lastRead && at + 1 == toks.size())
                    index = prefixUnsigned(toks[at]);  // what is left of it is never read
                else if (!wholeUnsigned(toks[at], UINT_MAX, index))
                    refuse(prop, toks[at], "a plain integer vertex index");
                d.polys.faceVerts.push_back(index);
            } else if (!wholeOfType(prop.type, toks[at])) {
                refuse(prop, toks[at], plyTypeSize(prop.type) == 1 ? "one character" : "a number of its type");
            }
        }
        if (read == Read::Indices) {
            d.polys.faceStart.push_back(uint32_t(d.polys.faceVerts.size()));
            indicesRead = true;
        }
    }
    if (vertex) {
        d.points.push_back(p);
        d.uv.push_back(uv);
    }
}

void walkAscii(const std::string& file, size_t pos, size_t lineNo, const std::string& path, const PlyHeader& h,
               PlyData& d) {
    std::vector<std::string> toks;
    std::vector<double> values;
    for (const PlyElement& e : h.elements)
        for (size_t k = 0; k < e.count; ++k) {
            // One element per line (blank lines skipped), every token a finite number.
            values.clear();
            toks.clear();
            while (values.empty()) {
                if (pos >= file.size())
                    failMesh(path, "file ends inside element '" + e.name + "' " + std::to_string(k) + " of " +
                                       std::to_string(e.count) + " (truncated?)");
                size_t end = file.find('\n', pos);
                if (end == std::string::npos) end = file.size();
                ++lineNo;
                for (size_t i = pos; i < end;) {
                    while (i < end && std::isspace(static_cast<unsigned char>(file[i]))) ++i;
                    const size_t b = i;
                    while (i < end && !std::isspace(static_cast<unsigned char>(file[i]))) ++i;
                    if (i > b) toks.emplace_back(file, b, i - b);
                }
                pos = end + 1;
                double v = 0;
                for (const std::string& tok : toks) {
                    if (!parseFinite(tok, v)) failMeshLine(path, lineNo, "'" + tok + "' is not a finite number");
                    requireFloatRange(path, lineNo, tok, v);
                    values.push_back(v);
                }
            }
            // Exactly the declared properties; list counts are non-negative integers.
            size_t at = 0;
            for (const PlyProperty& p : e.props) {
                if (at >= values.size()) failMeshLine(path, lineNo, "too few values for element '" + e.name + "'");
                if (p.list) {
                    const double n = values[at++];
                    if (n < 0 || n != std::floor(n) || n > double(values.size() - at))
                        failMeshLine(path, lineNo, "list '" + p.name + "' has a bad count");
                    at += size_t(n);
                } else {
                    ++at;
                }
            }
            if (at != values.size()) failMeshLine(path, lineNo, "too many values for element '" + e.name + "'");
            if (e.recorded) {
                const bool lastRead = e.name == "face" && k + 1 == e.count;
                recordAscii(path, lineNo, e, h, toks, values, lastRead, d);
            }
        }
}

// Binary: walk the elements through the bytes, recording as OpenMesh read them.
void walkBinary(const std::string& body, size_t at, const std::string& path, const PlyHeader& h, PlyData& d) {
    for (const PlyElement& e : h.elements) {
        // An element without properties holds no bytes: nothing to walk, however many it declares
        // (a count of 2^53 would otherwise spin for ever: tests/fuzz_corpus/ply/timeout-3d69138e...).
        if (e.props.empty()) continue;
        const bool vertex = e.recorded && e.name == "vertex";
        for (size_t k = 0; k < e.count; ++k) {
            glm::dvec3 point(0.0);
            glm::dvec2 uv(0.0);
            for (const PlyProperty& p : e.props) {
                auto truncated = [&] {
                    failMesh(path, "file ends inside element '" + e.name + "' " + std::to_string(k) + " of " +
                                       std::to_string(e.count) + " (truncated?)");
                };
                const Read read = readOf(p, h);
                if (!p.list) {
                    const PlyScalar& type = p.value;
                    const size_t n = size_t(type.size);
                    if (body.size() - at < n) truncated();
                    if (vertex && p.slot != Slot::None)
                        record(p.slot, plyBinaryValue(body, at, type, h.bigEndian), slotAsFloat(p), point, uv);
                    at += n;
                    continue;
                }
                const PlyScalar &countType = p.count, &type = p.value;
                const size_t cn = size_t(countType.size), n = size_t(type.size);
                if (body.size() - at < cn) truncated();
                const double count = plyBinaryValue(body, at, countType, h.bigEndian);
                at += cn;
                if (count < 0 || count > double(body.size() - at) / double(n))
                    failMesh(path, "element '" + e.name + "' " + std::to_string(k) + ": list '" + p.name +
                                       "' has a bad count (" + std::to_string(count) + ")");
                if (e.recorded && read == Read::Indices) {
                    for (size_t c = 0; c < size_t(count); ++c) {
                        const double v = plyBinaryValue(body, at + c * n, type, h.bigEndian);
                        d.polys.faceVerts.push_back(static_cast<int>(uint32_t(int64_t(v))));
                    }
                    d.polys.faceStart.push_back(uint32_t(d.polys.faceVerts.size()));
                } else if (e.recorded && read == Read::Skip && cn + size_t(count) * n != n &&
                           !(e.name == "face" && k + 1 == e.count && &p == &e.props.back() &&
                             at - cn + n <= body.size())) {
                    // OpenMesh skipped one value of the list's type: the rest of the file was misread
                    // (harmlessly only after a list ending the last face, if that stayed in the file).
                    d.refuse(path + ": element '" + e.name + "' " + std::to_string(k) + ": list '" + p.name +
                             "' is not supported in a binary file: lists other than the face's vertex_indices are read "
                             "only beside texture_u/texture_v, and this one was misread");
                }
                at += size_t(count) * n;
            }
            if (vertex) {
                d.points.push_back(point);
                d.uv.push_back(uv);
            }
        }
    }
}

// Where OpenMesh 9.0 took each property's values from (the layout a file was read with), and the
// header layouts it parsed differently from the walk, refused (they failed or loaded wrongly).
void assignReads(const std::string& path, PlyHeader& h, PlyData& d) {
    static const char* kColours[] = {"red", "green", "blue", "alpha", "diffuse_red", "diffuse_green", "diffuse_blue"};
    bool seenFace = false, seenVertex = false;
    for (PlyElement& e : h.elements) {
        e.recorded = !seenFace;
        if (e.name == "vertex" || e.name == "face") {
            if (e.name == "vertex" ? seenVertex : seenFace)
                d.refuse(path + ": a second '" + e.name + "' element (only one is supported)");
            (e.name == "vertex" ? seenVertex : seenFace) = true;
        }
        for (size_t i = 0; i < e.props.size(); ++i) {
            PlyProperty& p = e.props[i];
            p.value = plyScalar(p.type);
            if (p.list) p.count = plyScalar(p.countType);
            if (!p.list && plyTypeSize(p.name))
                d.refuse(path + ": property '" + p.type + " " + p.name + "' of element '" + e.name +
                         "' is named after a type (not supported)");
            if (e.name == "vertex") {
                // A property declared twice is read twice (the last value counts), except that
                // OpenMesh's ASCII reader wanted x, y, z once each.
                for (size_t j = 0; j < i; ++j)
                    if (h.ascii && e.props[j].name == p.name && !p.list && !e.props[j].list &&
                        (p.name == "x" || p.name == "y" || p.name == "z"))
                        d.fail(path + ": property '" + p.name + "' of element 'vertex' is declared twice");
                const std::string& n = p.name;
                if (p.list) p.read = Read::Custom;
                else if (n == "x" || n == "y" || n == "z")
                    p.read = Read::Float, p.slot = Slot(int(Slot::X) + (n[0] - 'x'));
                else if (n == "nx" || n == "ny" || n == "nz") p.read = Read::Float;
                else if (n == "u" || n == "s" || n == "v" || n == "t") {
                    p.read = Read::Float;
                    h.vertexTexcoord = true;
                    if (!h.hasTextureUV) p.slot = n == "u" || n == "s" ? Slot::U : Slot::V;
                } else if (std::any_of(std::begin(kColours), std::end(kColours), [&](const char* c) { return n == c; }))
                    p.read = p.type == "float" || p.type == "float32" ? Read::Float : Read::Int;
                else {
                    p.read = Read::Custom;
                    // A custom property declared with two types was two properties; the float
                    // one was taken, else the double one.
                    auto taken = [&](const std::string& name) {
                        if (!h.hasTextureUV || n != name || !plyFloatType(p.type)) return false;
                        const bool isFloat = p.type == "float" || p.type == "float32";
                        return isFloat || !std::any_of(e.props.begin(), e.props.end(), [&](const PlyProperty& q) {
                                   return !q.list && q.name == name && (q.type == "float" || q.type == "float32");
                               });
                    };
                    if (taken(h.textureU)) p.slot = Slot::TexU;
                    if (taken(h.textureV)) p.slot = Slot::TexV;
                }
            } else if (e.name == "face") {
                if (p.list && (p.name == "vertex_indices" || p.name == "vertex_index")) {
                    p.read = Read::Indices;
                    // OpenMesh dropped the face properties declared before the index list.
                    if (i > 0)
                        d.refuse(path + ": property '" + e.props[0].name +
                                 "' of element 'face' comes before its vertex_indices list (not supported)");
                } else {
                    p.read = Read::Custom;
                }
            }
            // OpenMesh read list counts of these types only.
            if (p.list && p.countType != "uchar" && p.countType != "uint8" && p.countType != "uint16" &&
                p.countType != "int")
                d.fail(path + ": list '" + p.name + "' of element '" + e.name + "' has count type '" + p.countType +
                       "' (supported: uchar, uint8, uint16, int)");
        }
        if (e.count > UINT_MAX) d.refuse(path + ": element '" + e.name + "' has more than 4294967295 entries");
    }
}

PlyHeader readPly(const std::string& path, PlyData& d) {
    std::ifstream in(path, std::ios::binary);
    if (!in) failMesh(path, "cannot open for reading");
    const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    PlyHeader h;
    std::string line, word;
    size_t lineNo = 0, pos = 0;
    // Where OpenMesh's header parse stood before 'end_header' (after the last token it read, or
    // after a comment line), which it took binary data to start 12 bytes after (14 after "\r\n").
    size_t omPos = 0;
    bool ended = false, hasFormat = false, contentBeforeFormat = false;
    while (!ended && pos < file.size()) {
        size_t end = file.find('\n', pos);
        if (end == std::string::npos) end = file.size();
        line.assign(file, pos, end - pos);
        const size_t lineStart = pos;
        pos = std::min(end + 1, file.size());
        ++lineNo;
        std::istringstream ls(trimmed(line));
        word.clear();
        ls >> word;
        if (lineNo == 1) {
            if (word != "ply") failMesh(path, "not a PLY file (the first line is not 'ply')");
            if (trimmed(line) != "ply") d.fail(lineMessage(path, 1, "the first line must be just 'ply'"));
            omPos = pos;
            continue;
        }
        if (word.empty()) continue;
        if (word == "end_header" && trimmed(line) == "end_header") {
            ended = true;
            continue;
        }
        if (word == "comment") {
            omPos = pos;
        } else {
            size_t last = line.size();
            while (last > 0 && std::isspace(static_cast<unsigned char>(line[last - 1]))) --last;
            omPos = lineStart + last;
        }
        if (word == "comment") {
            if (!hasFormat) contentBeforeFormat = true;
            continue;
        }
        if (word == "obj_info") {
            // OpenMesh read an obj_info line's words as header keywords.
            std::string w;
            while (ls >> w)
                if (w == "element" || w == "property" || w == "end_header")
                    d.refuse(lineMessage(path, lineNo, "an obj_info line may not contain the word '" + w + "'"));
            if (!hasFormat) contentBeforeFormat = true;
            continue;
        }
        if (word == "format") {
            std::string fmt, version, extra;
            ls >> fmt >> version >> extra;
            double v = 0;
            if (fmt != "ascii" && fmt != "binary_little_endian" && fmt != "binary_big_endian")
                failMeshLine(path, lineNo, "unknown PLY format '" + fmt + "'");
            // PLY has only version 1.0; OpenMesh loops forever on other versions.
            if (!parseFinite(version, v) || v != 1.0 || !extra.empty())
                failMeshLine(path, lineNo, "the format line must be 'format " + fmt + " 1.0'");
            // OpenMesh took the three words after 'ply' as the format line.
            if (hasFormat) d.refuse(lineMessage(path, lineNo, "a second format line"));
            else if (contentBeforeFormat)
                d.fail(lineMessage(path, lineNo, "the format line must come right after the 'ply' line"));
            h.ascii = fmt == "ascii";
            h.bigEndian = fmt == "binary_big_endian";
            hasFormat = true;
            continue;
        }
        if (!hasFormat) contentBeforeFormat = true;
        if (word == "element") {
            PlyElement e;
            std::string count, extra;
            ls >> e.name >> count >> extra;
            long n = 0;
            if (e.name.empty() || !(count == "0" || parseIndex(count, n)) || n < 0 || !extra.empty())
                failMeshLine(path, lineNo, "element line needs a name and a non-negative count");
            e.count = size_t(n);
            h.elements.push_back(e);
        } else if (word == "property") {
            if (h.elements.empty()) failMeshLine(path, lineNo, "property line before any element line");
            PlyProperty p;
            ls >> p.type;
            if (p.type == "list") {
                p.list = true;
                ls >> p.countType >> p.type;
                if (!plyTypeSize(p.countType) || plyFloatType(p.countType) || !plyTypeSize(p.type))
                    failMeshLine(path, lineNo, "bad list property types '" + p.countType + " " + p.type + "'");
            } else if (!plyTypeSize(p.type)) {
                failMeshLine(path, lineNo, "unknown property type '" + p.type + "'");
            }
            std::string extra;
            ls >> p.name >> extra;
            if (p.name.empty() || !extra.empty())
                failMeshLine(path, lineNo, "a property line must be 'property TYPE NAME'");
            h.elements.back().props.push_back(p);
        } else {
            failMeshLine(path, lineNo, "unexpected PLY header line '" + trimmed(line) + "'");
        }
    }
    if (!ended) failMesh(path, "PLY header has no end_header line");
    if (!hasFormat) failMesh(path, "PLY header has no format line");
    // The vertex element needs x, y, z; the face element a vertex index list.
    const PlyElement* vertex = nullptr;
    const PlyElement* face = nullptr;
    for (const PlyElement& e : h.elements) {
        if (e.name == "vertex") vertex = &e;
        if (e.name == "face") face = &e;
    }
    if (!vertex) failMesh(path, "the PLY file has no vertex element");
    if (!face || face->count == 0) failMesh(path, "the mesh has no faces");
    auto has = [&](const char* n) {
        return std::any_of(vertex->props.begin(), vertex->props.end(),
                           [&](const PlyProperty& p) { return !p.list && p.name == n; });
    };
    if (!has("x") || !has("y") || !has("z")) failMesh(path, "the PLY vertex element needs x, y and z properties");
    if (!std::any_of(face->props.begin(), face->props.end(), [](const PlyProperty& p) {
            return p.list && (p.name == "vertex_indices" || p.name == "vertex_index");
        }))
        failMesh(path, "the PLY face element has no vertex_indices list");
    const bool known = (has("u") && has("v")) || (has("s") && has("t"));
    if (!known) {
        if (has("texture_u") && has("texture_v")) h.textureU = "texture_u", h.textureV = "texture_v";
        else if (has("texture_s") && has("texture_t")) h.textureU = "texture_s", h.textureV = "texture_t";
        h.hasTextureUV = !h.textureU.empty();
    }
    if (!h.ascii) checkPlyConvertible(h, path);
    assignReads(path, h, d);
    if (h.ascii) {
        walkAscii(file, pos, lineNo, path, h, d);
    } else {
        const bool crlf = omPos + 1 < file.size() && file[omPos] == '\r' && file[omPos + 1] == '\n';
        if (omPos + (crlf ? 14 : 12) != pos)
            d.refuse(path + ": in a binary PLY file 'end_header' must directly follow the last header line (no "
                            "comment, blank line or trailing spaces before it, one line ending): where the data "
                            "starts is ambiguous");
        walkBinary(file, pos, path, h, d);
    }
    return h;
}

}  // namespace

BaseMesh readPlyMesh(const std::string& path, const MeshLoadOptions& options) {
    PlyData d;
    const PlyHeader h = readPly(path, d);
    if (!d.failed.empty()) throw Error(d.failed);
    // UVs per vertex: texture_u,texture_v (float or double) or u,v / s,t.
    if (h.hasTextureUV) {
        auto declared = [&](const std::string& name) {
            for (const PlyElement& e : h.elements)
                if (e.name == "vertex")
                    for (const PlyProperty& p : e.props)
                        if (!p.list && p.name == name && plyFloatType(p.type)) return true;
            return false;
        };
        if (!declared(h.textureU) || !declared(h.textureV))
            failMesh(path, "could not read vertex properties " + h.textureU + "/" + h.textureV);
    } else if (!h.vertexTexcoord) {
        failMesh(path, "no per-vertex texture coordinates (u,v / s,t / texture_u,texture_v); libknit needs UVs");
    }
    if (!d.refusal.empty()) throw Error(d.refusal);
    return buildPolygonMesh(path, d.polys, d.points, d.uv, false, nullptr, options);
}

}  // namespace knit::impl
