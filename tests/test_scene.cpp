// Scenes: the plan of tables a scene needs (which kinds, over which ranges, merged where they can
// be shared), the glTF mapping, bad scene files, and `bake` (tables written, index, second bake
// does no work).
#include <catch2/catch.hpp>

#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfInputFile.h>
#include <nlohmann/json.hpp>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <fstream>
#include <set>

#include "brdfbake/error.h"
#include "brdfbake/lut.h"
#include "brdfbake/spec.h"
#include "scene/scene.h"
#include "scene_support.h"
#include "support.h"

using namespace brdfbake;
using testing::run_cli;

using namespace testing::scene;

namespace {

double mtime(const std::string& path) {
    struct stat st;
    if (::stat(path.c_str(), &st) != 0) return -1;
    return double(st.st_mtim.tv_sec) + 1e-9 * double(st.st_mtim.tv_nsec);
}

/// Bakes the scene file `scene` of tests/data into `out`, which must succeed; returns its index.
nlohmann::json bake_index(const std::string& scene, const std::string& out) {
    const auto r = run_cli("bake " + data(scene) + " -o " + out);
    INFO(r.err);
    REQUIRE(r.status == 0);
    return nlohmann::json::parse(testing::slurp(out + "/index.json"));
}

}  // namespace

TEST_CASE("two GGX metals and a rough glass plan exactly albedo and eavg over the metals' range plus one dielectric "
          "table", "[scene][quick]") {
    const Scene scene = load_scene(data("metals_glass.json"));
    const Plan plan = make_plan(scene);
    REQUIRE(plan.tables.size() == 3);
    std::multiset<std::string> kinds;
    for (const auto& t : plan.tables) kinds.insert(t.request.kind);
    CHECK(kinds == std::multiset<std::string>{"albedo", "eavg", "dielectric"});
    CHECK(plan.models == std::vector<std::string>{"ggx"});  // kernels for nothing else

    // albedo and eavg: the metals' alpha range, gold roughness [0.3, 0.5] and steel alpha 0.16
    // (roughness 0.4), i.e. roughness 0.3..0.5, with the first and last texel centres on it.
    for (const char* kind : {"albedo", "eavg"}) {
        INFO(kind);
        const PlannedTable* t = find_kind(plan, kind);
        REQUIRE(t);
        CHECK(t->request.model == "ggx:shadowing=correlated");
        CHECK(t->request.fresnel == "none");
        CHECK(t->alpha.lo == Approx(0.09));
        CHECK(t->alpha.hi == Approx(0.25));
        CHECK(t->request.alpha_map == "roughness");
        const int n = std::string(kind) == "eavg" ? t->request.width : t->request.height;
        CHECK(n >= 2);
        CHECK(n < 32);  // a share of the full range, not all of it
        CHECK(centre(t->request.alpha_lo, t->request.alpha_hi, n, 0) == Approx(0.3));
        CHECK(centre(t->request.alpha_lo, t->request.alpha_hi, n, n - 1) == Approx(0.5));
        CHECK(t->materials == std::vector<std::string>{"gold", "steel"});
        CHECK(t->unavailable.empty());
    }
    CHECK(find_kind(plan, "eavg")->request.height == 1);
    // The same alpha axis in both, so that a renderer reads them at the same coordinate.
    CHECK(find_kind(plan, "eavg")->request.alpha_lo == find_kind(plan, "albedo")->request.alpha_lo);
    CHECK(find_kind(plan, "eavg")->request.alpha_hi == find_kind(plan, "albedo")->request.alpha_hi);

    // One dielectric table at the glass's eta and roughness: one texel centred on each.
    const PlannedTable* d = find_kind(plan, "dielectric");
    REQUIRE(d);
    CHECK(d->materials == std::vector<std::string>{"glass"});
    CHECK(d->depth == 1);
    CHECK(centre(d->eta_lo, d->eta_hi, 1, 0) == Approx(1.5));
    CHECK(d->request.height == 1);
    CHECK(centre(d->request.alpha_lo, d->request.alpha_hi, 1, 0) == Approx(std::sqrt(0.05)));

    // The diffuse material needs none; estimates are there and positive.
    REQUIRE(plan.no_table.size() == 1);
    CHECK(plan.no_table[0].find("plaster") == 0);
    for (const auto& t : plan.tables) {
        CHECK(t.est_seconds > 0);
        CHECK(t.est_memory > 0);
        CHECK(t.samples_total == t.cells * t.request.samples);
        CHECK(t.hash.size() == 16);
    }
    CHECK(plan.warnings.empty());
}

