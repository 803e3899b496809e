// glTF scenes as they come (issue 19): no geometry buffers needed, meshopt files, material
// variants, type errors and duplicate keys, texture-driven ranges from generated PNGs, the ends of
// the eta and roughness ranges, and the texel-centre statement of the plan. The scene files are in
// tests/data; images are written here with libpng's own writer, so the ranges the planner reads
// are checked against the values put into the file.
#include <catch2/catch.hpp>

#include <cstdio>
#include <jpeglib.h>
#include <png.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <cstdlib>
#include <functional>
#include <map>
#include <set>
#include <fstream>
#include <sys/stat.h>

#include "brdfbake/lut.h"
#include "scene/scene.h"
#include "scene_support.h"
#include "support.h"

using namespace brdfbake;
using namespace testing::scene;
using testing::run_cli;

namespace {

void write_text(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

/// An 8-bit RGB (or RGBA) PNG of w x h pixels, every pixel's channel c from value(x, y, c), in memory.
std::string png_rgb(int w, int h, const std::function<int(int, int, int)>& value, bool alpha = false) {
    const int nc = alpha ? 4 : 3;
    std::vector<unsigned char> px(std::size_t(w) * h * nc);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < nc; ++c) px[(std::size_t(y) * w + x) * nc + c] = (unsigned char)value(x, y, c);
    png_image img;
    std::memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    img.width = png_uint_32(w);
    img.height = png_uint_32(h);
    img.format = alpha ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB;
    png_alloc_size_t size = 0;
    REQUIRE(png_image_write_to_memory(&img, nullptr, &size, 0, px.data(), 0, nullptr));
    std::string out(size, '\0');
    REQUIRE(png_image_write_to_memory(&img, &out[0], &size, 0, px.data(), 0, nullptr));
    out.resize(size);
    return out;
}

std::string base64(const std::string& in) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::size_t i = 0;
    for (; i + 2 < in.size(); i += 3) {
        const unsigned v = unsigned((unsigned char)in[i]) << 16 | unsigned((unsigned char)in[i + 1]) << 8 | (unsigned char)in[i + 2];
        for (int s = 18; s >= 0; s -= 6) out += k[(v >> s) & 63];
    }
    if (i < in.size()) {
        unsigned v = unsigned((unsigned char)in[i]) << 16;
        if (i + 1 < in.size()) v |= unsigned((unsigned char)in[i + 1]) << 8;
        out += k[(v >> 18) & 63];
        out += k[(v >> 12) & 63];
        out += i + 1 < in.size() ? k[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

void put_le32(std::string& s, std::uint32_t v) {
    for (int b = 0; b < 4; ++b) s += char((v >> (8 * b)) & 0xff);
}

/// A .glb (glTF 2.0 binary container, the specification's section 4.4) of a JSON document and a
/// binary chunk.
std::string glb(std::string json_text, std::string bin) {
    while (json_text.size() % 4) json_text += ' ';
    while (bin.size() % 4) bin += '\0';
    std::string out = "glTF";
    put_le32(out, 2);
    put_le32(out, std::uint32_t(12 + 8 + json_text.size() + (bin.empty() ? 0 : 8 + bin.size())));
    put_le32(out, std::uint32_t(json_text.size()));
    put_le32(out, 0x4E4F534Au);
    out += json_text;
    if (!bin.empty()) {
        put_le32(out, std::uint32_t(bin.size()));
        put_le32(out, 0x004E4942u);
        out += bin;
    }
    return out;
}

/// A glTF material library (no meshes) of one material given as JSON text, with optional
/// textures/images arrays.
std::string library(const std::string& material, const std::string& rest = "") {
    return R"({"asset": {"version": "2.0"}, "materials": [)" + material + "]" + (rest.empty() ? "" : ", " + rest) + "}";
}

const Lobe* lobe_of(const Scene& s, const std::string& material, const std::string& role) {
    for (const auto& m : s.materials)
        if (m.name == material)
            for (const auto& l : m.lobes)
                if (l.role == role) return &l;
    return nullptr;
}

const SceneMaterial* material_of(const Scene& s, const std::string& name) {
    for (const auto& m : s.materials)
        if (m.name == name) return &m;
    return nullptr;
}

/// The parameter (alpha) at texel centre i of a planned table's roughness axis.
double alpha_at_centre(const PlannedTable& t, int i) {
    const int n = t.kind->one_dimensional ? t.request.width : t.request.height;
    const double c = centre(t.request.alpha_lo, t.request.alpha_hi, n, i);
    return t.request.alpha_map == "roughness" ? c * c : c;
}

/// The plan's dielectric table, which must be one `lut` (and so `bake`) accepts as planned.
const PlannedTable* bakeable_dielectric(const Plan& p) {
    const PlannedTable* d = find_kind(p, "dielectric");
    REQUIRE(d);
    CHECK(d->unavailable.empty());
    LutRequest r = d->request;
    apply_eta_axis(*d, r);
    CHECK_NOTHROW(validate_lut(r));
    return d;
}

}  // namespace

TEST_CASE("glTF: a .gltf plans without its geometry buffer", "[gltf][quick]") {
    // The .bin the file names is not there: only materials are read.
    const Scene scene = load_scene(data("gltf_nobin.gltf"));
    const Plan plan = make_plan(scene);
    const PlannedTable* a = find_kind(plan, "albedo");
    REQUIRE(a);
    CHECK(a->materials == std::vector<std::string>{"rough metal", "smooth metal"});
    CHECK(a->alpha.lo == Approx(0.0625));
    CHECK(a->alpha.hi == Approx(0.25));
    const auto r = run_cli("plan " + data("gltf_nobin.gltf"));
    INFO(r.err);
    CHECK(r.status == 0);
}

TEST_CASE("glTF: a meshopt-compressed .gltf (buffer without uri) and the same document as .glb plan alike",
          "[gltf][quick]") {
    const std::string dir = fresh_tmp_dir("meshopt");
    ::mkdir(dir.c_str(), 0755);
    const std::string text = testing::slurp(data("gltf_meshopt.gltf"));
    write_text(dir + "/meshopt.glb", glb(text, std::string(48, '\0')));
    const Plan a = make_plan(load_scene(data("gltf_meshopt.gltf")));
    const Plan b = make_plan(load_scene(dir + "/meshopt.glb"));
    REQUIRE(a.tables.size() == b.tables.size());
    CHECK(a.tables.size() == 3);  // brass: albedo, eavg; lacquer: dielectric at eta 1.6
    for (size_t i = 0; i < a.tables.size(); ++i) {
        CHECK(a.tables[i].file == b.tables[i].file);
        CHECK(a.tables[i].hash == b.tables[i].hash);
    }
    CHECK(contains(a.warnings, "EXT_meshopt_compression is not modelled (geometry compression"));
    const PlannedTable* d = find_kind(a, "dielectric");
    REQUIRE(d);
    CHECK(d->eta->lo == 1.6);
}

TEST_CASE("glTF: every material of every KHR_materials_variants variant is planned", "[gltf][quick]") {
    const Scene scene = load_scene(data("gltf_variants.gltf"));
    // The glass is used only by the variant "street glass": its transmission lobe and table.
    const Lobe* glass = lobe_of(scene, "glass", "transmission");
    REQUIRE(glass);
    CHECK(glass->eta->lo == 1.5);
    CHECK(contains(material_of(scene, "glass")->notes, "variant 'street glass'"));
    CHECK(lobe_of(scene, "midnight leather", "metal"));
    const Plan plan = make_plan(scene);
    const PlannedTable* d = find_kind(plan, "dielectric");
    REQUIRE(d);
    CHECK(d->serves == std::vector<std::string>{"glass (transmission)"});
    CHECK_FALSE(contains(plan.warnings, "KHR_materials_variants"));
}

TEST_CASE("glTF: a value of the wrong type is an error naming the file, the material and the key", "[gltf][quick]") {
    const std::string dir = fresh_tmp_dir("types");
    ::mkdir(dir.c_str(), 0755);
    struct Case {
        const char* material;
        const char* key;
    };
    const Case cases[] = {
        {R"({"name": "m", "pbrMetallicRoughness": {"roughnessFactor": "0.5"}})", "roughnessFactor"},
        {R"({"name": "m", "extensions": {"KHR_materials_ior": {"ior": "2.5"}}})", "ior"},
        {R"({"name": "m", "extensions": {"KHR_materials_transmission": {"transmissionFactor": "x"}}})", "transmissionFactor"},
        {R"({"name": "m", "pbrMetallicRoughness": {"metallicRoughnessTexture": 3}})", "metallicRoughnessTexture"},
        {R"({"name": "m", "pbrMetallicRoughness": "rough"})", "pbrMetallicRoughness"},
    };
    int i = 0;
    for (const auto& c : cases) {
        INFO(c.material);
        const std::string path = dir + "/t" + std::to_string(i++) + ".gltf";
        write_text(path, library(c.material));
        const std::string msg = error_of([&] { load_scene(path); });
        CHECK(msg.find(path) != std::string::npos);
        CHECK(msg.find("material 'm'") != std::string::npos);
        CHECK(msg.find(c.key) != std::string::npos);
        const auto r = run_cli("plan " + path);
        CHECK(r.status == 2);
        CHECK(r.err.find("brdfbake: error: ") == 0);
    }
}

TEST_CASE("scene files: a key given twice is an error naming the file, the material and the key", "[scene][gltf][quick]") {
    const std::string msg = error_of([&] {
        parse_scene_json(R"({"materials": [{"name": "gold", "model": "ggx", "roughness": 0.2, "roughness": 0.5}]})",
                         "dup.json");
    });
    CHECK(msg.find("dup.json") != std::string::npos);
    CHECK(msg.find("'roughness' is given twice") != std::string::npos);
    CHECK(msg.find("materials[0]") != std::string::npos);
    CHECK(msg.find("'gold'") != std::string::npos);
    const std::string top = error_of([&] {
        parse_scene_json(R"({"materials": [{"name": "a", "model": "ggx", "alpha": 0.2}], "materials": []})", "dup.json");
    });
    CHECK(top.find("'materials' is given twice in the top-level object") != std::string::npos);
    // glTF: the same rule
    const std::string dir = fresh_tmp_dir("dup");
    ::mkdir(dir.c_str(), 0755);
    write_text(dir + "/d.gltf",
               library(R"({"name": "paint", "pbrMetallicRoughness": {"roughnessFactor": 0.2, "roughnessFactor": 0.9}})"));
    const std::string g = error_of([&] { load_scene(dir + "/d.gltf"); });
    CHECK(g.find("'roughnessFactor' is given twice in materials[0].pbrMetallicRoughness ('paint')") != std::string::npos);
}

TEST_CASE("scene files: a relative nk: path is read from the scene file's folder", "[scene][gltf][quick]") {
    const std::string dir = fresh_tmp_dir("nk");
    ::mkdir(dir.c_str(), 0755);
    const std::string here = __FILE__;
    const std::string root = here.substr(0, here.find_last_of('/', here.find_last_of('/') - 1));
    write_text(dir + "/copper.yml", testing::slurp(root + "/data/nk/Cu-Johnson.yml"));
    write_text(dir + "/s.json",
               R"({"materials": [{"name": "cu", "model": "ggx", "fresnel": "nk:copper.yml", "roughness": 0.3,
                   "tables": ["conductor"]}]})");
    // The test runs in the build folder, which has no copper.yml.
    const Scene s = load_scene(dir + "/s.json");
    REQUIRE(s.materials.size() == 1);
    CHECK(s.materials[0].lobes[0].fresnel == "nk:" + dir + "/copper.yml");
    CHECK(make_plan(s).tables.at(0).unavailable.empty());
}

