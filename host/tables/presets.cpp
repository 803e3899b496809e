// The presets: for each engine, the settings that make `brdfbake lut` write a table that replaces
// one the engine ships. Each convention is read from the engine's public source (cited per entry
// and in the README's "Drop-in tables" section); where an engine's own table sits away from where
// its shader reads, the preset writes what the shader reads.
#include <limits>
#include <sstream>
#include <tuple>
#include <utility>

#include "brdfbake/error.h"
#include "brdfbake/fresnel_terms.h"
#include "brdfbake/lut.h"
#include "brdfbake/table_kinds.h"
#include "models/key_reader.h"
#include "tables/lut_common.h"

namespace brdfbake {
namespace {

/// What every preset shares: height-correlated GGX (each engine's visibility term is the
/// height-correlated Smith G2 of Heitz 2014, or an approximation of it), F = 1 or factored out,
/// a fixed sample count per texel, every engine indexing by perceptual roughness r, alpha = r^2;
/// then the engine's size, axis order and flips.
LutRequest engine_layout(int width, int height, std::vector<std::string> axes = {},
                         std::vector<std::string> flip = {}) {
    LutRequest r;
    r.model = "ggx:shadowing=correlated";
    r.alpha_map = "roughness";
    r.alpha_lo = 0.0;
    r.alpha_hi = 1.0;
    r.samples = std::uint64_t(1) << 16;
    r.width = width;
    r.height = height;
    r.axes = std::move(axes);
    r.flip = std::move(flip);
    return r;
}

// Blender Cycles (intern/cycles/app/cycles_precompute.cpp): table_ggx_E[y * 32 + x] with
// x = roughness r = i/31 (floored at 1e-4), y = mu = j/31 (floored at 1e-4), alpha = r^2, and
// table_ggx_Eavg[x] = integral of 2 mu E(mu) over mu in [0, 1]; read by lookup_table_read_2D,
// which interpolates between texels at i/(N - 1) (edges), at roughness sqrt(sqrt(alpha_x alpha_y))
// (intern/cycles/kernel/closure/bsdf_microfacet.h). The r = 0 column is Cycles' r = 1e-4
// (alpha = 1e-8): computed here as the mirror limit, E = 1, which Cycles' own values reach.
// Cycles prints 6 decimals: half a unit of the last is 5e-7, the tolerance of every table but
// the glass ones (cycles_glass_layout).
LutRequest cycles_layout(int width, int height, int depth, std::vector<std::string> axes, double tolerance = 5e-7) {
    LutRequest r = engine_layout(width, height, std::move(axes));
    r.depth = depth;
    r.texels = Texels::Edge;
    r.mu_lo = 0.0;
    r.mu_hi = 1.0;
    r.mu_floor = 1e-4;
    r.precision = Precision::Double;
    r.tolerance.tolerance = tolerance;
    r.tolerance.auto_method = true;
    return r;
}

// table_sheen_ltc[(k * 32 + j) * 32 + i]: planes k = A, B, R of the volumetric sheen (Zeltner et
// al. 2022), x = mu i/31, y = roughness j/31, both floored at 0.01 as the paper's fit floors them
// (kind_sheen_ltc.cpp); read by bsdf_sheen_setup (intern/cycles/kernel/closure/bsdf_sheen.h).
LutRequest cycles_sheen_layout() {
    LutRequest r = engine_layout(32, 32);
    r.model = "sheen";  // alpha = roughness^2 = the layer's sigma (engine_layout's --alpha-map roughness)
    r.texels = Texels::Edge;
    r.mu_floor = 0.01;
    r.samples = std::uint64_t(1) << 18;
    return r;
}

// table_ggx_glass_E and table_ggx_glass_inv_E[(z * 16 + y) * 16 + x], table_ggx_glass_Eavg and
// table_ggx_glass_inv_Eavg[z * 16 + x]: the single-scattering albedo R + T of a rough GGX glass
// interface (Eavg: 2 integral of (R + T) mu dmu over mu) with the exact dielectric Fresnel and
// Cycles' G2 = 1/(1 + Lambda_i + Lambda_o) for both lobes; x = roughness i/15, y = mu j/15
// (floored at 1e-4), z = k/15 with eta = (1 + z^2)/(1 - z^2) (ior_from_F0(z^4)), z clamped to
// [1e-4, 0.99] (eta 1 to 99.5); "inv" is light from the denser side, at 1/eta: brdfbake's
// *_inside channels. Read by microfacet_ggx_preserve_energy at z = sqrt(|eta - 1|/(eta + 1)) with
// eta < 1 inverted onto the inv tables (bsdf_microfacet.h). z = 0 (eta = 1, no interface) is
// E = 1: Cycles computes it at z = 1e-4, where eta rounds to 1 in float, and treats
// |eta - 1| < 1e-4 as a smooth pass. The glass tables are Monte Carlo of 2^23 (E) and 2^26 (Eavg)
// samples a texel in Cycles, about 1e-4 of noise; 5e-7 is out of the dielectric kind's reach at
// a few texels (67M samples each), 1e-6 takes about 4 minutes.
LutRequest cycles_glass_layout(int height, std::vector<std::string> axes, double tolerance) {
    LutRequest r = cycles_layout(16, height, 16, std::move(axes), tolerance);
    r.model = "ggx:shadowing=correlated,transmission_shadowing=cycles";
    r.eta_map = "cycles";
    r.eta_lo = 1.0;
    r.eta_hi = std::numeric_limits<double>::infinity();  // z up to 1, computed at 0.99 (eta_axis)
    return r;
}

// The glTF Sample Viewer's sheen LUTs (host/tables/kind_sheen_viewer.cpp): x = NdotV, y =
// sheenRoughness, texel centres, row 0 at roughness near 0 (no flip, as lut_ggx.png), one channel
// written R = G = B (lut_charlie is read .b, lut_sheen_E .r); 128 x 128 (the shaders read by
// normalized coordinates with linear filtering, so any size drops in; the viewer renders its own
// at 1024 x 1024: --size 1024x1024 takes 64 times as long). The model picks the table: visibility
// charlie is lut_sheen_E (the default), ashikhmin lut_charlie.
LutRequest gltf_sheen_layout() {
    LutRequest r = engine_layout(128, 128);
    r.model = "sheen:visibility=charlie";
    r.samples = 128 * 128 + 64 * 64;  // the nodes of its two quadrature rules: what the plan's estimate counts
    return r;
}

// three.js's rect-light LTC textures (examples/jsm/lights/RectAreaLightTexturesLib.js: LTC_FLOAT_1
// and LTC_FLOAT_2, 64 x 64 RGBA) as its shaders read them (bsdfs LTC_Uv: uv = (roughness,
// sqrt(1 - dotNV)) * 63/64 + 0.5/64, i.e. texel i at i/63 on both axes; the matrix packing in
// kind_ltc.cpp, "three"); ltc_code's fit behind them sets theta = min(1.57, acos(mu)), so the last
// row is computed at mu = cos(1.57). docs/ltc_presets.md.
LutRequest three_ltc_layout() {
    LutRequest r = engine_layout(64, 64, {"roughness", "sqrt_one_minus_mu"});
    r.texels = Texels::Edge;
    r.mu_map = "sqrt-one-minus";
    r.mu_floor = 7.963e-4;  // cos(1.57)
    r.packing = "three";
    return r;
}

// Blender EEVEE's LTC tables (source/blender/draw/engines/eevee/eevee_lut.cc: ltc_mat_ggx and
// ltc_mag_ggx, declared in eevee_lut.hh): three.js's grid and numbers (ltc_code's fit/results/ltc.js
// printed to 6 decimals, docs/ltc_presets.md), read at lut_coords / utility_tx_sample_lut:
// uv = (roughness, sqrt(1 - cos_theta)) * 63/64 + 0.5/64 (eevee_utility_tx_lib.glsl). Packing
// "eevee" (kind_ltc.cpp) names the channels after Blender's arrays; -o NAME.cc writes Blender 4.2's
// eevee_lut.cc arrays, -o NAME.c legacy EEVEE's (table_eevee_source).
LutRequest eevee_ltc_layout() {
    LutRequest r = three_ltc_layout();
    r.packing = "eevee";
    return r;
}

// Unity HDRP's GGX LTC table (Runtime/Material/LTCAreaLight/Generated/LtcData.BRDF_GGX.cs,
// s_LtcMatrixData_BRDF_GGX[a + 64 t]): three.js's axes (LTCTableGenerator.cs GetRoughnessAndAngle,
// CosTheta parametrisation: perceptual roughness a/63, cos theta = 1 - (t/63)^2 floored at
// 3.7540224885647058e-4; read at Remap01ToHalfTexelCoord(perceptualRoughness, sqrt(1 - NdotV)) in
// LTCAreaLight.hlsl). Packing "unity-hdrp" (kind_ltc.cpp); -o NAME.cs writes the C# file
// (table_unity_hdrp_source). docs/ltc_presets.md, "Unity HDRP".
LutRequest unity_hdrp_ltc_layout() {
    LutRequest r = three_ltc_layout();
    r.mu_floor = 3.7540224885647058e-4;
    r.packing = "unity-hdrp";
    return r;
}

// HDRP's GGX LTC table of 2021 to mid-2023 (the same file, s_LtcMatrixData_BRDF_GGX as double[64 * 64,
// 3 * 3], read by LoadLUT): the same grid, packing "unity-hdrp-2021" (kind_ltc.cpp).
LutRequest unity_hdrp_2021_ltc_layout() {
    LutRequest r = unity_hdrp_ltc_layout();
    r.packing = "unity-hdrp-2021";
    return r;
}

std::string join_names(const std::vector<std::string>& names) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    return list;
}

/// A preset row: its layouts' kind names filled in from the table-kind registry.
LutPreset preset_row(LutPreset p) {
    for (const PresetLayout& l : p.layouts) p.kinds.push_back(table_kind(l.kind).name);
    return p;
}

}  // namespace

