// glTF 2.0 scenes (.gltf, .glb) mapped to brdfbake lobes.
//
// Only the JSON document is read (for a .glb its JSON chunk), with nlohmann-json: materials,
// which materials the mesh primitives and the KHR_materials_variants mappings use, and the
// images of the textures that decide a range. Geometry buffers are never read, so a .gltf whose
// .bin is elsewhere, a meshopt- or Draco-compressed file (a buffer without a uri) and a .glb all
// plan alike. Every value is read with its type checked: a wrong type is an error naming the
// file, the material and the key.
//
// The core metallic-roughness material is GGX with alpha = roughness^2 (Smith height-correlated
// masking-shadowing, as the glTF specification's appendix B). A metal is a conductor lobe whose
// Fresnel is Schlick with f0 = baseColor: its albedo and average albedo tables are computed with
// F = 1 and the Fresnel enters at render time. A non-metal is a dielectric interface with eta 1.5
// (or KHR_materials_ior): its rough reflection (and, with transmission, transmission) albedo comes
// from the dielectric table. A factor multiplied by a texture takes the range of the texture's
// values (the channel the specification names, times the factor) when the image can be read
// (texture_image.h), else [0, factor] with a warning naming the image. The extensions that change
// which tables are needed are mapped; every other extension is reported by name.
// docs/scenes.md has the table of this mapping.
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>

#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "models/input_file.h"
#include "models/key_reader.h"
#include "scene/gltf_extensions.h"
#include "scene/json_read.h"
#include "scene/scene.h"
#include "scene/texture_image.h"

