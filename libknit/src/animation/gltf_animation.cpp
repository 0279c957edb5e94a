// gltf_animation.cpp — GltfAnimation: a glTF / GLB with morph-target or skinned animation,
// sampled as meshes. Read with the project's one glTF reader (gltf_document.hpp); the posed
// positions go through the base-mesh reader (mesh_gltf.hpp), so welding and UVs are loadMesh's.
//
// Per sample time: channels -> node transforms and morph weights -> world matrices (parents
// first) -> per primitive: POSITION + sum(w_i target_i) -> skin (linear blend of joint world x
// inverse bind) or the node's world transform.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>

#include "io/gltf_document.hpp"
#include "knit/animation.hpp"
#include "knit/error.hpp"
#include "mesh/mesh_gltf.hpp"
#include "util/platform.hpp"

namespace knit {
namespace {

using json = nlohmann::json;

enum class Path { Translation, Rotation, Scale, Weights };
enum class Interpolation { Linear, Step, CubicSpline };

// One animation channel with its sampler's keys: `width` values per key (CUBICSPLINE: in-tangent,
// value, out-tangent, each `width` wide).
struct Channel {
    size_t node = 0;
    Path path = Path::Translation;
    Interpolation interpolation = Interpolation::Linear;
    std::vector<double> times, values;
    size_t width = 0;
};

// A node's local transform parts (the node's own, overridden by channels) and its morph weights.
struct NodePose {
    glm::dvec3 t{0.0}, s{1.0};
    glm::dquat r{1.0, 0.0, 0.0, 0.0};
    std::vector<double> weights;
    bool hasMatrix = false;
    glm::dmat4 matrix{1.0};
};

Path pathOf(const gltf::Document& d, const std::string& path, const std::string& where) {
    if (path == "translation") return Path::Translation;
    if (path == "rotation") return Path::Rotation;
    if (path == "scale") return Path::Scale;
    if (path == "weights") return Path::Weights;
    d.fail(where + ": target path '" + path + "' is not translation, rotation, scale or weights");
}

// Step 1: the channels of animation `a`, each with its sampler's times and values.
std::vector<Channel> readChannels(const gltf::Document& d, size_t a) {
    const json& anim = d.element("animations", a, "the animation input");
    const std::string where = "animations[" + std::to_string(a) + "]";
    const json& samplers = d.member(anim, "samplers", json::value_t::array, where);
    std::vector<Channel> out;
    const json& channels = d.member(anim, "channels", json::value_t::array, where);
    for (size_t c = 0; c < channels.size(); ++c) {
        const std::string cw = where + ".channels[" + std::to_string(c) + "]";
        const json& target = d.member(channels[c], "target", json::value_t::object, cw);
        const auto node = d.index(target, "node", cw + ".target");
        if (!node) continue;  // no node: ignored, as the spec allows
        Channel ch;
        ch.node = *node;
        ch.path = pathOf(d, target.value("path", std::string()), cw);
        const size_t s = d.asIndex(channels[c].value("sampler", json()), cw + ".sampler");
        if (s >= samplers.size()) d.fail(cw + ": sampler " + std::to_string(s) + " does not exist");
        const json& sampler = samplers[s];
        const std::string interp = sampler.value("interpolation", std::string("LINEAR"));
        ch.interpolation = interp == "STEP"          ? Interpolation::Step
                           : interp == "CUBICSPLINE" ? Interpolation::CubicSpline
                                                     : Interpolation::Linear;
        ch.times = d.accessor(d.asIndex(sampler.value("input", json()), cw), cw + " input").values();
        ch.values = d.accessor(d.asIndex(sampler.value("output", json()), cw), cw + " output").values();
        const size_t perKey = ch.values.size() / std::max<size_t>(ch.times.size(), 1);
        ch.width = ch.interpolation == Interpolation::CubicSpline ? perKey / 3 : perKey;
        for (size_t k = 0; k < ch.times.size(); ++k)
            if (!std::isfinite(ch.times[k]) || (k > 0 && !(ch.times[k] > ch.times[k - 1])))
                d.fail(cw + ": the sampler's input time " + std::to_string(k) +
                       " is not finite or not after the previous one (key times must increase)");
        for (size_t k = 0; k < ch.values.size(); ++k)
            if (!std::isfinite(ch.values[k]))
                d.fail(cw + ": the sampler's output value " + std::to_string(k) + " is not finite");
        if (ch.times.empty() || ch.width == 0 || perKey * ch.times.size() != ch.values.size())
            d.fail(cw + ": the sampler's output does not match its " + std::to_string(ch.times.size()) + " keys");
        // A transform path has a fixed width (weights: one per morph target, any count).
        const size_t width = ch.path == Path::Rotation ? 4 : ch.path == Path::Weights ? ch.width : 3;
        if (ch.width != width || (ch.interpolation == Interpolation::CubicSpline && perKey != 3 * width))
            d.fail(cw + ": a " + target.value("path", std::string()) + " channel needs " + std::to_string(width) +
                   " numbers per key, but its sampler's output has " + std::to_string(perKey) + " per key (" +
                   std::to_string(ch.values.size()) + " numbers for " + std::to_string(ch.times.size()) + " keys)");
        out.push_back(std::move(ch));
    }
    if (out.empty()) d.fail(where + " has no channel that targets a node");
    return out;
}

// The value (`width` numbers) of key k: the middle element for CUBICSPLINE.
const double* keyValue(const Channel& c, size_t k, size_t part = 1) {
    const size_t stride = c.interpolation == Interpolation::CubicSpline ? 3 * c.width : c.width;
    const size_t offset = c.interpolation == Interpolation::CubicSpline ? part * c.width : 0;
    return c.values.data() + k * stride + offset;
}

// Step 2: a channel's value at time t (clamped to its first / last key).
std::vector<double> sampleChannel(const Channel& c, double t) {
    const size_t n = c.times.size();
    std::vector<double> v(c.width);
    const size_t k1 = size_t(std::upper_bound(c.times.begin(), c.times.end(), t) - c.times.begin());
    if (k1 == 0 || k1 == n || c.interpolation == Interpolation::Step) {
        const double* x = keyValue(c, k1 == 0 ? 0 : k1 - 1);
        std::copy(x, x + c.width, v.begin());
        return v;
    }
    const size_t k0 = k1 - 1;
    const double dt = c.times[k1] - c.times[k0], u = dt > 0 ? (t - c.times[k0]) / dt : 0.0;
    const double *a = keyValue(c, k0), *b = keyValue(c, k1);
    if (c.interpolation == Interpolation::CubicSpline) {  // Hermite with the keys' tangents
        const double *ta = keyValue(c, k0, 2), *tb = keyValue(c, k1, 0);
        const double u2 = u * u, u3 = u2 * u;
        for (size_t i = 0; i < c.width; ++i)
            v[i] = (2 * u3 - 3 * u2 + 1) * a[i] + (u3 - 2 * u2 + u) * dt * ta[i] + (-2 * u3 + 3 * u2) * b[i] +
                   (u3 - u2) * dt * tb[i];
    } else if (c.path == Path::Rotation) {
        const glm::dquat q = glm::slerp(glm::dquat(a[3], a[0], a[1], a[2]), glm::dquat(b[3], b[0], b[1], b[2]), u);
        v = {q.x, q.y, q.z, q.w};
    } else {
        for (size_t i = 0; i < c.width; ++i) v[i] = a[i] + u * (b[i] - a[i]);
    }
    return v;
}

// The node's own pose (before animation).
NodePose restPose(const gltf::Document& d, size_t i) {
    const json& n = d.element("nodes", i, "the animation input");
    const std::string where = "nodes[" + std::to_string(i) + "]";
    NodePose p;
    if (n.contains("matrix")) p.hasMatrix = true, p.matrix = d.localTransform(i);
    if (auto t = d.numbers(n, "translation", 3, where); !t.empty()) p.t = {t[0], t[1], t[2]};
    if (auto r = d.numbers(n, "rotation", 4, where); !r.empty()) p.r = glm::dquat(r[3], r[0], r[1], r[2]);
    if (auto s = d.numbers(n, "scale", 3, where); !s.empty()) p.s = {s[0], s[1], s[2]};
    if (n.contains("weights") && n["weights"].is_array()) p.weights = n["weights"].get<std::vector<double>>();
    else if (auto m = d.index(n, "mesh", where)) {
        const json& mesh = d.element("meshes", *m, where);
        if (mesh.contains("weights") && mesh["weights"].is_array())
            p.weights = mesh["weights"].get<std::vector<double>>();
    }
    return p;
}

glm::dmat4 localMatrix(const NodePose& p) {
    if (p.hasMatrix) return p.matrix;
    const double len = glm::length(p.r);
    const glm::dquat q = len > 0 ? p.r / len : glm::dquat(1.0, 0.0, 0.0, 0.0);
    return glm::scale(glm::translate(glm::dmat4(1.0), p.t) * glm::mat4_cast(q), p.s);
}

// Step 3: every node's world matrix at time t, and its morph weights.
void poseNodes(const gltf::Document& d, const std::vector<Channel>& channels, const std::vector<size_t>& parent,
               double t, std::vector<glm::dmat4>& world, std::vector<std::vector<double>>& weights) {
    const size_t n = parent.size();
    std::vector<NodePose> pose(n);
    for (size_t i = 0; i < n; ++i) pose[i] = restPose(d, i);
    for (const Channel& c : channels) {
        if (c.node >= n)
            d.fail("an animation channel targets node " + std::to_string(c.node) + ", which does not exist");
        const std::vector<double> v = sampleChannel(c, t);
        NodePose& p = pose[c.node];
        if (c.path == Path::Translation && v.size() == 3) p.t = {v[0], v[1], v[2]};
        else if (c.path == Path::Rotation && v.size() == 4) p.r = glm::dquat(v[3], v[0], v[1], v[2]);
        else if (c.path == Path::Scale && v.size() == 3) p.s = {v[0], v[1], v[2]};
        else if (c.path == Path::Weights) p.weights = v;
        else d.fail("an animation channel of node " + std::to_string(c.node) + " has values of the wrong width");
    }
    world.assign(n, glm::dmat4(1.0));
    std::vector<char> done(n, 0);
    for (size_t i = 0; i < n; ++i) {
        std::vector<size_t> chain;  // i and its ancestors not yet placed, child first
        for (size_t j = i; j != SIZE_MAX && !done[j]; j = parent[j]) chain.push_back(j);
        for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
            const size_t p = parent[*it];
            world[*it] = (p == SIZE_MAX ? glm::dmat4(1.0) : world[p]) * localMatrix(pose[*it]);
            done[*it] = 1;
        }
    }
    weights.resize(n);
    for (size_t i = 0; i < n; ++i) weights[i] = std::move(pose[i].weights);
}

std::vector<size_t> parentsOf(const gltf::Document& d) {
    const json& nodes = d.member(d.root(), "nodes", json::value_t::array, "the file");
    std::vector<size_t> parent(nodes.size(), SIZE_MAX);
    for (size_t i = 0; i < nodes.size(); ++i)
        for (const json& c : d.member(nodes[i], "children", json::value_t::array, "nodes[" + std::to_string(i) + "]")) {
            const size_t k = d.asIndex(c, "nodes[" + std::to_string(i) + "].children");
            if (k >= nodes.size()) d.fail("nodes[" + std::to_string(i) + "] has a child that does not exist");
            parent[k] = i;
        }
    return parent;
}

}  // namespace

