// Strain table files: the project's `T.npy` + `T.axes.txt` and MADYPG's `sxsasy/` folder
// (axes.txt + data.npy), see knit/strain.hpp. The .npy format is NumPy's documented format 1.0
// (numpy.lib.format): magic "\x93NUMPY", version, a little-endian header length, an ASCII dict
// {'descr', 'fortran_order', 'shape'} padded so the data starts at a multiple of 64 bytes.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

#include "io/atomic_file.hpp"
#include "knit/error.hpp"
#include "knit/strain.hpp"

namespace knit {
namespace {

constexpr uint64_t kMaxTableBytes = uint64_t(1) << 31;  // 2 GiB: far beyond any table (400 vertices, 9^3: 4.7 MB)
const char kMagic[] = "\x93NUMPY";

// The value after `'key':` in a .npy header dict, up to the next top-level comma or brace.
std::string dictValue(const std::string& header, const std::string& key, const std::string& source) {
    const size_t k = header.find("'" + key + "'");
    if (k == std::string::npos) throw Error(source + ": the .npy header has no '" + key + "'");
    size_t p = header.find(':', k);
    if (p == std::string::npos) throw Error(source + ": the .npy header's '" + key + "' has no value");
    ++p;
    while (p < header.size() && header[p] == ' ') ++p;
    size_t e = p;
    int depth = 0;
    for (; e < header.size(); ++e) {
        const char c = header[e];
        if (c == '(') ++depth;
        if (c == ')') --depth;
        if (depth == 0 && (c == ',' || c == '}')) break;
        if (depth < 0) break;
    }
    std::string v = header.substr(p, e - p + (e < header.size() && header[e] == ')' ? 1 : 0));
    while (!v.empty() && v.back() == ' ') v.pop_back();
    return v;
}

// The shape tuple "(R, 4)" -> R; anything else is refused.
uint64_t parseShape(const std::string& shape, const std::string& source) {
    uint64_t rows = 0, cols = 0;
    char tail = 0;
    std::istringstream in(shape);
    char open = 0, comma = 0;
    in >> open >> rows >> comma >> cols >> tail;
    if (!in || open != '(' || comma != ',' || tail != ')' || cols != 4)
        throw Error(source + ": the .npy array's shape is " + shape + "; a strain table is (rows, 4)");
    return rows;
}

struct NpyArray {
    uint64_t rows = 0;
    bool doubles = false;
    size_t dataOffset = 0;
};

NpyArray parseNpyHeader(const std::string& npy, const std::string& source) {
    if (npy.size() < 10 || npy.compare(0, 6, kMagic, 6) != 0)
        throw Error(source + ": not a NumPy .npy file (no \\x93NUMPY magic)");
    const auto major = uint8_t(npy[6]);
    size_t headerLen = 0, start = 0;
    if (major == 1) {
        headerLen = size_t(uint8_t(npy[8])) | size_t(uint8_t(npy[9])) << 8;
        start = 10;
    } else if (major == 2 || major == 3) {
        if (npy.size() < 12) throw Error(source + ": the .npy header is truncated");
        for (int i = 0; i < 4; ++i) headerLen |= size_t(uint8_t(npy[size_t(8 + i)])) << (8 * i);
        start = 12;
    } else {
        throw Error(source + ": .npy format version " + std::to_string(major) + " is not supported (1, 2 or 3)");
    }
    if (headerLen > npy.size() - start) throw Error(source + ": the .npy header is truncated");
    const std::string header = npy.substr(start, headerLen);
    NpyArray a;
    const std::string descr = dictValue(header, "descr", source);
    if (descr == "'<f4'" || descr == "'|f4'") a.doubles = false;
    else if (descr == "'<f8'") a.doubles = true;
    else throw Error(source + ": the .npy data type is " + descr + "; a strain table is float32 ('<f4')");
    if (dictValue(header, "fortran_order", source) != "False")
        throw Error(source + ": the .npy array is in Fortran order; a strain table is C order");
    a.rows = parseShape(dictValue(header, "shape", source), source);
    a.dataOffset = start + headerLen;
    const uint64_t bytes = a.rows > kMaxTableBytes ? 0 : a.rows * 4 * (a.doubles ? 8 : 4);
    if (a.rows > kMaxTableBytes || bytes != npy.size() - a.dataOffset) {
        std::ostringstream m;
        m << source << ": the .npy header declares " << a.rows << " rows of 4 (" << bytes
          << " bytes) but the file holds " << npy.size() - a.dataOffset << " bytes of data";
        throw Error(m.str());
    }
    return a;
}

// Axes text: '#' lines are metadata ("# key value..."), then three lines of sample values (blanks
// or commas between them).
struct AxesFile {
    std::array<std::vector<double>, 3> axes;
    std::string pattern;
    double px = 0, py = 0, radius = 0;
    size_t vertices = 0;
    bool own = false;  // written by this project (has the metadata)
};

AxesFile parseAxes(const std::string& text, const std::string& source) {
    AxesFile f;
    std::istringstream in(text);
    std::string line;
    size_t axis = 0;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        const std::string where = source + ":" + std::to_string(lineNo);
        if (!line.empty() && line[0] == '#') {
            std::istringstream meta(line.substr(1));
            std::string key;
            meta >> key;
            if (key == "pattern") std::getline(meta >> std::ws, f.pattern);
            if (key == "vertices" && !(meta >> f.vertices)) throw Error(where + ": the vertex count is not a number");
            if (key == "period" && !(meta >> f.px >> f.py)) throw Error(where + ": the period is not two numbers");
            if (key == "radius" && !(meta >> f.radius)) throw Error(where + ": the radius is not a number");
            if (key == "libknit") f.own = true;
            continue;
        }
        for (char& c : line)
            if (c == ',') c = ' ';
        // A line without values is blank, whatever white space it holds (a form feed included:
        // counted as an axis, it made an axis of no samples and a table of none).
        std::istringstream values(line);
        std::vector<std::string> tokens;
        for (std::string token; values >> token;) tokens.push_back(token);
        if (tokens.empty()) continue;
        if (axis == 3) throw Error(where + ": more than three lines of axis values (sx, sa, sy)");
        for (const std::string& token : tokens) {
            char* end = nullptr;
            const double v = std::strtod(token.c_str(), &end);
            if (end == token.c_str() || *end != '\0' || !std::isfinite(v))
                throw Error(where + ": '" + token + "' is not a finite number");
            std::vector<double>& a = f.axes[axis];
            if (!a.empty() && !(v > a.back()))
                throw Error(where + ": the sample values must increase (" + token + " after " +
                            std::to_string(a.back()) + ")");
            if (a.size() >= 4096) throw Error(where + ": more than 4096 samples");
            a.push_back(v);
        }
        ++axis;
    }
    if (axis != 3) throw Error(source + ": " + std::to_string(axis) + " lines of axis values; need three (sx, sa, sy)");
    if (f.own && !(f.px > 0 && f.py > 0 && std::isfinite(f.px) && std::isfinite(f.py)))
        throw Error(source + ": the period must be two positive numbers");
    return f;
}

std::string readWhole(const std::string& path, const std::string& what) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw Error("cannot read " + what + " '" + path + "': no such file");
    const uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw Error("cannot read " + what + " '" + path + "': " + ec.message());
    if (size > kMaxTableBytes)
        throw Error(path + ": " + std::to_string(size) + " bytes; a strain table is at most 2 GiB");
    std::ifstream in(path, std::ios::binary);
    std::string bytes(size_t(size), '\0');
    if (!in || !in.read(bytes.data(), std::streamsize(size))) throw Error("cannot read " + what + " '" + path + "'");
    return bytes;
}

}  // namespace