namespace brdfbake {
namespace {

using json = nlohmann::json;

/// The largest .gltf document, JSON chunk of a .glb, or image read (bytes).
constexpr std::uintmax_t kMaxDocumentBytes = std::uintmax_t(256) << 20;
constexpr std::uintmax_t kMaxImageBytes = std::uintmax_t(256) << 20;

std::string fmt(double v) { return format_number(v); }

std::string range_text(Interval r) { return r.lo == r.hi ? fmt(r.lo) : "[" + fmt(r.lo) + ", " + fmt(r.hi) + "]"; }

Interval square(Interval r) { return {r.lo * r.lo, r.hi * r.hi}; }

std::string type_name(const json& v) { return v.type_name(); }

/// The glTF document: its JSON, and where the binary chunk of a .glb lies in the file.
struct Document {
    std::string path, dir, label;  // label: "glTF 'PATH'"
    json j;
    bool glb = false;
    std::uint64_t bin_offset = 0, bin_length = 0;
    bool has_bin = false;
    std::map<long, std::optional<ChannelRanges>> images;  // decoded, by image index
    std::map<long, std::string> image_problem;             // why an image cannot be read
    std::map<long, std::string> image_name;
};

std::string folder_of(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

std::uint32_t le32(const std::string& b, std::size_t at) {
    return std::uint32_t(static_cast<unsigned char>(b[at])) | std::uint32_t(static_cast<unsigned char>(b[at + 1])) << 8 |
           std::uint32_t(static_cast<unsigned char>(b[at + 2])) << 16 |
           std::uint32_t(static_cast<unsigned char>(b[at + 3])) << 24;
}

/// `length` bytes of a regular file from `offset`; throws Error naming `what`.
std::string read_range(const std::string& path, std::uint64_t offset, std::uint64_t length, const std::string& what) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("cannot read " + what + " '" + path + "': " + std::strerror(errno));
    in.seekg(std::streamoff(offset));
    std::string out(std::size_t(length), '\0');
    in.read(&out[0], std::streamsize(length));
    if (std::uint64_t(in.gcount()) != length) throw Error(what + " '" + path + "' is truncated");
    return out;
}

/// Opens the document: a .gltf through read_input_file, a .glb by its header and JSON chunk only
/// (its binary chunk is read only where an image lies in it).
Document open_document(const std::string& path) {
    Document d;
    d.path = path;
    d.dir = folder_of(path);
    d.label = "glTF '" + path + "'";
    struct stat st;
    if (::stat(path.c_str(), &st) != 0) throw Error("cannot read scene '" + path + "': " + std::strerror(errno));
    std::string head;
    if (S_ISREG(st.st_mode) && st.st_size >= 4) head = read_range(path, 0, 4, "scene");
    std::string text;
    if (head == "glTF") {
        d.glb = true;
        const std::uint64_t size = std::uint64_t(st.st_size);
        const auto broken = [&](const std::string& why) { return Error(d.label + " cannot be read: " + why); };
        if (size < 20) throw broken("truncated .glb (no JSON chunk)");
        const std::string h = read_range(path, 0, 20, "scene");
        if (le32(h, 4) != 2) throw broken("glTF binary version " + std::to_string(le32(h, 4)) + " (this build reads 2)");
        const std::uint64_t total = le32(h, 8), json_length = le32(h, 12);
        if (total > size) throw broken("truncated .glb (header says " + std::to_string(total) + " bytes, file has " +
                                       std::to_string(size) + ")");
        if (le32(h, 16) != 0x4E4F534Au) throw broken("the first chunk of a .glb must be JSON");
        if (20 + json_length > total) throw broken("truncated .glb (JSON chunk runs past the end)");
        if (json_length > kMaxDocumentBytes) throw broken("JSON chunk larger than 256 MiB");
        text = read_range(path, 20, json_length, "scene");
        const std::uint64_t next = 20 + ((json_length + 3) & ~std::uint64_t(3));
        if (next + 8 <= total) {
            const std::string c = read_range(path, next, 8, "scene");
            if (le32(c, 4) == 0x004E4942u && next + 8 + le32(c, 0) <= total) {
                d.has_bin = true;
                d.bin_offset = next + 8;
                d.bin_length = le32(c, 0);
            }
        }
    } else {
        text = read_input_file(path, "scene", kMaxDocumentBytes);
    }
    d.j = scene_json::parse_strict(text, d.label);
    if (!d.j.is_object()) throw Error(d.label + " cannot be read: the document is not a JSON object");
    if (!d.j.contains("asset") || !d.j["asset"].is_object())
        throw Error(d.label + " cannot be read: no 'asset' object (every glTF file has one)");
    const json& asset = d.j["asset"];
    if (!asset.contains("version") || !asset["version"].is_string())
        throw Error(d.label + " cannot be read: 'asset.version' must be a string");
    const std::string version = asset["version"].get<std::string>();
    if (version.rfind("2.", 0) != 0)
        throw Error(d.label + " cannot be read: glTF version " + version + " (this build reads 2.x)");
    return d;
}

// --- typed access: a wrong type is an error naming the file, the material and the key ---------

/// The array at `key` of the document (empty when absent).
const json& top_array(const Document& d, const char* key) {
    static const json empty = json::array();
    if (!d.j.contains(key)) return empty;
    if (!d.j[key].is_array()) throw Error(d.label + ": '" + key + "' must be an array, not " + type_name(d.j[key]));
    return d.j[key];
}

/// An object member that must be an object if present.
const json* object_at(const json& o, const std::string& key, const std::string& where) {
    if (!o.is_object() || !o.contains(key)) return nullptr;
    const json& v = o[key];
    if (!v.is_object()) throw Error(where + ": '" + key + "' must be an object, not " + type_name(v));
    return &v;
}

double number_at(const json* o, const std::string& key, double fallback, const std::string& where) {
    if (!o || !o->contains(key)) return fallback;
    const json& v = (*o)[key];
    if (!v.is_number())
        throw Error(where + ": '" + key + "' must be a number, not " + type_name(v) + " " + v.dump());
    return v.get<double>();
}

long index_at(const json& o, const std::string& key, std::size_t count, const std::string& what, const std::string& where) {
    const json& v = o[key];
    if (!v.is_number_integer() || v.get<long long>() < 0)
        throw Error(where + ": '" + key + "' must be a non-negative whole number, not " + v.dump());
    const long i = long(v.get<long long>());
    if (std::size_t(i) >= count)
        throw Error(where + ": '" + key + "' refers to " + what + " " + std::to_string(i) + ", which does not exist (" +
                    std::to_string(count) + " in the file)");
    return i;
}

std::vector<double> numbers_at(const json* o, const std::string& key, std::vector<double> fallback, const std::string& where) {
    if (!o || !o->contains(key)) return fallback;
    const json& a = (*o)[key];
    if (!a.is_array()) throw Error(where + ": '" + key + "' must be an array of numbers, not " + type_name(a));
    std::vector<double> out;
    for (const auto& x : a) {
        if (!x.is_number()) throw Error(where + ": '" + key + "' must hold numbers, not " + type_name(x) + " " + x.dump());
        out.push_back(x.get<double>());
    }
    return out;
}

void check_factor(const std::string& where, const std::string& what, double v, double lo, double hi) {
    if (!std::isfinite(v) || v < lo || v > hi)
        throw Error(where + ": " + what + " " + fmt(v) + " is out of range [" + fmt(lo) + ", " + fmt(hi) + "]");
}

// --- images: the values a texture holds ----------------------------------------------------------

/// The bytes of image `i`, or nullopt with the reason in `problem`.
std::optional<std::string> image_bytes(Document& d, long i, std::string& problem, std::string& name) {
    const json& img = top_array(d, "images")[std::size_t(i)];
    const std::string where = d.label + ": image " + std::to_string(i);
    if (!img.is_object()) throw Error(where + " must be an object");
    name = img.contains("name") && img["name"].is_string() ? img["name"].get<std::string>() : "image " + std::to_string(i);
    auto from_data_uri = [&](const std::string& uri) -> std::optional<std::string> {
        const size_t comma = uri.find(',');
        if (comma == std::string::npos || uri.rfind(";base64", comma) == std::string::npos) {
            problem = "its data: URI is not base64";
            return std::nullopt;
        }
        std::optional<std::string> bytes = base64_decode(uri.substr(comma + 1));
        if (!bytes) problem = "its data: URI holds invalid base64";
        return bytes;
    };
    if (img.contains("uri")) {
        if (!img["uri"].is_string()) throw Error(where + ": 'uri' must be a string");
        const std::string uri = img["uri"].get<std::string>();
        if (uri.rfind("data:", 0) == 0) {
            name += " (data URI)";
            return from_data_uri(uri);
        }
        name = uri;
        try {
            return read_input_file(d.dir + percent_decode(uri), "texture image", kMaxImageBytes);
        } catch (const Error& e) {
            problem = e.what();
            return std::nullopt;
        }
    }
    if (!img.contains("bufferView")) {
        problem = "it has neither a uri nor a bufferView";
        return std::nullopt;
    }
    const json& views = top_array(d, "bufferViews");
    const long v = index_at(img, "bufferView", views.size(), "buffer view", where);
    const json& view = views[std::size_t(v)];
    const std::string vwhere = d.label + ": bufferViews[" + std::to_string(v) + "]";
    if (!view.is_object() || !view.contains("buffer")) throw Error(vwhere + " has no 'buffer'");
    const json& buffers = top_array(d, "buffers");
    const long b = index_at(view, "buffer", buffers.size(), "buffer", vwhere);
    const double offset = number_at(&view, "byteOffset", 0, vwhere), length = number_at(&view, "byteLength", -1, vwhere);
    if (!(offset >= 0 && length >= 0)) throw Error(vwhere + ": needs a non-negative 'byteLength' and 'byteOffset'");
    if (length > double(kMaxImageBytes)) {
        problem = "it is larger than 256 MiB";
        return std::nullopt;
    }
    const json& buffer = buffers[std::size_t(b)];
    if (buffer.is_object() && buffer.contains("uri") && buffer["uri"].is_string()) {
        const std::string uri = buffer["uri"].get<std::string>();
        if (uri.rfind("data:", 0) == 0) {
            std::optional<std::string> all = from_data_uri(uri);
            if (!all) return all;
            if (offset + length > double(all->size())) {
                problem = "its buffer view runs past the end of buffer " + std::to_string(b);
                return std::nullopt;
            }
            return all->substr(std::size_t(offset), std::size_t(length));
        }
        try {
            return read_range(d.dir + percent_decode(uri), std::uint64_t(offset), std::uint64_t(length), "buffer");
        } catch (const Error& e) {
            problem = std::string("its buffer cannot be read: ") + e.what();
            return std::nullopt;
        }
    }
    if (d.glb && b == 0 && d.has_bin) {
        if (offset + length > double(d.bin_length)) {
            problem = "its buffer view runs past the end of the binary chunk";
            return std::nullopt;
        }
        return read_range(d.path, d.bin_offset + std::uint64_t(offset), std::uint64_t(length), "scene");
    }
    problem = "its buffer holds no data in this file (a buffer without a uri outside a .glb)";
    return std::nullopt;
}

/// The channel ranges of the image texture `t` uses, decoded once per image; nullopt with the
/// reason in `problem` and the image's name in `name`.
std::optional<ChannelRanges> texture_ranges(Document& d, long t, std::string& problem, std::string& name) {
    const json& tex = top_array(d, "textures")[std::size_t(t)];
    const std::string where = d.label + ": texture " + std::to_string(t);
    if (!tex.is_object()) throw Error(where + " must be an object");
    if (!tex.contains("source")) {
        // Only an image of a texture-format extension (KTX2, WebP, AVIF).
        const json* ext = object_at(tex, "extensions", where);
        name = "texture " + std::to_string(t);
        problem = ext && !ext->empty() ? "its only image is one of " + ext->begin().key() + ", which this build does not decode"
                                       : "it has no image";
        return std::nullopt;
    }
    const json& images = top_array(d, "images");
    const long i = index_at(tex, "source", images.size(), "image", where);
    auto cached = d.images.find(i);
    if (cached == d.images.end()) {
        std::string why, image_name;
        std::optional<ChannelRanges> ranges;
        if (std::optional<std::string> bytes = image_bytes(d, i, why, image_name)) {
            const std::string format = image_format(*bytes);
            if (format == "png") {
                try {
                    ranges = png_channel_ranges(*bytes, "image '" + image_name + "'");
                } catch (const Error& e) {
                    why = e.what();
                }
            } else if (format == "jpeg") {
                try {
                    ranges = jpeg_channel_ranges(*bytes, "image '" + image_name + "'");
                } catch (const Error& e) {
                    why = e.what();
                }
            } else {
                why = format.empty() ? "its format is not recognised" : "it is " + format + ", which this build does not decode";
            }
        }
        cached = d.images.emplace(i, ranges).first;
        d.image_problem[i] = why;
        d.image_name[i] = image_name;
    }
    problem = d.image_problem[i];
    name = d.image_name[i];
    return cached->second;
}

// --- materials -------------------------------------------------------------------------------------

/// Reads one material's values with the file and material in every message.
struct MaterialReader {
    Document& d;
    std::string where;  // "glTF 'F': material 'M'"
    std::string name;
    SceneMaterial& out;
    std::vector<std::string>& warnings;
    std::map<std::string, std::size_t> unread = {};  // texture key -> index of its warning in `warnings`