const std::vector<LutPreset>& lut_presets() {
    using K = TableKindId;
    static const std::vector<std::string> roughness_mu = {"roughness", "mu"},
                                          cycles_3d = {"roughness", "mu", "cycles_z"};
    static const std::vector<LutPreset> presets = {
        // glTF Sample Viewer (KhronosGroup/glTF-Sample-Viewer, source/Renderer/shaders/ibl.glsl): the
        // split-sum LUT lut_ggx.png is read as texture(u_GGXLUT, vec2(NdotV, roughness)).rg, f_ab.x the
        // scale A and f_ab.y the bias B; 16-bit PNG, WebGL upload without a flip (row 0 at t = 0).
        // Its sheen LUTs: gltf_sheen_layout.
        preset_row({"gltf", "glTF Sample Viewer",
                    "lut_ggx.png; sheen-viewer: lut_sheen_E.png (model sheen:visibility=charlie, the default) and "
                    "lut_charlie.png (sheen:visibility=ashikhmin)",
                    "png", false,
                    "1024 x 1024, x = NdotV, y = roughness (row 0 at 0), texel centres, R = A, G = B, B = 0, 16-bit PNG; "
                    "sheen-viewer: 128 x 128, x = NdotV, y = sheenRoughness (row 0 at 0), texel centres, R = G = B = "
                    "min(E, 1), 16-bit PNG",
                    {{K::Dfg, engine_layout(1024, 1024), ""}, {K::SheenViewer, gltf_sheen_layout(), ""}}, {}}),
        // Filament (google/filament, libs/ibl/src/CubemapIBL.cpp, CubemapIBL::DFG with multiscatter):
        // R = sum of V Fc = B, G = sum of V = E = A + B, read as mix(dfg.xxx, dfg.yyy, f0)
        // (shaders/src/surface_light_indirect.fs); x = NoV at texel centres. cmgen's image has its
        // row 0 at the roughest, but the dfg.inc Filament builds in (tools/cmgen/src/cmgen.cpp,
        // iblLutDfg: "in GL order", row y written from image row size - 1 - y) starts at the
        // smoothest, row 0 at t = 0 of the texture the shader samples at perceptual roughness: the
        // preset writes that order (no flip); --flip roughness gives cmgen's image order. cmgen
        // computes image row y at (height - y + 0.5)/height, one texel off the centre that a sampler
        // reads: the preset writes the centres.
        preset_row({"filament", "Filament", "dfg.inc (cmgen --ibl-dfg-multiscatter)", "exr", true,
                    "128 x 128, x = NoV, y = perceptual roughness from 0 (row 0) up as in dfg.inc, texel centres, "
                    "R = B, G = E = A + B, half-float EXR",
                    {{K::DfgMs, engine_layout(128, 128), ""}}, {}}),
        // three.js (mrdoob/three.js, src/renderers/shaders/DFGLUTData.js): a 16 x 16 RG16F DataTexture,
        // (scale, bias) = (A, B), sampled at vec2(roughness, dotNV): x = roughness, y = NoV, texel
        // centres, row 0 at NoV near 0.
        preset_row({"three", "three.js",
                    "src/renderers/shaders/DFGLUTData.js; ltc: LTC_FLOAT_1 and LTC_FLOAT_2 of "
                    "examples/jsm/lights/RectAreaLightTexturesLib.js",
                    "exr", true,
                    "16 x 16, x = roughness, y = NoV, texel centres, R = A (scale), G = B (bias), half-float EXR "
                    "(RG16F); ltc: 64 x 64, x = roughness a/63, y = sqrt(1 - NoV) t/63, channels ltc_1.RGBA = "
                    "M^-1 / M^-1_11 as (00, 20, 02, 22) and ltc_2.RGBA = (magnitude, fresnel, 0, 0)",
                    {{K::Dfg, engine_layout(16, 16, roughness_mu), ""}, {K::Ltc, three_ltc_layout(), ""}}, {}}),
        // Blender Cycles: see cycles_layout and cycles_glass_layout. table_ggx_gen_schlick_s and
        // table_ggx_gen_schlick_ior_s[(z * 16 + y) * 16 + x]: x and y as table_ggx_E's, z = i/15 on
        // the kind's own z axis (cycles_z: Cycles' exponent or eta parameterisation, clamped to
        // [1e-4, 0.99]), read by lookup_table_read_3D; with --estimator cycles, what Cycles' own
        // tables hold: the albedo of the lobe whose G2 is the masking term G1(wo) alone (its
        // Monte-Carlo estimator averages w over the visible normals). dielectric-eavg shares its
        // tolerance out, a quarter to each of R and T: 4e-6 holds them to 1e-6.
        preset_row({"cycles", "Blender Cycles",
                    "table_ggx_E, table_ggx_Eavg, table_ggx_gen_schlick_s, table_ggx_gen_schlick_ior_s, "
                    "table_ggx_glass_E and table_ggx_glass_inv_E (dielectric: R + T and R_inside + T_inside), "
                    "table_ggx_glass_Eavg and table_ggx_glass_inv_Eavg (dielectric-eavg: Eavg, Eavg_inside), "
                    "table_sheen_ltc (sheen-ltc: a, b, R) (intern/cycles/scene/shader.tables)",
                    "h", false,
                    "32 x 32 (32 for eavg; 16 x 16 x 16 for gen-schlick, gen-schlick-ior and dielectric with z = "
                    "cycles_z, 16 x 16 for dielectric-eavg with z = cycles_z, the dielectric kinds with Cycles' "
                    "transmission shadowing; gen-schlick kinds with --estimator cycles: Cycles' own estimator on "
                    "ggx:shadowing=masking), x = roughness, y = mu, edge texels (i/(N - 1)), mu floored at 1e-4, "
                    "double precision to 5e-7 (dielectric: 1e-6, dielectric-eavg: 4e-6), C header; sheen-ltc: "
                    "32 x 32, x = mu, y = roughness, both floored at 0.01",
                    {{K::Albedo, cycles_layout(32, 32, 16, roughness_mu), ""},
                     {K::Eavg, cycles_layout(32, 1, 16, {}), ""},
                     {K::GenSchlick, cycles_layout(16, 16, 16, cycles_3d), "ggx:shadowing=masking"},
                     {K::GenSchlickIor, cycles_layout(16, 16, 16, cycles_3d), "ggx:shadowing=masking"},
                     {K::Dielectric, cycles_glass_layout(16, cycles_3d, 1e-6), ""},
                     // x = roughness, z = cycles_z: already Cycles' order
                     {K::DielectricEavg, cycles_glass_layout(1, {}, 4e-6), ""},
                     {K::SheenLtc, cycles_sheen_layout(), ""}}, {}}),
        // Unreal Engine (Engine/Shaders/Private/BRDF.ush, EnvBRDF): the split-sum texture
        // PreIntegratedGF is read at float2(NoV, Roughness), .x the scale A and .y the bias B of
        // SpecularColor * A + saturate(50 * SpecularColor.g) * B; 128 x 32 texels, centres.
        preset_row({"unreal", "Unreal Engine", "PreIntegratedGF (EnvBRDF)", "png", false,
                    "128 x 32, x = NoV, y = roughness, texel centres, R = A, G = B, 16-bit PNG",
                    {{K::Dfg, engine_layout(128, 32), ""}}, {}}),
        // Blender EEVEE: see eevee_ltc_layout.
        preset_row({"eevee", "Blender EEVEE",
                    "ltc_mat_ggx and ltc_mag_ggx (source/blender/draw/engines/eevee/eevee_lut.cc, declared in "
                    "eevee_lut.hh; read by eevee_ltc_lib.glsl's ltc_matrix)",
                    "cc", false,
                    "ltc: 64 x 64, x = roughness a/63, y = sqrt(1 - NoV) t/63 (three.js's grid), "
                    "ltc_mat_ggx[t][a] = M^-1 / M^-1_11 as (00, 20, 02, 22) (three.js's ltc_1), ltc_mag_ggx[t][a] = "
                    "(magnitude, fresnel); C++ source, float literals: .cc for Blender 4.2 and later "
                    "(namespace blender::eevee::lut, float[64][64][4] and [64][64][2]), .c for legacy EEVEE, "
                    "Blender 2.80 to 4.1 (float[64 * 64 * 4] and [64 * 64 * 2])",
                    {{K::Ltc, eevee_ltc_layout(), ""}}, {}}),
        // Unity HDRP: see unity_hdrp_ltc_layout.
        preset_row({"unity-hdrp", "Unity HDRP",
                    "s_LtcMatrixData_BRDF_GGX (Runtime/Material/LTCAreaLight/Generated/LtcData.BRDF_GGX.cs, "
                    "uploaded by LTCAreaLight.cs into slice 0 of _LtcData; read by SampleLtcMatrix)",
                    "cs", false,
                    "ltc: 64 x 64, x = perceptual roughness a/63, y = sqrt(1 - NoV) t/63 (NoV floored at 3.754e-4), "
                    "s_LtcMatrixData_BRDF_GGX[4 (a + 64 t) + c] = M^-1 / M^-1_22 as (00, 20, 11, 02) in half floats "
                    "(ushort bits, clamped to 65504); C# source for HDRP from 2023 (pull request #7929)",
                    {{K::Ltc, unity_hdrp_ltc_layout(), ""}}, {}}),
        preset_row({"unity-hdrp-2021", "Unity HDRP (2021 to mid-2023)",
                    "s_LtcMatrixData_BRDF_GGX as double[64 * 64, 3 * 3] (Generated/LtcData.BRDF_GGX.cs from the LTC "
                    "table generator of pull request #3957 to pull request #7929; uploaded by LTCAreaLight.cs LoadLUT)",
                    "cs", false,
                    "ltc: unity-hdrp's grid, s_LtcMatrixData_BRDF_GGX[a + 64 t, r + 3 c] = M^-1_rc / M^-1_22 (all nine, "
                    "doubles; LoadLUT uploads entries 0, 2, 4, 6 clamped to 65504 as half floats)",
                    {{K::Ltc, unity_hdrp_2021_ltc_layout(), ""}}, {}}),
    };
    return presets;
}