TEST_CASE("eta at the ends of its range: plan and bake agree, every planned table is one lut accepts",
          "[scene][gltf][quick]") {
    const std::string dir = fresh_tmp_dir("eta");
    ::mkdir(dir.c_str(), 0755);
    // JSON: eta 10 (the documented maximum), a range ending at 10, eta just above 1.
    for (const char* eta : {"10", "9.98", "[9.975, 10]", "1.001", "[1.001, 1.2]"}) {
        INFO(eta);
        const Plan p = make_plan(parse_scene_json(
            std::string(R"({"materials": [{"name": "g", "model": "ggx", "roughness": 0.3, "eta": )") + eta + "}]}", "e.json"));
        const PlannedTable* d = bakeable_dielectric(p);
        // The slice centres the plan states are the axis's, and the scene's extremes where it says so.
        CHECK(centre(d->eta_lo, d->eta_hi, d->depth, 0) == Approx(d->eta_centres.lo).epsilon(1e-12));
        CHECK(centre(d->eta_lo, d->eta_hi, d->depth, d->depth - 1) == Approx(d->eta_centres.hi).epsilon(1e-12));
        if (d->eta_lo_exact) CHECK(d->eta_centres.lo == Approx(d->eta->lo).epsilon(1e-12));
        CHECK(d->eta_hi_exact);
        CHECK(d->eta_centres.hi == Approx(d->eta->hi).epsilon(1e-12));
        CHECK(d->eta_lo >= 1.0);
    }
    // eta 1.001 alone: its one slice sits on 1.001, not at 1.025.
    {
        const Plan p = make_plan(parse_scene_json(
            R"({"materials": [{"name": "g", "model": "ggx", "roughness": 0.3, "eta": 1.001}]})", "e.json"));
        const PlannedTable* d = find_kind(p, "dielectric");
        REQUIRE(d);
        CHECK(d->depth == 1);
        CHECK(centre(d->eta_lo, d->eta_hi, 1, 0) == Approx(1.001).epsilon(1e-12));
    }
    // glTF ior 9.99 to 1000 (the extension allows any ior >= 1): planned, at most at the scene
    // limit, with a warning naming the material where it is clamped.
    for (const char* ior : {"9.99", "10", "50", "1000"}) {
        INFO(ior);
        const std::string path = dir + "/ior" + ior + ".gltf";
        write_text(path, library(std::string(R"({"name": "diamondish", "pbrMetallicRoughness": {"metallicFactor": 0},
                                               "extensions": {"KHR_materials_ior": {"ior": )") + ior + "}}}"));
        const Plan p = make_plan(load_scene(path));
        const PlannedTable* d = bakeable_dielectric(p);
        CHECK(d->eta_centres.hi == Approx(std::min(std::stod(ior), kSceneEtaMax)));
        if (std::stod(ior) > kSceneEtaMax) CHECK(contains(p.warnings, "material 'diamondish': KHR_materials_ior: ior"));
    }
}

TEST_CASE("roughness 0 and tiny roughness: JSON scenes plan them as glTF does, at the alpha floor",
          "[scene][gltf][quick]") {
    const std::string dir = fresh_tmp_dir("rough0");
    ::mkdir(dir.c_str(), 0755);
    write_text(dir + "/m.gltf", library(R"({"name": "mirror", "pbrMetallicRoughness": {"roughnessFactor": 0}})"));
    const Plan g = make_plan(load_scene(dir + "/m.gltf"));
    for (const char* rough : {"0", "0.001"}) {
        INFO(rough);
        const Scene s = parse_scene_json(
            std::string(R"({"materials": [{"name": "mirror", "model": "ggx", "roughness": )") + rough + "}]}", "r.json");
        CHECK(contains(s.materials[0].notes, "alpha floor"));
        const Plan j = make_plan(s);
        const PlannedTable* a = find_kind(j, "albedo");
        const PlannedTable* b = find_kind(g, "albedo");
        REQUIRE(a);
        REQUIRE(b);
        CHECK(a->request.alpha_lo == b->request.alpha_lo);
        CHECK(a->request.alpha_hi == b->request.alpha_hi);
        CHECK(a->request.height == 1);
        // The one texel is centred on the alpha floor, the smallest alpha a texel centre computes.
        CHECK(alpha_at_centre(*a, 0) == Approx(1e-4).epsilon(1e-9));
    }
    const std::string neg = error_of([&] {
        parse_scene_json(R"({"materials": [{"name": "chrome", "model": "ggx", "roughness": -0.1}]})", "r.json");
    });
    CHECK(neg.find("r.json") != std::string::npos);
    CHECK(neg.find("'chrome'") != std::string::npos);
    CHECK(neg.find("roughness") != std::string::npos);
}

TEST_CASE("the plan's texel-centre statement is exact for ranges that start at 0", "[scene][gltf][quick]") {
    const Plan p = make_plan(parse_scene_json(
        R"({"materials": [{"name": "worn", "model": "ggx", "roughness": [0, 0.5]}]})", "z.json"));
    const PlannedTable* a = find_kind(p, "albedo");
    REQUIRE(a);
    const int n = a->request.height;
    // The last centre sits on roughness 0.5; the first is where the axis (starting at 0) puts it,
    // and the plan says so instead of claiming the scene's extreme.
    CHECK(alpha_at_centre(*a, n - 1) == Approx(0.25).epsilon(1e-12));
    CHECK(a->alpha_centres.hi == Approx(0.25).epsilon(1e-12));
    CHECK(alpha_at_centre(*a, 0) == Approx(a->alpha_centres.lo).epsilon(1e-12));
    CHECK_FALSE(a->alpha_lo_exact);
    CHECK(a->request.alpha_lo == 0.0);
    const std::string text = plan_text(p);
    CHECK(text.find("sit on the scene's extremes") == std::string::npos);
    CHECK(text.find("texel centres at alpha") != std::string::npos);
    // A range clear of 0 keeps the promise.
    const Plan q = make_plan(parse_scene_json(
        R"({"materials": [{"name": "worn", "model": "ggx", "roughness": [0.3, 0.5]}]})", "z.json"));
    const PlannedTable* b = find_kind(q, "albedo");
    REQUIRE(b);
    CHECK(alpha_at_centre(*b, 0) == Approx(0.09).epsilon(1e-12));
    CHECK(alpha_at_centre(*b, b->request.height - 1) == Approx(0.25).epsilon(1e-12));
    CHECK(plan_text(q).find("sit on the scene's extremes") != std::string::npos);
}

TEST_CASE("a range that ends at the top of the model's alpha range (sheenRoughness 1) plans a table lut accepts",
          "[gltf][quick]") {
    const std::string dir = fresh_tmp_dir("sheen1");
    ::mkdir(dir.c_str(), 0755);
    // The sheen model takes alpha <= 1 (Estevez and Kulla's fit); before, the half-texel margin
    // above roughness 1 made the table one lut refuses, and bake failed.
    write_text(dir + "/s.gltf", R"({"asset": {"version": "2.0"}, "materials": [
        {"name": "a", "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 1, 1], "sheenRoughnessFactor": 1}}},
        {"name": "b", "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 1, 1], "sheenRoughnessFactor": 0.5}}},
        {"name": "c", "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 1, 1], "sheenRoughnessFactor": 1}}}]})");
    const Plan p = make_plan(load_scene(dir + "/s.gltf"));
    const PlannedTable* t = find_kind(p, "sheen-albedo");
    REQUIRE(t);
    CHECK(t->unavailable.empty());
    CHECK_NOTHROW(validate_lut(t->request));
    CHECK(t->request.alpha_hi <= 1.0);
    // the first centre on sheenRoughness 0.5, the last inside [0.5, 1] and said so
    CHECK(alpha_at_centre(*t, 0) == Approx(0.25).epsilon(1e-12));
    CHECK(t->alpha_lo_exact);
    CHECK_FALSE(t->alpha_hi_exact);
    CHECK(alpha_at_centre(*t, t->request.height - 1) == Approx(t->alpha_centres.hi).epsilon(1e-12));
    CHECK(plan_text(p).find("the axis stops at the model's largest alpha") != std::string::npos);
}

TEST_CASE("texture-driven ranges: a metallicRoughness texture holding roughness 0.3..0.6 plans that range",
          "[gltf][quick]") {
    const std::string dir = fresh_tmp_dir("tex");
    ::mkdir(dir.c_str(), 0755);
    // G (roughness) runs from 77 to 153 (0.302 to 0.6), B (metallic) is 255 everywhere.
    const std::string png = png_rgb(16, 8, [](int x, int y, int c) {
        return c == 1 ? 77 + (x * 8 + y) * 76 / 127 : c == 2 ? 255 : 0;
    });
    const double g_lo = 77 / 255.0, g_hi = 153 / 255.0, factor = 0.8;
    const std::string material =
        R"({"name": "scuffed", "pbrMetallicRoughness": {"roughnessFactor": 0.8, "metallicRoughnessTexture": {"index": 0}}})";
    auto check_scene = [&](const Scene& s) {
        const Lobe* metal = lobe_of(s, "scuffed", "metal");
        REQUIRE(metal);
        CHECK(metal->alpha.lo == Approx(g_lo * factor * g_lo * factor).epsilon(1e-12));
        CHECK(metal->alpha.hi == Approx(g_hi * factor * g_hi * factor).epsilon(1e-12));
        CHECK_FALSE(lobe_of(s, "scuffed", "dielectric"));  // metallic 1 throughout
        CHECK(contains(material_of(s, "scuffed")->notes, "roughness [0.24"));
        CHECK(s.warnings.empty());
    };
    // beside the file
    write_text(dir + "/orm.png", png);
    write_text(dir + "/beside.gltf", library(material, R"("textures": [{"source": 0}], "images": [{"uri": "orm.png"}])"));
    check_scene(load_scene(dir + "/beside.gltf"));
    // as a data: URI
    write_text(dir + "/embedded.gltf",
               library(material, R"("textures": [{"source": 0}], "images": [{"uri": "data:image/png;base64,)" +
                                     base64(png) + R"("}])"));
    check_scene(load_scene(dir + "/embedded.gltf"));
    // in a .glb's binary chunk
    write_text(dir + "/packed.glb",
               glb(library(material, R"("textures": [{"source": 0}], "images": [{"bufferView": 0, "mimeType": "image/png"}],
                                       "bufferViews": [{"buffer": 0, "byteLength": )" +
                                         std::to_string(png.size()) + R"(}], "buffers": [{"byteLength": )" +
                                         std::to_string(png.size()) + "}]"),
                   png));
    check_scene(load_scene(dir + "/packed.glb"));
    // The plan: the albedo table's centres on the texture's extremes.
    const Plan p = make_plan(load_scene(dir + "/beside.gltf"));
    const PlannedTable* a = find_kind(p, "albedo");
    REQUIRE(a);
    CHECK(alpha_at_centre(*a, 0) == Approx(std::pow(g_lo * factor, 2)).epsilon(1e-12));
    CHECK(alpha_at_centre(*a, a->request.height - 1) == Approx(std::pow(g_hi * factor, 2)).epsilon(1e-12));

    // A texture that cannot be found: the full range, with a warning naming the image.
    write_text(dir + "/missing.gltf", library(material, R"("textures": [{"source": 0}], "images": [{"uri": "gone.png"}])"));
    const Scene m = load_scene(dir + "/missing.gltf");
    CHECK(contains(m.warnings, "gone.png"));
    const Lobe* metal = lobe_of(m, "scuffed", "metal");
    REQUIRE(metal);
    CHECK(metal->alpha.lo == 0.0);
    CHECK(metal->alpha.hi == Approx(0.64));
    CHECK(lobe_of(m, "scuffed", "dielectric"));  // metallic [0, 1] unknown: both lobes
}

TEST_CASE("plan and bake: command-line flags override the scene's settings", "[scene][gltf][cli]") {
    auto plan_json = [](const std::string& args) {
        const auto r = run_cli("plan " + args + " --format json");
        INFO(r.err);
        REQUIRE(r.status == 0);
        return nlohmann::json::parse(r.out);
    };
    // --tables: every lobe takes the listed kinds it can; --size, the axis maps, --eta-step.
    const auto j = plan_json(data("merge.json") + " --tables dfg,dielectric --size 8x16 --mu-map sqrt --alpha-map alpha "
                                                  "--eta-step 0.1");
    std::set<std::string> kinds;
    for (const auto& t : j["tables"]) {
        kinds.insert(t["kind"].get<std::string>());
        CHECK(t["axes"][0]["mapping"].get<std::string>().find("sqrt") != std::string::npos);
        CHECK(t["axes"][0]["size"] == 8);
        CHECK(t["axes"][1]["name"] == "alpha");
        if (t["kind"] == "dielectric") {
            // glasses at eta 1.33 and 1.7: (1.7 - 1.33) / 0.1 -> 5 slices
            CHECK(t["axes"][2]["size"] == 5);
        }
    }
    CHECK(kinds == std::set<std::string>{"dfg", "dielectric"});
    // a kind no lobe can take is an error
    const auto bad = run_cli("plan " + data("merge.json") + " --tables conductor-nope");
    CHECK(bad.status == 2);
    // --preset: the tables of the preset's kinds and model in the engine's layout
    const auto c = plan_json(data("metals_glass.json") + " --preset cycles");
    std::set<std::string> files;
    for (const auto& t : c["tables"]) files.insert(t["file"].get<std::string>());
    CHECK(files.count("cycles-albedo.h"));
    CHECK(files.count("cycles-eavg.h"));
    CHECK(files.count("dielectric-ggx.exr"));
    for (const auto& t : c["tables"])
        if (t["file"] == "cycles-albedo.h") {
            CHECK(t["size"] == "32x32");
            CHECK(t["layout"].get<std::string>().find("Blender Cycles") != std::string::npos);
        }
}

TEST_CASE("target gltf: --target gltf plans the glTF renderers' LUT set", "[scene][gltf][cli]") {
    auto files_of = [](const std::string& args) {
        const auto r = run_cli("plan " + args + " --format json");
        INFO(r.err);
        REQUIRE(r.status == 0);
        std::map<std::string, nlohmann::json> files;
        const nlohmann::json j = nlohmann::json::parse(r.out);
        for (const auto& t : j["tables"]) files[t["file"].get<std::string>()] = t;
        return files;
    };
    // metals and a transmissive glass: lut_ggx, and the glass's dielectric tables
    auto f = files_of(data("metals_glass.json") + " --target gltf");
    REQUIRE(f.count("lut_ggx.png"));
    CHECK(f["lut_ggx.png"]["kind"] == "dfg");
    CHECK(f["lut_ggx.png"]["size"] == "1024x1024");  // the sample viewer's size
    CHECK(f.count("dielectric-ggx.exr"));
    CHECK_FALSE(f.count("albedo-ggx.exr"));
    CHECK_FALSE(f.count("lut_charlie.png"));
    // KHR_materials_sheen adds lut_charlie (ashikhmin visibility) and lut_sheen_E (charlie)
    f = files_of(data("materials.gltf") + " --target gltf --size 16");
    REQUIRE(f.count("lut_charlie.png"));
    REQUIRE(f.count("lut_sheen_E.png"));
    CHECK(f["lut_charlie.png"]["model"] == "sheen:visibility=ashikhmin");
    CHECK(f["lut_sheen_E.png"]["model"] == "sheen:visibility=charlie");
    CHECK(f["lut_ggx.png"]["size"] == "16x16");
    CHECK(f.count("dielectric-eavg-ggx.exr"));  // the bottle glass transmits
}

TEST_CASE("bake --target gltf writes the LUT set, previews and an index that names the layouts", "[scene][gltf][device]") {
    const std::string out = fresh_tmp_dir("target");
    const auto r = run_cli("bake " + data("small_glass.json") + " --target gltf --size 4x4 --samples 64 -o " + out);
    // (small_glass.json: one transmissive glass; a JSON scene's glass gets the dielectric table)
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto index = nlohmann::json::parse(testing::slurp(out + "/index.json"));
    std::set<std::string> files;
    for (const auto& t : index["tables"]) {
        files.insert(t["file"].get<std::string>());
        struct stat st;
        CHECK(::stat((out + "/" + t["preview"].get<std::string>()).c_str(), &st) == 0);
    }
    CHECK(files == std::set<std::string>{"lut_ggx.png", "dielectric-ggx.exr"});
    CHECK(index["settings"]["target"] == "gltf");
    for (const auto& t : index["tables"])
        if (t["file"] == "lut_ggx.png") CHECK(t["layout"].get<std::string>().find("glTF Sample Viewer") != std::string::npos);
}

TEST_CASE("texture-driven ranges read the channel each extension names, a corrupt JPEG and KTX2-only textures are "
          "named in a warning", "[gltf][quick]") {
    const std::string dir = fresh_tmp_dir("channels");
    ::mkdir(dir.c_str(), 0755);
    // One RGBA image, each channel its own range: R 51..102 (0.2..0.4), G 102..153 (0.4..0.6),
    // B 153..204 (0.6..0.8), A 204..255 (0.8..1).
    write_text(dir + "/rgba.png", png_rgb(8, 8, [](int x, int y, int c) { return 51 * (c + 1) + (x * 8 + y) * 51 / 63; }, true));
    auto lo = [](int c) { return 51.0 * (c + 1) / 255; };
    auto hi = [](int c) { return 51.0 * (c + 2) / 255; };
    const std::string images = R"("textures": [{"source": 0}, {"source": 1}, {"extensions": {"KHR_texture_basisu": {"source": 2}}}],
        "images": [{"uri": "rgba.png"}, {"uri": "photo.jpg"}, {"uri": "x.ktx2"}])";
    write_text(dir + "/photo.jpg", std::string("\xff\xd8\xff\xe0", 4) + std::string(64, '\0'));
    write_text(dir + "/c.gltf", library(R"({"name": "coated", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.5},
        "extensions": {
          "KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatRoughnessFactor": 1, "clearcoatRoughnessTexture": {"index": 0}},
          "KHR_materials_sheen": {"sheenColorFactor": [1, 1, 1], "sheenRoughnessFactor": 1, "sheenRoughnessTexture": {"index": 0}},
          "KHR_materials_transmission": {"transmissionFactor": 1, "transmissionTexture": {"index": 0}}}},
        {"name": "photo", "pbrMetallicRoughness": {"metallicRoughnessTexture": {"index": 1}}},
        {"name": "compressed", "pbrMetallicRoughness": {"metallicRoughnessTexture": {"index": 2}}})",
                                        images));
    const Scene s = load_scene(dir + "/c.gltf");
    // clearcoatRoughnessTexture: G; sheenRoughnessTexture: A (KHR_materials_clearcoat, _sheen).
    const Lobe* coat = lobe_of(s, "coated", "clearcoat");
    REQUIRE(coat);
    CHECK(coat->alpha.lo == Approx(lo(1) * lo(1)).epsilon(1e-12));
    CHECK(coat->alpha.hi == Approx(hi(1) * hi(1)).epsilon(1e-12));
    const Lobe* sheen = lobe_of(s, "coated", "sheen");
    REQUIRE(sheen);
    CHECK(sheen->alpha.lo == Approx(lo(3) * lo(3)).epsilon(1e-12));
    CHECK(sheen->alpha.hi == Approx(1.0).epsilon(1e-12));
    // transmissionTexture: R, 0.2..0.4 > 0: transmissive
    CHECK(lobe_of(s, "coated", "transmission"));
    CHECK(contains(material_of(s, "coated")->notes, "transmission [0.2, 0.4] from transmissionTexture 'rgba.png'"));
    // a JPEG and a KTX2-only texture: full ranges, named
    CHECK(contains(s.warnings, "material 'photo': metallicRoughnessTexture (image 'photo.jpg') cannot be read: image "
                               "'photo.jpg' is not a readable JPEG"));
    CHECK(contains(s.warnings, "material 'compressed': metallicRoughnessTexture (image 'texture 2') cannot be read: its "
                               "only image is one of KHR_texture_basisu"));
    CHECK(lobe_of(s, "photo", "metal")->alpha.lo == 0.0);
}