struct GltfAnimation::State {
    explicit State(gltf::Document d) : doc(std::move(d)) {}
    gltf::Document doc;
    std::vector<Channel> channels;
    std::vector<size_t> parent;
    std::vector<double> times;
};

GltfAnimation::GltfAnimation(const std::string& path, double fps, size_t animation)
    : GltfAnimation(std::make_unique<State>(gltf::Document::load(path)), fps, animation) {}

std::unique_ptr<GltfAnimation> GltfAnimation::fromBytes(const std::string& bytes, const std::string& name, double fps,
                                                        size_t animation) {
    return std::unique_ptr<GltfAnimation>(
        new GltfAnimation(std::make_unique<State>(gltf::Document(bytes, name, "")), fps, animation));
}

GltfAnimation::GltfAnimation(std::unique_ptr<State> state, double fps, size_t animation) : state_(std::move(state)) {
    State& s = *state_;
    if (s.doc.member(s.doc.root(), "animations", json::value_t::array, "the file").size() <= animation)
        s.doc.fail("has no animation " + std::to_string(animation) + " (give a mesh sequence or an animated glTF)");
    s.channels = readChannels(s.doc, animation);
    s.parent = parentsOf(s.doc);
    // The sample times: the keyframes, or k / fps up to the last key.
    for (const Channel& c : s.channels) s.times.insert(s.times.end(), c.times.begin(), c.times.end());
    std::sort(s.times.begin(), s.times.end());
    s.times.erase(std::unique(s.times.begin(), s.times.end()), s.times.end());
    constexpr double kMaxSamples = 1e6;
    if (fps > 0) {
        const double last = s.times.back();
        if (!std::isfinite(fps) || !(last * fps < kMaxSamples))
            s.doc.fail("sampling its animation (last key at " + std::to_string(last) + " s) at the frame rate " +
                       std::to_string(fps) + " gives more than 1e6 frames; lower the frame rate");
        s.times.clear();
        for (size_t k = 0; double(k) / fps <= last + 1e-9; ++k) s.times.push_back(double(k) / fps);
    }
}