TEST_CASE("materials that can share a table share it, model, shadowing and kind split them", "[scene][quick]") {
    const Plan plan = make_plan(load_scene(data("merge.json")));
    // correlated GGX: albedo + eavg shared by two metals and a Schlick plastic, ranges merged
    const PlannedTable* a = find_kind(plan, "albedo", "ggx:shadowing=correlated");
    REQUIRE(a);
    CHECK(a->materials == std::vector<std::string>{"rough iron", "shiny chrome", "plastic coat"});
    CHECK(a->alpha.lo == Approx(0.02));
    CHECK(a->alpha.hi == Approx(0.5));
    CHECK(a->file == "albedo-ggx.exr");
    // separable shadowing is another table
    const PlannedTable* s = find_kind(plan, "albedo", "ggx:shadowing=separable");
    REQUIRE(s);
    CHECK(s->materials == std::vector<std::string>{"old paint"});
    CHECK(s->file != a->file);
    // two glasses: one dielectric table over eta 1.33..1.7, texel centres on both ends
    const PlannedTable* d = find_kind(plan, "dielectric");
    REQUIRE(d);
    CHECK(d->materials == std::vector<std::string>{"water", "crystal"});
    REQUIRE(d->depth >= 2);
    CHECK(centre(d->eta_lo, d->eta_hi, d->depth, 0) == Approx(1.33));
    CHECK(centre(d->eta_lo, d->eta_hi, d->depth, d->depth - 1) == Approx(1.7));
    CHECK(d->alpha.lo == Approx(0.01));
    CHECK(d->alpha.hi == Approx(0.04));
    // an explicit "tables" list asks for the split-sum table only
    const PlannedTable* ms = find_kind(plan, "dfg-ms");
    REQUIRE(ms);
    CHECK(ms->materials == std::vector<std::string>{"ibl probe"});
    CHECK(plan.tables.size() == 6);
    std::set<std::string> files;
    for (const auto& t : plan.tables) files.insert(t.file);
    CHECK(files.size() == plan.tables.size());
    CHECK(plan.no_table.size() == 1);
    CHECK(plan.warnings.empty());
}

TEST_CASE("delta lobes need no table, oren-nayar's sigma is its roughness axis", "[scene][quick]") {
    const auto names = model_names();
    for (const char* needed : {"mirror", "oren-nayar"})
        if (std::find(names.begin(), names.end(), needed) == names.end()) {
            WARN("this build has no model '" << needed << "'");
            return;
        }
    const Scene scene = parse_scene_json(R"({"materials": [
        {"name": "mirror", "model": "mirror", "fresnel": "schlick:f0=0.9"},
        {"name": "skin", "model": "oren-nayar:sigma=0.3"},
        {"name": "gold", "model": "ggx", "fresnel": "metal:Au", "alpha": 0.2}]})",
                                         "inline.json");
    const Plan plan = make_plan(scene);
    // skin: albedo and eavg of oren-nayar over the table alpha that sets sigma = 0.3 (sigma = alpha,
    // the registry's RoughnessAxis), gold: those of ggx; the mirror none
    CHECK(plan.tables.size() == 4);
    CHECK(plan.models == std::vector<std::string>{"oren-nayar", "ggx"});  // in the order of the materials
    CHECK(plan.no_table.size() == 1);
    CHECK(contains(plan.no_table, "mirror (mirror: delta lobe"));
    CHECK(plan.warnings.empty());
    size_t on = 0;
    for (const auto& t : plan.tables)
        if (t.materials == std::vector<std::string>{"skin"}) {
            ++on;
            CHECK(t.alpha.lo == Approx(0.3).epsilon(1e-12));
            CHECK(t.alpha.hi == Approx(0.3).epsilon(1e-12));
        }
    CHECK(on == 2);
}