    const json* object(const json* o, const std::string& key) const { return o ? object_at(*o, key, where) : nullptr; }
    double number(const json* o, const std::string& key, double fallback, const std::string& prefix) const {
        return number_at(o, key, fallback, where + (prefix.empty() ? "" : ": " + prefix));
    }
    bool has_texture(const json* o, const std::string& key, const std::string& prefix) const {
        if (!o) return false;
        const json* t = object_at(*o, key, where + (prefix.empty() ? "" : ": " + prefix));
        if (!t) return false;
        if (!t->contains("index")) throw Error(where + ": " + prefix + (prefix.empty() ? "" : ": ") + key + " has no 'index'");
        index_at(*t, "index", top_array(d, "textures").size(), "texture", where + ": " + key);
        return true;
    }

    /// factor x the values the texture at `key` holds in `channel` (0 R, 1 G, 2 B, 3 A); the
    /// factor alone without a texture; [0, factor] with a warning when the image cannot be read.
    Interval textured(const json* o, const std::string& key, double factor, int channel, const std::string& quantity,
                      const std::string& prefix = "") {
        if (!has_texture(o, key, prefix)) return {factor, factor};
        const long t = index_at((*o)[key], "index", top_array(d, "textures").size(), "texture", where + ": " + key);
        std::string problem, image;
        const std::optional<ChannelRanges> r = texture_ranges(d, t, problem, image);
        static const char* kChannel[] = {"R", "G", "B", "A"};
        if (!r) {
            // One warning per texture of the material, naming what its channels hold.
            const std::string what = quantity + " planned over the full range [0, " + fmt(factor) + "]";
            const auto seen = unread.find(key);
            if (seen != unread.end()) {
                warnings[seen->second] += ", " + what;
            } else {
                unread[key] = warnings.size();
                warnings.push_back("material '" + name + "': " + key + " (image '" + image + "') cannot be read: " + problem +
                                   "; " + what);
            }
            out.notes.push_back(quantity + " [0, " + fmt(factor) + "]: " + key + " not read (" + image + ")");
            return {0.0, factor};
        }
        const Interval v{r->lo[size_t(channel)] * factor, r->hi[size_t(channel)] * factor};
        out.notes.push_back(quantity + " " + range_text(v) + " from " + key + " '" + image + "' (" +
                            std::to_string(r->width) + "x" + std::to_string(r->height) + ", " + kChannel[channel] +
                            " channel " + range_text({r->lo[size_t(channel)], r->hi[size_t(channel)]}) + " x factor " +
                            fmt(factor) + ")");
        return v;
    }
};

/// A lobe of `model` (a registry spec) with `role`, `fresnel` and `alpha`, needing the default kinds.
Lobe lobe_of(const std::string& role, const std::string& model, const std::string& fresnel, Interval alpha,
             std::optional<Interval> eta = std::nullopt) {
    Lobe l;
    l.role = role;
    l.model = model_without_alpha(model);
    l.model_name = l.model.substr(0, l.model.find(':'));
    l.fresnel = fresnel;
    l.alpha = alpha;
    l.eta = eta;
    l.kinds = default_lobe_kinds(l);
    return l;
}

/// The material's extensions that change no table, or that are not modelled: a warning each.
void report_extensions(const MaterialReader& m, const json* exts) {
    if (!exts) return;
    for (const auto& e : exts->items()) {
        if (!e.value().is_object()) throw Error(m.where + ": extension " + e.key() + " must be an object");
        if (!gltf_extensions::modelled(e.key()))
            m.warnings.push_back("material '" + m.name + "': " + e.key() + " is not modelled" +
                                 gltf_extensions::unmodelled_text(e.key(), true));
    }
}

/// What the base layer's lobes are made of: roughness (as alpha, anisotropy included),
/// metalness, index of refraction, transmission and specular.
struct BaseInputs {
    Interval alpha, metallic, transmission{0.0, 0.0}, specular{1.0, 1.0};
    double ior = 1.5;
    bool tinted = false;  // KHR_materials_specular tints F0
};

/// pbrMetallicRoughness and KHR_materials_anisotropy: the base's alpha and metalness.
void read_roughness(MaterialReader& m, const json& mat, const json* anisotropy, BaseInputs& in) {
    const json* pbr = object_at(mat, "pbrMetallicRoughness", m.where);
    const std::string pp = "pbrMetallicRoughness";
    const double metallic_factor = m.number(pbr, "metallicFactor", 1.0, pp);
    const double roughness_factor = m.number(pbr, "roughnessFactor", 1.0, pp);
    check_factor(m.where, "metallicFactor", metallic_factor, 0, 1);
    check_factor(m.where, "roughnessFactor", roughness_factor, 0, 1);
    // metallicRoughnessTexture: roughness in G, metallic in B (glTF 2.0, 3.9.2).
    const Interval roughness = m.textured(pbr, "metallicRoughnessTexture", roughness_factor, 1, "roughness", pp);
    in.metallic = m.textured(pbr, "metallicRoughnessTexture", metallic_factor, 2, "metallic", pp);
    in.alpha = square(roughness);
    if (in.alpha.lo < double(BB_ALPHA_MIN)) m.out.notes.push_back(alpha_floor_note(in.alpha.lo));

    // Anisotropy: alpha_t = mix(alpha, 1, strength^2), alpha_b = alpha (KHR_materials_anisotropy);
    // its texture's B channel scales anisotropyStrength.
    if (!anisotropy) return;
    const std::string ap = "KHR_materials_anisotropy";
    const double strength = m.number(anisotropy, "anisotropyStrength", 0.0, ap);
    check_factor(m.where, "anisotropyStrength", strength, 0, 1);
    const Interval s = m.textured(anisotropy, "anisotropyTexture", strength, 2, "anisotropyStrength", ap);
    if (s.hi > 0.0) {
        const double at_hi = in.alpha.hi + (1.0 - in.alpha.hi) * s.hi * s.hi;
        in.alpha.hi = std::max(in.alpha.hi, at_hi);
        m.out.notes.push_back("KHR_materials_anisotropy: isotropic tables over [alpha_b, alpha_t] = " + range_text(in.alpha));
        m.warnings.push_back("material '" + m.name + "': KHR_materials_anisotropy is approximated: the tables are "
                             "isotropic and cover alpha up to alpha_t = " + fmt(at_hi));
    }
}

/// KHR_materials_ior: the index of refraction, planned at kSceneEtaMax above it.
void read_ior(MaterialReader& m, const json* e, BaseInputs& in) {
    if (!e) return;
    in.ior = m.number(e, "ior", 1.5, "KHR_materials_ior");
    if (!std::isfinite(in.ior) || in.ior < 1.0 || in.ior > 1e3)
        throw Error(m.where + ": KHR_materials_ior: ior " + fmt(in.ior) + " is out of range [1, 1000]");
    if (in.ior > kSceneEtaMax) {
        auto f0 = [](double n) { return ((n - 1) / (n + 1)) * ((n - 1) / (n + 1)); };
        m.warnings.push_back("material '" + m.name + "': KHR_materials_ior: ior " + fmt(in.ior) +
                             " is beyond the dielectric tables' index range (at most " + fmt(kSceneEtaMax) +
                             "); planned at eta " + fmt(kSceneEtaMax) + " (F0 " + fmt(f0(kSceneEtaMax)) + " instead of " +
                             fmt(f0(in.ior)) + ")");
        m.out.notes.push_back("ior " + fmt(in.ior) + " planned at eta " + fmt(kSceneEtaMax) + ", the tables' limit");
        in.ior = kSceneEtaMax;
    }
}

/// KHR_materials_transmission and KHR_materials_specular (read, with their types checked, whether
/// or not a dielectric lobe uses them), and the type of KHR_materials_volume's thickness.
void read_transmission_specular(MaterialReader& m, const json* t, const json* s, const json* v, BaseInputs& in) {
    if (t) {
        const std::string tp = "KHR_materials_transmission";
        const double factor = m.number(t, "transmissionFactor", 0.0, tp);
        check_factor(m.where, "transmissionFactor", factor, 0, 1);
        in.transmission = m.textured(t, "transmissionTexture", factor, 0, "transmission", tp);
    }
    if (s) {
        const std::string sp = "KHR_materials_specular";
        const double factor = m.number(s, "specularFactor", 1.0, sp);
        check_factor(m.where, "specularFactor", factor, 0, 1);
        in.specular = m.textured(s, "specularTexture", factor, 3, "specularFactor", sp);
        const std::vector<double> color = numbers_at(s, "specularColorFactor", {1, 1, 1}, m.where + ": " + sp);
        for (double c : color) check_factor(m.where, "specularColorFactor", c, 0, 1e3);
        in.tinted = m.has_texture(s, "specularColorTexture", sp) ||
                    std::any_of(color.begin(), color.end(), [](double c) { return c != 1.0; });
    }
    if (v) m.number(v, "thicknessFactor", 0.0, "KHR_materials_volume");  // its type
}

/// The dielectric lobe of the non-metal part, or the note saying why there is none.
void add_dielectric_lobe(MaterialReader& m, const BaseInputs& in, const json* volume_ext) {
    const bool transmissive = in.transmission.hi > 0.0;
    const bool reflects = in.specular.hi > 0.0 && in.ior > 1.0;
    if (!reflects && !transmissive) {
        m.out.notes.push_back(in.ior == 1.0 ? "ior 1: the dielectric interface does not reflect, no table"
                                            : "KHR_materials_specular: specularFactor 0, no specular reflection");
        return;
    }
    if (in.ior == 1.0) {
        m.out.notes.push_back("ior 1: index-matched interface, transmission albedo 1, no table");
        return;
    }
    Lobe l = lobe_of(transmissive ? "transmission" : "dielectric", "ggx", "dielectric:eta=" + fmt(in.ior), in.alpha,
                     Interval{in.ior, in.ior});
    if (in.specular.lo != 1.0 || in.specular.hi != 1.0)
        m.out.notes.push_back("KHR_materials_specular: specularFactor " + range_text(in.specular) +
                              " scales the reflection albedo (linear in F), same table");
    if (in.tinted) {
        // A tinted F0 makes F Schlick with a per-channel f0: E = f0 A + B (split-sum terms).
        l.kinds.push_back(&table_kind(TableKindId::Dfg));
        m.out.notes.push_back("KHR_materials_specular: specularColor tints F0 (Schlick), E = f0 A + B from dfg");
    }
    if (transmissive) {
        // Rough glass's multiple-scattering compensation (Kulla and Conty 2017) needs the average
        // of R + T over mu from both sides, as Cycles' ggx_glass_Eavg.
        l.kinds.push_back(&table_kind(TableKindId::DielectricEavg));
        m.out.notes.push_back("KHR_materials_transmission: transmission " + range_text(in.transmission) +
                              ", rough transmission from the dielectric table");
        bool volume = false;
        if (const json* v = volume_ext) {
            const std::string vp = "KHR_materials_volume";
            const double thickness = m.number(v, "thicknessFactor", 0.0, vp);
            if (!std::isfinite(thickness) || thickness < 0)
                throw Error(m.where + ": KHR_materials_volume: thicknessFactor " + fmt(thickness) + " is negative");
            volume = thickness > 0.0 && m.textured(v, "thicknessTexture", thickness, 1, "thickness", vp).hi > 0.0;
        }
        m.out.notes.push_back(volume ? "KHR_materials_volume: refracting volume, both sides of the interface (eta and 1/eta)"
                                     : "thin-walled (no volume): the outside of the interface only");
    } else if (volume_ext) {
        m.out.notes.push_back("KHR_materials_volume without transmission has no effect");
    }
    m.out.lobes.push_back(l);
}

/// Clear coat: a GGX dielectric layer with ior 1.5 (fixed by KHR_materials_clearcoat) and its own
/// roughness; its reflection albedo weights the base by 1 - E_coat. Textures: clearcoat in R,
/// clearcoat roughness in G.
void add_clearcoat_lobe(MaterialReader& m, const json* c) {
    if (!c) return;
    const std::string cp = "KHR_materials_clearcoat";
    const double factor = m.number(c, "clearcoatFactor", 0.0, cp);
    check_factor(m.where, "clearcoatFactor", factor, 0, 1);
    if (!(m.textured(c, "clearcoatTexture", factor, 0, "clearcoat", cp).hi > 0.0)) return;
    const double cr = m.number(c, "clearcoatRoughnessFactor", 0.0, cp);
    check_factor(m.where, "clearcoatRoughnessFactor", cr, 0, 1);
    const Interval r = m.textured(c, "clearcoatRoughnessTexture", cr, 1, "clearcoat roughness", cp);
    const Lobe l = lobe_of("clearcoat", "ggx", "dielectric:eta=1.5", square(r), Interval{1.5, 1.5});
    m.out.notes.push_back("KHR_materials_clearcoat: GGX coat, eta 1.5, roughness " + range_text(r));
    if (l.alpha.lo < double(BB_ALPHA_MIN)) m.out.notes.push_back("clearcoat: " + alpha_floor_note(l.alpha.lo));
    m.out.lobes.push_back(l);
}

/// Sheen: the Charlie lobe of Estevez and Kulla 2017 with alpha = sheenRoughness^2 and the
/// specification's visibility (charlie), layered over the rest; its directional albedo scales the
/// layer beneath (KHR_materials_sheen, "Sheen layering"). A black sheen adds nothing. Textures:
/// sheen colour in RGB, sheen roughness in A.
void add_sheen_lobe(MaterialReader& m, const json* s) {
    if (!s) return;
    const std::string sp = "KHR_materials_sheen";
    const std::vector<double> color = numbers_at(s, "sheenColorFactor", {0, 0, 0}, m.where + ": " + sp);
    for (double c : color) check_factor(m.where, "KHR_materials_sheen: sheenColorFactor", c, 0, 1);
    const double sr = m.number(s, "sheenRoughnessFactor", 0.0, sp);
    check_factor(m.where, "KHR_materials_sheen: sheenRoughnessFactor", sr, 0, 1);
    bool colored = false;
    for (size_t ch = 0; ch < std::min<size_t>(3, color.size()); ++ch)
        colored = colored || m.textured(s, "sheenColorTexture", color[ch], int(ch), "sheenColor", sp).hi > 0.0;
    if (!colored) {
        m.out.notes.push_back("KHR_materials_sheen: sheenColorFactor 0, no sheen, no table");
        return;
    }
    const Interval r = m.textured(s, "sheenRoughnessTexture", sr, 3, "sheenRoughness", sp);
    const Lobe l = lobe_of("sheen", "sheen", "none", square(r));
    m.out.notes.push_back("KHR_materials_sheen: Charlie sheen, sheenRoughness " + range_text(r) +
                          ", charlie visibility; its albedo scales the base (1 - max(sheenColor) E)");
    if (l.alpha.lo < double(BB_ALPHA_MIN)) m.out.notes.push_back("sheen: " + alpha_floor_note(l.alpha.lo));
    m.out.lobes.push_back(l);
}

/// KHR_materials_iridescence (KhronosGroup/glTF extensions/2.0/Khronos/KHR_materials_iridescence):
/// a film of index iridescenceIor (default 1.3) on the base, thickness
/// mix(iridescenceThicknessMinimum, iridescenceThicknessMaximum, iridescenceThicknessTexture.g)
/// (defaults 100 and 400 nm; iridescenceThicknessMaximum without the texture), and
/// F = mix(F_base, F_iridescence, iridescenceFactor x iridescenceTexture.r). The albedo is linear in
/// F, so the film's table (the thin-film kind, over the thickness range) serves every factor. The
/// film's substrate is the dielectric base at the material's ior; a metallic base has only a
/// colour (the Sample Viewer turns baseColor into a real index per channel, k = 0), no spectrum.
void add_iridescence_lobe(MaterialReader& m, const BaseInputs& in, const json* e) {
    if (!e) return;
    const std::string ip = "KHR_materials_iridescence";
    const double factor = m.number(e, "iridescenceFactor", 0.0, ip);
    check_factor(m.where, "KHR_materials_iridescence: iridescenceFactor", factor, 0, 1);
    if (!(m.textured(e, "iridescenceTexture", factor, 0, "iridescence", ip).hi > 0.0)) {
        m.out.notes.push_back("KHR_materials_iridescence: iridescenceFactor 0, no film, no table");
        return;
    }
    const double ior = m.number(e, "iridescenceIor", 1.3, ip);
    const double lo = m.number(e, "iridescenceThicknessMinimum", 100.0, ip);
    const double hi = m.number(e, "iridescenceThicknessMaximum", 400.0, ip);
    if (!(ior >= 1.0 && ior <= 10.0))
        throw Error(m.where + ": KHR_materials_iridescence: iridescenceIor " + fmt(ior) + " is out of range [1, 10]");
    if (!(lo >= 0.0 && hi >= 0.0 && lo <= 100000.0 && hi <= 100000.0))
        throw Error(m.where + ": KHR_materials_iridescence: thickness " + fmt(lo) + ", " + fmt(hi) +
                    " nm is out of range [0, 100000]");
    const Interval g = m.has_texture(e, "iridescenceThicknessTexture", ip)
                           ? m.textured(e, "iridescenceThicknessTexture", 1.0, 1, "iridescence thickness ratio", ip)
                           : Interval{1.0, 1.0};
    const Interval d{std::min(lo + (hi - lo) * g.lo, lo + (hi - lo) * g.hi), std::max(lo + (hi - lo) * g.lo, lo + (hi - lo) * g.hi)};
    if (in.metallic.hi > 0.0)
        m.out.notes.push_back("KHR_materials_iridescence: over the metallic base the film's substrate is baseColor "
                              "(no spectrum), not tabulated; the film's table is for the dielectric base");
    if (in.metallic.lo >= 1.0) return;
    Lobe l = lobe_of("iridescence", "ggx", "thin-film:eta=" + fmt(ior) + ",base_eta=" + fmt(in.ior), in.alpha);
    l.thickness = d;
    l.kinds = {&table_kind(TableKindId::ThinFilm)};
    m.out.notes.push_back("KHR_materials_iridescence: film ior " + fmt(ior) + " on the base's ior " + fmt(in.ior) +
                          ", thickness " + range_text(d) + " nm; F = mix(F_base, F_film, iridescence) with the "
                          "film's albedo from the thin-film table (colour in linear sRGB)");
    m.out.lobes.push_back(l);
}

SceneMaterial map_material(Document& d, const json& mat, const std::string& name, std::vector<std::string>& warnings) {
    SceneMaterial out;
    out.name = name;
    MaterialReader m{d, d.label + ": material '" + name + "'", name, out, warnings};
    if (!mat.is_object()) throw Error(m.where + " must be an object");
    const json* exts = object_at(mat, "extensions", m.where);
    report_extensions(m, exts);
    auto ext = [&](const char* key) -> const json* { return exts ? object_at(*exts, key, m.where) : nullptr; };
    if (ext("KHR_materials_unlit")) {
        out.notes.push_back("KHR_materials_unlit: no BRDF, no table");
        return out;
    }
    BaseInputs in;
    read_roughness(m, mat, ext("KHR_materials_anisotropy"), in);
    read_ior(m, ext("KHR_materials_ior"), in);
    read_transmission_specular(m, ext("KHR_materials_transmission"), ext("KHR_materials_specular"),
                               ext("KHR_materials_volume"), in);
    if (in.metallic.hi > 0.0) out.lobes.push_back(lobe_of("metal", "ggx", "schlick:f0=baseColor", in.alpha));
    if (in.metallic.lo < 1.0) add_dielectric_lobe(m, in, ext("KHR_materials_volume"));
    add_clearcoat_lobe(m, ext("KHR_materials_clearcoat"));
    add_sheen_lobe(m, ext("KHR_materials_sheen"));
    add_iridescence_lobe(m, in, ext("KHR_materials_iridescence"));
    if (out.lobes.empty() && out.notes.empty()) out.notes.push_back("no lobe needs a table");
    return out;
}

}  // namespace

Scene load_gltf_scene(const std::string& path) {
    Document d = open_document(path);
    Scene scene;
    scene.path = path;
    scene.source = "glTF 2.0";

    // Variant names (KHR_materials_variants), for the notes of the materials they select.
    std::vector<std::string> variant_names;
    if (const json* e = object_at(d.j, "extensions", d.label))
        if (const json* v = object_at(*e, "KHR_materials_variants", d.label + ": extensions"))
            if (v->contains("variants") && (*v)["variants"].is_array())
                for (const auto& x : (*v)["variants"])
                    variant_names.push_back(x.is_object() && x.contains("name") && x["name"].is_string()
                                                ? x["name"].get<std::string>()
                                                : "variant " + std::to_string(variant_names.size()));

    // Only the materials that a mesh primitive uses, directly or through a variant mapping (all of
    // them in a file without meshes: a material library); a primitive without a material uses
    // the glTF default material.
    const json& materials = top_array(d, "materials");
    const json& meshes = top_array(d, "meshes");
    std::set<long> used;
    std::map<long, std::set<std::string>> variants_of;
    bool default_used = false;
    for (std::size_t mi = 0; mi < meshes.size(); ++mi) {
        const json& mesh = meshes[mi];
        const std::string mwhere = d.label + ": mesh " + std::to_string(mi);
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
            throw Error(mwhere + " has no 'primitives' array");
        for (const auto& prim : mesh["primitives"]) {
            if (!prim.is_object()) throw Error(mwhere + ": a primitive must be an object");
            if (prim.contains("material")) used.insert(index_at(prim, "material", materials.size(), "material", mwhere));
            else default_used = true;
            const json* pe = object_at(prim, "extensions", mwhere);
            const json* pv = pe ? object_at(*pe, "KHR_materials_variants", mwhere) : nullptr;
            if (!pv || !pv->contains("mappings")) continue;
            if (!(*pv)["mappings"].is_array()) throw Error(mwhere + ": KHR_materials_variants 'mappings' must be an array");
            for (const auto& mapping : (*pv)["mappings"]) {
                const std::string vwhere = mwhere + ": KHR_materials_variants mapping";
                if (!mapping.is_object() || !mapping.contains("material"))
                    throw Error(vwhere + " needs a 'material'");
                const long mat = index_at(mapping, "material", materials.size(), "material", vwhere);
                used.insert(mat);
                if (mapping.contains("variants") && mapping["variants"].is_array())
                    for (const auto& v : mapping["variants"])
                        if (v.is_number_integer() && v.get<long long>() >= 0 &&
                            std::size_t(v.get<long long>()) < variant_names.size())
                            variants_of[mat].insert(variant_names[std::size_t(v.get<long long>())]);
            }
        }
    }
    const bool library = meshes.empty();

    std::set<std::string> material_exts;
    std::map<std::string, int> seen_names;
    for (std::size_t i = 0; i < materials.size(); ++i) {
        const json& mat = materials[i];
        std::string name = mat.is_object() && mat.contains("name") && mat["name"].is_string() &&
                                   !mat["name"].get<std::string>().empty()
                               ? mat["name"].get<std::string>()
                               : "material " + std::to_string(i);
        if (seen_names[name]++) name += " #" + std::to_string(i);
        if (!library && !used.count(long(i))) {
            SceneMaterial m;
            m.name = name;
            m.notes.push_back("not used by any mesh primitive or variant, not planned");
            scene.materials.push_back(m);
            continue;
        }
        if (mat.is_object() && mat.contains("extensions") && mat["extensions"].is_object())
            for (const auto& e : mat["extensions"].items()) material_exts.insert(e.key());
        SceneMaterial m = map_material(d, mat, name, scene.warnings);
        if (variants_of.count(long(i))) {
            std::string list;
            for (const auto& v : variants_of[long(i)]) list += (list.empty() ? "'" : ", '") + v + "'";
            m.notes.push_back("KHR_materials_variants: material of variant " + list);
        }
        scene.materials.push_back(std::move(m));
    }
    if (default_used) {
        // glTF defaults: metallic 1, roughness 1.
        scene.materials.push_back(map_material(d, json::object(), "(glTF default material)", scene.warnings));
    }
    if (scene.materials.empty()) throw Error(d.label + " has no materials and no meshes: nothing to plan");

    if (d.j.contains("extensionsUsed")) {
        if (!d.j["extensionsUsed"].is_array()) throw Error(d.label + ": 'extensionsUsed' must be an array");
        for (const auto& x : d.j["extensionsUsed"]) {
            if (!x.is_string()) throw Error(d.label + ": 'extensionsUsed' must hold strings");
            const std::string e = x.get<std::string>();
            if (material_exts.count(e) || gltf_extensions::modelled(e)) continue;  // reported per material, or modelled
            scene.warnings.push_back("extension " + e + " is not modelled" + gltf_extensions::unmodelled_text(e, false));
        }
    }
    return scene;
}

}  // namespace brdfbake