GltfAnimation::~GltfAnimation() = default;

const std::vector<double>& GltfAnimation::times() const { return state_->times; }

BaseMesh GltfAnimation::sample(size_t i, const MeshLoadOptions& options) const {
    const State& s = *state_;
    const gltf::Document& d = s.doc;
    std::vector<glm::dmat4> world;
    std::vector<std::vector<double>> weights;
    poseNodes(d, s.channels, s.parent, s.times.at(i), world, weights);
    const impl::GltfPoser poser = [&](const gltf::MeshInstance& inst, const gltf::Primitive& p,
                                      const gltf::Accessor& P) {
        // Morph targets: POSITION + sum of weight x target POSITION.
        std::vector<glm::dvec3> v(P.count);
        for (size_t k = 0; k < P.count; ++k) v[k] = {P.get(k, 0), P.get(k, 1), P.get(k, 2)};
        if (inst.node == gltf::MeshInstance::kNoNode) return v;  // no scene: nothing animates
        const json& targets = d.member(*p.object, "targets", json::value_t::array, p.what);
        const std::vector<double>& w = weights.at(inst.node);
        for (size_t t = 0; t < targets.size() && t < w.size(); ++t) {
            const auto a = d.index(targets[t], "POSITION", p.what + " target " + std::to_string(t));
            if (!a || w[t] == 0) continue;
            const gltf::Accessor T = d.accessor(*a, p.what + " target " + std::to_string(t));
            if (T.count != P.count || T.components != 3)
                d.fail(p.what + ": target " + std::to_string(t) + " POSITION does not match POSITION");
            for (size_t k = 0; k < P.count; ++k) v[k] += w[t] * glm::dvec3(T.get(k, 0), T.get(k, 1), T.get(k, 2));
        }
        // Skin (the node's own transform is ignored, as glTF specifies) or the node's world.
        const json& node = d.element("nodes", inst.node, p.what);
        const auto skin = d.index(node, "skin", p.what);
        if (!skin) {
            for (glm::dvec3& x : v) x = glm::dvec3(world[inst.node] * glm::dvec4(x, 1.0));
            return v;
        }
        const std::string sw = "skins[" + std::to_string(*skin) + "]";
        const json& sk = d.element("skins", *skin, p.what);
        std::vector<glm::dmat4> joint;
        for (const json& j : d.member(sk, "joints", json::value_t::array, sw)) {
            const size_t n = d.asIndex(j, sw + ".joints");
            if (n >= world.size()) d.fail(sw + ": joint node " + std::to_string(n) + " does not exist");
            joint.push_back(world[n]);
        }
        if (const auto ibm = d.index(sk, "inverseBindMatrices", sw)) {
            const std::vector<double> m = d.accessor(*ibm, sw + " inverseBindMatrices").values();
            if (m.size() != 16 * joint.size()) d.fail(sw + ": inverseBindMatrices does not hold one matrix per joint");
            for (size_t j = 0; j < joint.size(); ++j) {
                glm::dmat4 b;
                for (int c = 0; c < 4; ++c)
                    for (int r = 0; r < 4; ++r) b[c][r] = m[16 * j + size_t(4 * c + r)];
                joint[j] = joint[j] * b;
            }
        }
        std::vector<glm::dvec3> out(P.count, glm::dvec3(0.0));
        for (int set = 0;; ++set) {
            const auto J = d.attribute(p, ("JOINTS_" + std::to_string(set)).c_str());
            const auto W = d.attribute(p, ("WEIGHTS_" + std::to_string(set)).c_str());
            if (!J || !W) {
                if (set == 0) d.fail(p.what + " is skinned but has no JOINTS_0 / WEIGHTS_0");
                break;
            }
            const gltf::Accessor ja = d.accessor(*J, p.what + " JOINTS"), wa = d.accessor(*W, p.what + " WEIGHTS");
            if (ja.count != P.count || wa.count != P.count || ja.components != 4 || wa.components != 4)
                d.fail(p.what + ": JOINTS_" + std::to_string(set) + " / WEIGHTS_" + std::to_string(set) +
                       " do not match POSITION");
            // glTF 2.0 (3.7.3.1): joint indices are unsigned bytes or shorts, never normalized.
            if ((ja.componentType != 5121 && ja.componentType != 5123) || ja.normalized)
                d.fail(p.what + ": JOINTS_" + std::to_string(set) +
                       " must hold unsigned bytes or unsigned shorts (componentType 5121 or 5123), not componentType " +
                       std::to_string(ja.componentType) + (ja.normalized ? " normalized" : ""));
            for (size_t k = 0; k < P.count; ++k)
                for (int c = 0; c < 4; ++c) {
                    const double wt = wa.get(k, c);
                    if (!std::isfinite(wt))
                        d.fail(p.what + ": vertex " + std::to_string(k) +
                               " has a weight that is not finite in WEIGHTS_" + std::to_string(set));
                    if (wt == 0) continue;
                    const size_t j = size_t(ja.get(k, c));
                    if (j >= joint.size())
                        d.fail(p.what + ": vertex " + std::to_string(k) + " uses joint " + std::to_string(j) + " of " +
                               std::to_string(joint.size()));
                    out[k] += wt * glm::dvec3(joint[j] * glm::dvec4(v[k], 1.0));
                }
        }
        return out;
    };
    return impl::gltfMeshOf(d, options, &poser);
}

bool isGltfAnimationSource(const std::string& source) {
    const std::string ext = util::lowerExtension(source);
    std::error_code ec;
    return (ext == "glb" || ext == "gltf") && source.find('%') == std::string::npos &&
           std::filesystem::is_regular_file(source, ec);
}

}  // namespace knit