TEST_CASE("scenes: oren-nayar and Phong lobes plan over their mapped roughness axes, or name the key they need",
          "[scene][quick]") {
    // The table alpha sets oren-nayar's sigma = alpha and Phong's n = 2/alpha^2 - 2 (Walter et al.
    // 2007 sec. 5.2): n = 100 is alpha = sqrt(2/102), a range of alpha is the tables' axis.
    const Scene scene = parse_scene_json(R"({"materials": [
        {"name": "felt", "model": "oren-nayar", "alpha": [0.1, 0.5]},
        {"name": "plastic", "model": "phong:n=100"},
        {"name": "paint", "model": "blinn-phong", "roughness": 0.5}]})",
                                         "inline.json");
    const Plan plan = make_plan(scene);
    CHECK(plan.warnings.empty());
    CHECK(plan.models == std::vector<std::string>{"oren-nayar", "phong", "blinn-phong"});
    CHECK(plan.tables.size() == 6);
    for (const auto& t : plan.tables) {
        INFO(t.file);
        REQUIRE(t.materials.size() == 1);
        const std::string& m = t.materials[0];
        const double lo = m == "felt" ? 0.1 : m == "plastic" ? std::sqrt(2.0 / 102.0) : 0.25;
        const double hi = m == "felt" ? 0.5 : lo;
        CHECK(t.alpha.lo == Approx(lo).epsilon(1e-9));
        CHECK(t.alpha.hi == Approx(hi).epsilon(1e-9));
    }
    // without it: one line naming the key, or the range the axis covers
    for (const auto& [material, needle] : std::vector<std::pair<std::string, std::string>>{
             {R"({"name": "felt", "model": "oren-nayar"})", "or sigma=S in the model spec"},
             {R"({"name": "plastic", "model": "phong"})", "or n=N in the model spec"},
             {R"({"name": "felt", "model": "oren-nayar", "alpha": 2})", "beyond oren-nayar's roughness axis"},
             {R"({"name": "plastic", "model": "phong", "alpha": [0.1, 1.5]})", "beyond phong's roughness axis"}}) {
        INFO(material);
        try {
            make_plan(parse_scene_json(R"({"materials": [)" + material + "]}", "inline.json"));
            FAIL("accepted");
        } catch (const Error& e) {
            CHECK(std::string(e.what()).find(needle) != std::string::npos);
            CHECK(std::string(e.what()).find('\n') == std::string::npos);
        }
    }
}

TEST_CASE("glTF: metals, glass with ior and volume, clear coat, specular colour and anisotropy map to tables, "
          "the rest is named", "[scene][quick]") {
    const Scene scene = load_gltf_scene(data("materials.gltf"));
    const Plan plan = make_plan(scene);
    CHECK(plan.models == std::vector<std::string>{"ggx", "sheen"});  // velvet's KHR_materials_sheen
    const PlannedTable* a = find_kind(plan, "albedo");
    REQUIRE(a);
    // metals: aluminium (roughness 0.4), brushed steel (textured: roughness 0..0.3, metallic 0..1,
    // anisotropy 0.5 widens alpha to mix(alpha, 1, 0.25)) and the default material (roughness 1)
    CHECK(a->materials == std::vector<std::string>{"aluminium", "brushed steel", "(glTF default material)"});
    CHECK(a->alpha.lo == 0.0);
    CHECK(a->alpha.hi == Approx(1.0));
    const PlannedTable* d = find_kind(plan, "dielectric");
    REQUIRE(d);
    // glass at ior 1.45 and the clear coat at 1.5 share one dielectric table
    CHECK(d->eta->lo == Approx(1.45));
    CHECK(d->eta->hi == Approx(1.5));
    CHECK(contains(d->serves, "bottle glass (transmission)"));
    CHECK(contains(d->serves, "car paint (clearcoat)"));
    CHECK(contains(d->serves, "car paint (dielectric)"));
    CHECK(contains(d->serves, "brushed steel (dielectric)"));  // the texture makes it partly non-metal
    // a tinted specular colour makes F0 Schlick per channel: the split-sum table at its roughness
    const PlannedTable* dfg = find_kind(plan, "dfg");
    REQUIRE(dfg);
    CHECK(dfg->materials == std::vector<std::string>{"tinted plastic"});
    CHECK(dfg->alpha.lo == Approx(0.36));
    // velvet's sheen (sheenRoughness 0.6): its albedo table (tests/test_sheen.cpp has the details)
    const PlannedTable* sheen = find_kind(plan, "sheen-albedo");
    REQUIRE(sheen);
    CHECK(sheen->materials == std::vector<std::string>{"velvet"});
    CHECK(sheen->alpha.lo == Approx(0.36));
    // the transmissive bottle glass: its average R + T for rough-glass compensation
    const PlannedTable* deavg = find_kind(plan, "dielectric-eavg");
    REQUIRE(deavg);
    CHECK(deavg->materials == std::vector<std::string>{"bottle glass"});
    CHECK(deavg->eta->lo == Approx(1.45));
    CHECK(plan.tables.size() == 6);
    // not modelled: named, never silent
    CHECK_FALSE(contains(plan.warnings, "KHR_materials_sheen"));
    CHECK(contains(plan.warnings, "material 'velvet': VENDOR_materials_glitter is not modelled"));
    CHECK(contains(plan.warnings, "KHR_texture_transform is not modelled"));
    CHECK(contains(plan.warnings, "material 'brushed steel': KHR_materials_anisotropy is approximated"));
    CHECK(contains(plan.no_table, "unused (not used by any mesh primitive"));
    // notes say how each extension was read
    for (const auto& m : scene.materials)
        if (m.name == "bottle glass") CHECK(contains(m.notes, "KHR_materials_volume"));
}