const LutPreset& lut_preset(const std::string& name) {
    std::string known;
    std::vector<std::string> names;
    for (const LutPreset& p : lut_presets()) {
        if (p.name == name) return p;
        known += (known.empty() ? "" : ", ") + p.name;
        names.push_back(p.name);
    }
    throw Error(unknown_name_message("preset", name, names, "known", known));
}

const PresetLayout* LutPreset::layout(const std::string& kind) const {
    const TableKind* asked = find_table_kind(kind);
    for (const PresetLayout& l : layouts)
        if (asked && l.kind == asked->id) return &l;
    return nullptr;
}

void LutPreset::apply(LutRequest& request) const {
    // A kind without a layout of its own gets the default one (the first).
    const PresetLayout* own = layout(request.kind);
    const PresetLayout* l = own ? own : &layouts.front();
    LutRequest r = l->settings;
    r.kind = request.kind;
    r.estimator = request.estimator;  // the preset's model follows the quantity asked for
    if (!l->cycles_estimator_model.empty() && r.estimator == "cycles")
        r.model = l->cycles_estimator_model;
    request = std::move(r);
}

namespace {

/// `--thickness-step NM`: the thin-film table's slices at most NM apart over its thickness range
/// (tables::thickness_slices, the scene setting thickness_step's rule) instead of --size's depth.
void apply_thickness_step(double step_nm, const std::optional<std::vector<int>>& size, LutRequest& r) {
    const auto nm = [](double v) {
        std::ostringstream text;
        text << v;
        return text.str();
    };
    const std::string step = nm(step_nm);
    if (r.kind != "thin-film") throw Error("--thickness-step spaces the thin-film table's slices; this is the " + r.kind + " table");
    if (size && size->size() == 3)
        throw Error("--thickness-step sets the table's depth; give --size N or WIDTHxHEIGHT beside it, not a depth");
    const double span = r.thickness_hi - r.thickness_lo;
    if (!(step_nm > 0.0 && step_nm <= span))
        throw Error("--thickness-step " + step + ": must lie in (0, HI - LO] = (0, " + nm(span) + "] nm");
    const int slices = tables::thickness_slices(r.thickness_lo, r.thickness_hi, step_nm);
    if (slices > 256) throw Error("--thickness-step " + step + " gives " + std::to_string(slices) + " slices; at most 256");
    r.depth = slices;
}

/// "--size 32x32x4", for the messages of set_lut_size.
std::string size_text(const std::vector<int>& size) {
    std::string text;
    for (int n : size) text += (text.empty() ? "" : "x") + std::to_string(n);
    return text;
}

std::pair<double, double> range_of(const std::vector<double>& range, const std::string& option) {
    if (range.size() != 2) throw Error(option + " needs two numbers: LO,HI");
    return {range[0], range[1]};
}

Precision precision_of(const std::string& name) {
    if (name == "float") return Precision::Float;
    if (name == "double") return Precision::Double;
    throw Error("--precision must be float or double, not '" + name + "'");
}

/// The kind asked for (the preset's first without one) and the preset's layout for it.
const LutPreset* preset_for_kind(const LutSettings& given, LutRequest& r) {
    const LutPreset* preset = given.preset ? &lut_preset(*given.preset) : nullptr;
    if (given.kind) {
        r.kind = *given.kind;
    } else {
        if (!preset) throw Error("lut needs a table kind (" + table_kind_names() + ")");
        r.kind = preset->kinds.front();
    }
    const TableKind& kind = table_kind(r.kind);
    if (given.estimator) {
        if (!kind.cycles_estimator)
            throw Error("--estimator is for the gen-schlick, gen-schlick-ior and sheen-ltc tables, not " + r.kind);
        r.estimator = *given.estimator;
    }
    if (preset) {
        if (!preset->layout(r.kind))
            throw Error("preset '" + preset->name + "' has a layout for " + join_names(preset->kinds) + " tables, not " +
                        r.kind);
        preset->apply(r);  // its layout for the kind (the kind and estimator stay)
    } else if (!given.model) {
        throw Error("--model is required (or give --preset)");
    }
    return preset;
}

}  // namespace