/// A baseline JPEG of an RGB image, written by libjpeg's own encoder at quality 100.
static std::string jpeg_rgb(int w, int h, const std::function<int(int, int, int)>& value) {
    jpeg_compress_struct info {};
    jpeg_error_mgr err {};
    info.err = jpeg_std_error(&err);
    jpeg_create_compress(&info);
    unsigned char* out = nullptr;
    unsigned long size = 0;
    jpeg_mem_dest(&info, &out, &size);
    info.image_width = unsigned(w);
    info.image_height = unsigned(h);
    info.input_components = 3;
    info.in_color_space = JCS_RGB;
    jpeg_set_defaults(&info);
    jpeg_set_quality(&info, 100, TRUE);
    jpeg_start_compress(&info, TRUE);
    std::vector<unsigned char> row(size_t(w) * 3);
    while (info.next_scanline < info.image_height) {
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) row[size_t(x) * 3 + size_t(c)] = (unsigned char)value(x, int(info.next_scanline), c);
        unsigned char* rows[1] = {row.data()};
        jpeg_write_scanlines(&info, rows, 1);
    }
    jpeg_finish_compress(&info);
    jpeg_destroy_compress(&info);
    std::string bytes(reinterpret_cast<char*>(out), size);
    std::free(out);
    return bytes;
}