StrainTable parseStrainTable(const std::string& npy, const std::string& axesText, const std::string& source) {
    const AxesFile axes = parseAxes(axesText, source + " (axes)");
    const NpyArray a = parseNpyHeader(npy, source);
    StrainTable t;
    t.source = source;
    t.axes = axes.axes;
    const uint64_t perVertex = uint64_t(t.axes[0].size()) * t.axes[1].size() * t.axes[2].size();
    if (a.rows == 0 || a.rows % perVertex != 0) {
        std::ostringstream m;
        m << source << ": " << a.rows << " rows is not a multiple of the " << perVertex << " strain samples ("
          << t.axes[0].size() << " x " << t.axes[1].size() << " x " << t.axes[2].size() << ")";
        throw Error(m.str());
    }
    t.vertexCount = size_t(a.rows / perVertex);
    if (axes.own && axes.vertices != t.vertexCount)
        throw Error(source + ": the axes file says " + std::to_string(axes.vertices) + " vertices, the data holds " +
                    std::to_string(t.vertexCount));
    t.data.resize(size_t(a.rows) * 4);
    const char* p = npy.data() + a.dataOffset;
    for (size_t i = 0; i < t.data.size(); ++i) {
        float v = 0;
        if (a.doubles) {
            double d = 0;
            std::memcpy(&d, p + 8 * i, 8);
            v = float(d);
        } else {
            std::memcpy(&v, p + 4 * i, 4);
        }
        if (!std::isfinite(v)) {
            const size_t row = i / 4;
            std::ostringstream m;
            m << source << ": row " << row << " (vertex " << row / perVertex << ") column " << i % 4
              << " is not finite";
            throw Error(m.str());
        }
        t.data[i] = v;
    }
    t.pattern = axes.pattern;
    t.px = axes.px;
    t.py = axes.py;
    t.radius = axes.radius;
    return t;
}