TEST_CASE("the example scene plans in well under a second and bakes in a few seconds by estimate", "[scene][quick]") {
    const std::string here = __FILE__;
    const std::string root = here.substr(0, here.find_last_of('/', here.find_last_of('/') - 1));
    const Plan plan = make_plan(load_scene(root + "/examples/scene.json"));
    REQUIRE(plan.tables.size() == 3);
    double seconds = 0;
    for (const auto& t : plan.tables) seconds += t.est_seconds;
    CHECK(seconds < 5.0);
    const Plan gltf = make_plan(load_scene(root + "/examples/scene.gltf"));
    CHECK(gltf.tables.size() >= 2);
    CHECK(gltf.models == std::vector<std::string>{"ggx"});
}

TEST_CASE("malformed scene files and unknown material features give clear errors", "[scene][quick]") {
    struct Case {
        const char* file;
        const char* must_mention;
    };
    const Case cases[] = {
        {"bad_syntax.json", "is not valid JSON"},
        {"unknown_model.json", "unknown model 'ggxx'"},
        {"missing_model.json", "material 'velvet' has no 'model'"},
        {"missing_roughness.json", "material 'gold': needs its roughness"},
        {"unknown_feature.json", "unknown key 'sheen'"},
        {"bad.gltf", "cannot be read"},
        {"truncated.glb", "cannot be read"},
        {"does-not-exist.json", "cannot read scene"},
    };
    for (const auto& c : cases) {
        INFO(c.file);
        const std::string msg = error_of([&] { load_scene(data(c.file)); });
        CHECK(msg.find(c.must_mention) != std::string::npos);
        CHECK(msg.find('\n') == std::string::npos);
    }
    // inline cases: values out of range and contradictions
    const std::pair<const char*, const char*> inline_cases[] = {
        {R"({"materials": [{"name": "a", "model": "ggx", "alpha": -0.1}]})", "must not be negative"},
        {R"({"materials": [{"name": "a", "model": "ggx", "alpha": [0.5, 0.1]}]})", "lo > hi"},
        {R"({"materials": [{"name": "a", "model": "ggx:alpha=0.2", "alpha": 0.3}]})", "roughness once"},
        {R"({"materials": [{"name": "a", "model": "ggx", "alpha": 0.2, "eta": 0.8, "transmission": true}]})", "1 < eta"},
        {R"({"materials": [{"name": "a", "model": "ggx", "alpha": 0.2, "transmission": true}]})", "needs an index of refraction"},
        {R"({"materials": [{"name": "a", "model": "ggx", "alpha": 0.2, "tables": ["sheen"]}]})", "unknown table kind 'sheen'"},
        {R"({"materials": [{"name": "a", "model": "lambert", "fresnel": "schlick:f0=0.04"}]})", "no Fresnel term"},
        {R"({"materials": [{"name": "a", "model": "ggx", "alpha": 0.2}, {"name": "a", "model": "ggx", "alpha": 0.3}]})", "two materials are named 'a'"},
        {R"({"materials": []})", "is empty"},
        {R"({"materials": [{"name": "a", "model": "ggx", "alpha": 0.2}], "settings": {"samples": 4}})", "samples"},
        {R"({"materials": [{"name": "a", "model": "ggx", "alpha": 0.2}], "settings": {"colour": 1}})", "not a setting"},
        {R"({"materials": [{"name": "a", "model": "ggx", "alpha": 0.2}], "lights": []})", "unknown top-level key 'lights'"},
    };
    for (const auto& c : inline_cases) {
        INFO(c.first);
        const std::string msg = error_of([&] { parse_scene_json(c.first, "inline.json"); });
        CHECK(msg.find(c.second) != std::string::npos);
    }
}