TEST_CASE("a JPEG metallic-roughness texture whose roughness lies in [0.3, 0.6] plans that range", "[gltf][quick]") {
    const std::string dir = fresh_tmp_dir("jpeg");
    ::mkdir(dir.c_str(), 0755);
    // G (roughness) from 77 to 153 of 255 (0.302 to 0.6), smooth so that JPEG keeps it within a
    // few levels; R and B 0.
    write_text(dir + "/mr.jpg", jpeg_rgb(32, 32, [](int x, int y, int c) { return c == 1 ? 77 + (x + 32 * y) * 76 / 1023 : 0; }));
    write_text(dir + "/m.gltf", library(R"({"name": "brushed", "pbrMetallicRoughness": {"metallicFactor": 1,
        "roughnessFactor": 1, "metallicRoughnessTexture": {"index": 0}}})",
                                        R"("textures": [{"source": 0}], "images": [{"uri": "mr.jpg"}])"));
    const Scene s = load_scene(dir + "/m.gltf");
    const Lobe* metal = lobe_of(s, "brushed", "metal");
    REQUIRE(metal);
    // alpha = roughness^2 at the ends of the decoded G range: JPEG's loss moves them a few levels.
    const double tol = 4.0 / 255;
    CHECK(std::sqrt(metal->alpha.lo) == Approx(77.0 / 255).margin(tol));
    CHECK(std::sqrt(metal->alpha.hi) == Approx(153.0 / 255).margin(tol));
    CHECK(std::sqrt(metal->alpha.lo) > 0.25);  // not the full range [0, 1]
}