LutSetup apply_preset(const LutSettings& given) {
    LutSetup setup;
    LutRequest& r = setup.request;
    const LutPreset* preset = preset_for_kind(given, r);
    setup.half = given.half ? *given.half : preset && preset->half;
    if (given.model) r.model = *given.model;
    if (given.fresnel) r.fresnel = *given.fresnel;
    if (given.wavelength_nm) r.wavelength_nm = *given.wavelength_nm;
    if (given.colour) {  // only where the table holds a colour: anywhere else it would be ignored
        const std::string option = *given.colour == "wavelengths" ? "--rgb-wavelengths" : "--colour-space";
        if (!table_kind(r.kind).spectral_colour)
            throw Error(option + " is for tables that hold a colour (conductor), not " + r.kind);
        if (r.wavelength_nm != 0.0 || !fresnel_needs_wavelength(r.fresnel))
            throw Error(option + " needs a Fresnel term that depends on the wavelength (metal:X, nk:FILE, "
                        "thin-film:) and no --wavelength; --fresnel " + (r.fresnel.empty() ? "none" : r.fresnel) +
                        (r.wavelength_nm != 0.0 ? " with --wavelength" : "") +
                        " has one value, not a colour");
        r.colour = *given.colour;
    }
    if (given.size) {
        try {
            // With --thickness-step the depth is the step's: WIDTHxHEIGHT is the whole size then.
            std::vector<int> dims = *given.size;
            if (given.thickness_step && dims.size() == 2) dims.push_back(dims[1]);
            set_lut_size(r, dims);
        } catch (const Error& e) {
            throw Error(std::string(e.what()) + " (--size " + size_text(*given.size) + ")");
        }
    } else if (!preset) {
        set_lut_size(r, {kDefaultLutTexels});
    }
    if (given.mu_map) r.mu_map = *given.mu_map;
    if (given.alpha_map) r.alpha_map = *given.alpha_map;
    if (given.eta_map) r.eta_map = *given.eta_map;
    if (given.alpha_range) std::tie(r.alpha_lo, r.alpha_hi) = range_of(*given.alpha_range, "--alpha-range");
    if (given.eta_range) std::tie(r.eta_lo, r.eta_hi) = range_of(*given.eta_range, "--eta-range");
    if (given.mu_range) std::tie(r.mu_lo, r.mu_hi) = range_of(*given.mu_range, "--mu-range");
    if (given.thickness_range) std::tie(r.thickness_lo, r.thickness_hi) = range_of(*given.thickness_range, "--thickness-range");
    if (given.thickness_step) apply_thickness_step(*given.thickness_step, given.size, r);
    if (given.mu_floor) r.mu_floor = *given.mu_floor;
    if (given.texels) r.texels = parse_texels(*given.texels);
    if (given.axes) r.axes = *given.axes;
    if (given.flip) r.flip = *given.flip;
    if (given.samples && given.tolerance) throw Error("--tolerance excludes --samples");
    if (given.samples || given.tolerance || given.method || given.max_samples) {
        const LutRequest defaults;
        const MethodChoice choice =
            choose_method(given.method.value_or("auto"), given.samples.value_or(double(defaults.samples)),
                          given.tolerance.value_or(0.0),
                          given.max_samples.value_or(double(defaults.tolerance.max_samples)));
        r.samples = choice.samples;
        r.method = choice.method;
        r.tolerance = choice.tolerance;
    }
    if (given.precision) r.precision = precision_of(*given.precision);
    return setup;
}

}  // namespace brdfbake