TEST_CASE("plan and bake reject bad scenes with one line and exit status 2, writing nothing", "[scene][cli]") {
    const std::string out = fresh_tmp_dir("bad");
    for (const char* f : {"bad_syntax.json", "unknown_model.json", "missing_model.json", "unknown_feature.json", "bad.gltf",
                          "truncated.glb"}) {
        INFO(f);
        for (const char* cmd : {"plan ", "bake "}) {
            const auto r = run_cli(std::string(cmd) + data(f) + (cmd[0] == 'b' ? " -o " + out : ""));
            CHECK(r.status == 2);
            CHECK(r.out.empty());
            CHECK(r.err.rfind("brdfbake: error: ", 0) == 0);
            CHECK(testing::count_lines(r.err) == 1);
        }
    }
    CHECK(::access(out.c_str(), F_OK) != 0);  // the bake never created its folder
    const auto r = run_cli("plan " + data("metals_glass.json") + " --format xml");
    CHECK(r.status == 2);
}

TEST_CASE("plan --format json lists the tables with their ranges, sizes, materials and estimates", "[scene][cli]") {
    const auto r = run_cli("plan " + data("metals_glass.json") + " --format json");
    REQUIRE(r.status == 0);
    const auto j = nlohmann::json::parse(r.out);
    REQUIRE(j.at("tables").size() == 3);
    for (const auto& t : j["tables"]) {
        CHECK(t.at("estimated_seconds").get<double>() > 0);
        CHECK(t.at("estimated_memory_bytes").get<double>() > 0);
        CHECK(!t.at("materials").empty());
        CHECK(!t.at("axes").empty());
    }
    CHECK(j.at("models") == nlohmann::json::array({"ggx"}));
    const auto text = run_cli("plan " + data("materials.gltf"));
    REQUIRE(text.status == 0);
    CHECK(text.out.find("warning: material 'velvet': VENDOR_materials_glitter is not modelled") != std::string::npos);
    CHECK(text.out.find("sheen-albedo-sheen.exr") != std::string::npos);
    CHECK(text.out.find("albedo-ggx.exr") != std::string::npos);
}

TEST_CASE("bake writes the tables and an index, a second bake does no work", "[scene][device]") {
    const std::string out = fresh_tmp_dir("bake");
    const auto index = bake_index("small_bake.json", out);
    REQUIRE(index.at("tables").size() == 2);
    std::map<std::string, double> times;
    for (const auto& t : index["tables"]) {
        const std::string file = t.at("file");
        CHECK(t.at("materials") == nlohmann::json::array({"iron", "brass"}));
        CHECK(t.at("max_error").get<double>() > 0);
        CHECK(t.at("max_error").get<double>() < 0.05);
        CHECK(t.at("request_hash").get<std::string>().size() == 16);
        times[file] = mtime(out + "/" + file);
        CHECK(times[file] > 0);
    }
    const double index_time = mtime(out + "/index.json");
    const auto ms = index.at("materials");
    REQUIRE(ms.size() == 2);
    CHECK(ms[0].at("tables").size() == 2);

    const auto second = run_cli("bake " + data("small_bake.json") + " -o " + out);
    REQUIRE(second.status == 0);
    CHECK(second.err.find("up to date") != std::string::npos);
    CHECK(second.err.find("nothing to compute") != std::string::npos);
    for (const auto& kv : times) CHECK(mtime(out + "/" + kv.first) == kv.second);
    CHECK(mtime(out + "/index.json") == index_time);

    // A removed file is recomputed, the other one is not.
    std::remove((out + "/eavg-ggx.exr").c_str());
    const auto third = run_cli("bake " + data("small_bake.json") + " -o " + out);
    REQUIRE(third.status == 0);
    CHECK(third.err.find("baked 1 table (1 up to date)") != std::string::npos);
    CHECK(mtime(out + "/albedo-ggx.exr") == times["albedo-ggx.exr"]);
    // Another sample count is another request: both recomputed.
    const auto fourth = run_cli("bake " + data("small_bake.json") + " -o " + out + " --samples 512");
    REQUIRE(fourth.status == 0);
    CHECK(fourth.err.find("baked 2 tables") != std::string::npos);
    std::system(("rm -rf " + out).c_str());
}