std::string strainAxesPath(const std::string& npyPath) {
    const std::string ext = ".npy";
    if (npyPath.size() > ext.size() && npyPath.compare(npyPath.size() - ext.size(), ext.size(), ext) == 0)
        return npyPath.substr(0, npyPath.size() - ext.size()) + ".axes.txt";
    return npyPath + ".axes.txt";
}

StrainTable loadStrainTable(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
        const std::string dir = (std::filesystem::path(path) / "").string();
        const std::string npy = readWhole(dir + "data.npy", "the strain table");
        StrainTable t = parseStrainTable(npy, readWhole(dir + "axes.txt", "the strain table's axes"), dir + "data.npy");
        t.source = path;
        return t;
    }
    const std::string npy = readWhole(path, "the strain table");
    return parseStrainTable(npy, readWhole(strainAxesPath(path), "the strain table's axes (beside the table)"), path);
}

void writeStrainTable(const StrainTable& table, const std::string& path) {
    if (table.data.size() != 4 * table.vertexCount * table.samples())
        throw Error("writing the strain table '" + path + "': its data does not match its axes and vertex count");
    // The header: the dict padded with blanks to end in '\n' at a multiple of 64 bytes.
    std::string dict = "{'descr': '<f4', 'fortran_order': False, 'shape': (" +
                       std::to_string(table.vertexCount * table.samples()) + ", 4), }";
    const size_t unpadded = 10 + dict.size() + 1;
    dict.append((64 - unpadded % 64) % 64, ' ');
    dict.push_back('\n');
    impl::AtomicFile npy(path, true), axes(strainAxesPath(path), false);
    std::ostream& o = npy.stream();
    o.write(kMagic, 6);
    o.put(char(1)).put(char(0));
    o.put(char(dict.size() & 0xff)).put(char((dict.size() >> 8) & 0xff));
    o << dict;
    static_assert(std::numeric_limits<float>::is_iec559, "float32 tables");
    o.write(reinterpret_cast<const char*>(table.data.data()), std::streamsize(table.data.size() * sizeof(float)));
    std::ostream& a = axes.stream();
    a << "# libknit strain table: three lines of samples (sx, sa, sy); data in "
      << std::filesystem::path(path).filename().string() << "\n";
    a << "# pattern " << table.pattern << "\n# vertices " << table.vertexCount << "\n";
    a << std::setprecision(17) << "# period " << table.px << " " << table.py << "\n# radius " << table.radius << "\n";
    for (const std::vector<double>& axis : table.axes) {
        for (size_t i = 0; i < axis.size(); ++i) a << (i ? " " : "") << axis[i];
        a << "\n";
    }
    npy.close();
    axes.close();
    npy.commit();
    try {
        axes.commit();
    } catch (...) {
        npy.undoCommit();
        throw;
    }
}

void checkStrainTable(const StrainTable& table, const Pattern& pattern) {
    if (table.vertexCount != pattern.points.size())
        throw Error("the strain table '" + table.source + "' is for " + std::to_string(table.vertexCount) +
                    " cell vertices; the pattern '" + pattern.name + "' has " + std::to_string(pattern.points.size()));
    if (table.px > 0 &&
        (std::abs(table.px - pattern.px) > 1e-6 * pattern.px || std::abs(table.py - pattern.py) > 1e-6 * pattern.py)) {
        std::ostringstream m;
        m << "the strain table '" << table.source << "' was made for the period " << table.px << " x " << table.py
          << " m; the pattern '" << pattern.name << "' has " << pattern.px << " x " << pattern.py << " m";
        throw Error(m.str());
    }
}

}  // namespace knit