TEST_CASE("a baked table, computed in tiles, holds what compute_lut gives for the whole request", "[scene][device]") {
    const std::string out = fresh_tmp_dir("tiles");
    REQUIRE(run_cli("bake " + data("small_bake.json") + " -o " + out).status == 0);
    const Plan plan = make_plan(load_scene(data("small_bake.json")));
    const PlannedTable* a = find_kind(plan, "albedo");
    REQUIRE(a);
    const Table whole = compute_lut(testing::engine(), a->request);

    Imf::InputFile in((out + "/" + a->file).c_str());
    const Imath::Box2i dw = in.header().dataWindow();
    const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
    REQUIRE(w == whole.width());
    REQUIRE(h == whole.height());
    std::vector<float> e(size_t(w) * h);
    Imf::FrameBuffer fb;
    fb.insert("E", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(e.data()), sizeof(float), sizeof(float) * w));
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    for (size_t k = 0; k < e.size(); ++k) {
        INFO("texel " << k);
        CHECK(e[k] == Approx(whole.values[0][k]).margin(1e-6));
    }
    std::system(("rm -rf " + out).c_str());
}

TEST_CASE("bake a rough glass: the dielectric table over the scene's eta", "[scene][device]") {
    const std::string out = fresh_tmp_dir("glass");
    const auto index = bake_index("small_glass.json", out);
    REQUIRE(index.at("tables").size() == 1);
    const auto& t = index["tables"][0];
    CHECK(t.at("kind") == "dielectric");
    REQUIRE(t.at("axes").size() == 3);
    CHECK(t.at("axes")[2].at("name") == "eta");
    CHECK(t.at("axes")[2].at("size") == 1);
    CHECK(t.at("channels").size() == 4);
    CHECK(t.at("max_error").get<double>() < 0.1);
    std::system(("rm -rf " + out).c_str());
}

TEST_CASE("grouped_warnings: a warning several materials share is one line naming them", "[scene][quick]") {
    const std::vector<std::string> in = {
        "material 'a': KHR_materials_dispersion is not modelled",
        "extension KHR_texture_transform is not modelled",
        "material 'b': KHR_materials_dispersion is not modelled",
        "material 'c': ior 1.2 is clamped",
        "material 'd': KHR_materials_dispersion is not modelled",
    };
    const std::vector<std::string> out = brdfbake::grouped_warnings(in);
    REQUIRE(out.size() == 3);
    CHECK(out[0] == "KHR_materials_dispersion is not modelled (3 materials: a, b, d)");
    CHECK(out[1] == in[1]);
    CHECK(out[2] == in[3]);  // one material: as it was
}

TEST_CASE("bake: oren-nayar and Phong materials bake their tables over the mapped axes", "[scene][device]") {
    const std::string out = fresh_tmp_dir("bake_mapped");
    std::system(("mkdir -p " + out).c_str());
    const std::string scene = out + "/scene.json";
    std::ofstream(scene) << R"({"settings": {"samples": 256, "mu_texels": 8, "alpha_texels": 4},
        "materials": [{"name": "skin", "model": "oren-nayar:sigma=0.3"},
                      {"name": "plastic", "model": "phong", "alpha": [0.1, 0.4]}]})";
    const auto r = run_cli("bake " + scene + " -o " + out + "/tables");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto index = nlohmann::json::parse(testing::slurp(out + "/tables/index.json"));
    REQUIRE(index.at("tables").size() == 4);
    std::set<std::string> models;
    for (const auto& t : index["tables"]) {
        const std::string model = t.at("model").get<std::string>();
        models.insert(model.substr(0, model.find(':')));
        CHECK(t.at("max_error").get<double>() > 0);
        CHECK(t.at("max_error").get<double>() < 0.05);
    }
    CHECK(models == std::set<std::string>{"oren-nayar", "phong"});
    std::system(("rm -rf " + out).c_str());
}
