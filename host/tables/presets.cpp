// The presets: for each engine, the settings that make `brdfbake lut` write a table that replaces
// one the engine ships. Each convention is read from the engine's public source (cited per entry
// and in the README's "Drop-in tables" section); where an engine's own table sits away from where
// its shader reads, the preset writes what the shader reads.
#include <limits>

#include "brdfbake/error.h"
#include "brdfbake/lut.h"

namespace brdfbake {
namespace {

/// What every preset shares: height-correlated GGX (each engine's visibility term is the
/// height-correlated Smith G2 of Heitz 2014, or an approximation of it), F = 1 or factored out,
/// a fixed sample count per texel.
LutRequest base(const LutRequest& r) {
    LutRequest p;
    p.kind = r.kind;
    p.estimator = r.estimator;
    p.model = "ggx:shadowing=correlated";
    p.alpha_map = "roughness";  // every engine indexes by perceptual roughness r, alpha = r^2
    p.alpha_lo = 0.0;
    p.alpha_hi = 1.0;
    p.samples = std::uint64_t(1) << 16;
    return p;
}

// glTF Sample Viewer (KhronosGroup/glTF-Sample-Viewer, source/Renderer/shaders/ibl.glsl): the
// split-sum LUT lut_ggx.png is read as texture(u_GGXLUT, vec2(NdotV, roughness)).rg, f_ab.x the
// scale A and f_ab.y the bias B; 16-bit PNG, WebGL upload without a flip (row 0 at t = 0).
void gltf(LutRequest& r) {
    r = base(r);
    r.width = r.height = 1024;
}

// Filament (google/filament, libs/ibl/src/CubemapIBL.cpp, CubemapIBL::DFG with multiscatter):
// R = sum of V Fc = B, G = sum of V = E = A + B, read as mix(dfg.xxx, dfg.yyy, f0)
// (shaders/src/surface_light_indirect.fs); x = NoV at texel centres, rows ordered from the
// roughest (row 0) down. cmgen computes row y at perceptual roughness (height - y + 0.5)/height,
// one texel above the centre (height - y - 0.5)/height that a sampler reads: the preset writes
// the centres.
void filament(LutRequest& r) {
    r = base(r);
    r.width = r.height = 128;
    r.flip = {"roughness"};
}

// three.js (mrdoob/three.js, src/renderers/shaders/DFGLUTData.js): a 16 x 16 RG16F DataTexture,
// (scale, bias) = (A, B), sampled at vec2(roughness, dotNV): x = roughness, y = NoV, texel
// centres, row 0 at NoV near 0.
void three(LutRequest& r) {
    r = base(r);
    r.width = r.height = 16;
    r.axes = {"roughness", "mu"};
}

// Blender Cycles (intern/cycles/app/cycles_precompute.cpp): table_ggx_E[y * 32 + x] with
// x = roughness r = i/31 (floored at 1e-4), y = mu = j/31 (floored at 1e-4), alpha = r^2, and
// table_ggx_Eavg[x] = integral of 2 mu E(mu) over mu in [0, 1]; read by lookup_table_read_2D,
// which interpolates between texels at i/(N - 1) (edges), at roughness sqrt(sqrt(alpha_x alpha_y))
// (intern/cycles/kernel/closure/bsdf_microfacet.h). The r = 0 column is Cycles' r = 1e-4
// (alpha = 1e-8): computed here as the mirror limit, E = 1, which Cycles' own values reach.
void cycles(LutRequest& r) {
    r = base(r);
    r.texels = Texels::Edge;
    r.mu_lo = 0.0;
    r.mu_hi = 1.0;
    r.mu_floor = 1e-4;
    if (r.kind == "eavg") {
        r.width = 32;
        r.height = 1;
    } else if (r.kind == "gen-schlick" || r.kind == "gen-schlick-ior") {
        // table_ggx_gen_schlick_s and table_ggx_gen_schlick_ior_s[(z * 16 + y) * 16 + x]: x and y
        // as above, z = i/15 on the kind's own z axis (cycles_z: Cycles' exponent or eta
        // parameterisation, clamped to [1e-4, 0.99]), read by lookup_table_read_3D.
        r.width = r.height = r.depth = 16;
        r.axes = {"roughness", "mu", "cycles_z"};
        // --estimator cycles: what Cycles' own tables hold, the albedo of the lobe whose G2 is the
        // masking term G1(wo) alone (its Monte-Carlo estimator averages w over the visible normals).
        if (r.estimator == "cycles") r.model = "ggx:shadowing=masking";
    } else if (r.kind == "dielectric" || r.kind == "dielectric-eavg") {
        // table_ggx_glass_E and table_ggx_glass_inv_E[(z * 16 + y) * 16 + x], table_ggx_glass_Eavg
        // and table_ggx_glass_inv_Eavg[z * 16 + x]: the single-scattering albedo R + T of a rough
        // GGX glass interface (Eavg: 2 integral of (R + T) mu dmu over mu) with the exact
        // dielectric Fresnel and Cycles' G2 = 1/(1 + Lambda_i + Lambda_o) for both lobes; x =
        // roughness i/15, y = mu j/15 (floored at 1e-4), z = k/15 with eta = (1 + z^2)/(1 - z^2)
        // (ior_from_F0(z^4)), z clamped to [1e-4, 0.99] (eta 1 to 99.5); "inv" is light from the
        // denser side, at 1/eta: brdfbake's *_inside channels. Read by microfacet_ggx_preserve_energy
        // at z = sqrt(|eta - 1|/(eta + 1)) with eta < 1 inverted onto the inv tables
        // (bsdf_microfacet.h). z = 0 (eta = 1, no interface) is E = 1: Cycles computes it at z =
        // 1e-4, where eta rounds to 1 in float, and treats |eta - 1| < 1e-4 as a smooth pass.
        r.model = "ggx:shadowing=correlated,transmission_shadowing=cycles";
        r.eta_map = "cycles";
        r.eta_lo = 1.0;
        r.eta_hi = std::numeric_limits<double>::infinity();  // z up to 1, computed at 0.99 (eta_axis)
        r.depth = 16;
        r.width = 16;
        if (r.kind == "dielectric-eavg") {
            r.height = 1;  // x = roughness, z = cycles_z: already Cycles' order
        } else {
            r.height = 16;
            r.axes = {"roughness", "mu", "cycles_z"};
        }
    } else {
        r.width = r.height = 32;
        r.axes = {"roughness", "mu"};
    }
    r.precision = Precision::Double;
    // Cycles prints 6 decimals: half a unit of the last is 5e-7. The glass tables are Monte Carlo
    // of 2^23 (E) and 2^26 (Eavg) samples a texel in Cycles, about 1e-4 of noise; 5e-7 is out of
    // the dielectric kind's reach at a few texels (67M samples each), 1e-6 takes about 4 minutes.
    // dielectric-eavg shares its tolerance out, a quarter to each of R and T: 4e-6 holds them to 1e-6.
    r.tolerance.tolerance = r.kind == "dielectric" ? 1e-6 : r.kind == "dielectric-eavg" ? 4e-6 : 5e-7;
    r.tolerance.auto_method = true;
}

// Unreal Engine (Engine/Shaders/Private/BRDF.ush, EnvBRDF): the split-sum texture PreIntegratedGF
// is read at float2(NoV, Roughness), .x the scale A and .y the bias B of
// SpecularColor * A + saturate(50 * SpecularColor.g) * B; 128 x 32 texels, centres.
void unreal(LutRequest& r) {
    r = base(r);
    r.width = 128;
    r.height = 32;
}

}  // namespace

const std::vector<LutPreset>& lut_presets() {
    static const std::vector<LutPreset> presets = {
        {"gltf", "glTF Sample Viewer", "lut_ggx.png", {"dfg"}, "png", false,
         "1024 x 1024, x = NdotV, y = roughness (row 0 at 0), texel centres, R = A, G = B, B = 0, 16-bit PNG", gltf},
        {"filament", "Filament", "dfg.inc (cmgen --ibl-dfg-multiscatter)", {"dfg-ms"}, "exr", true,
         "128 x 128, x = NoV, y = perceptual roughness from 1 (row 0) down, texel centres, R = B, G = E = A + B, "
         "half-float EXR",
         filament},
        {"three", "three.js", "src/renderers/shaders/DFGLUTData.js", {"dfg"}, "exr", true,
         "16 x 16, x = roughness, y = NoV, texel centres, R = A (scale), G = B (bias), half-float EXR (RG16F)", three},
        {"cycles", "Blender Cycles",
         "table_ggx_E, table_ggx_Eavg, table_ggx_gen_schlick_s, table_ggx_gen_schlick_ior_s, table_ggx_glass_E "
         "and table_ggx_glass_inv_E (dielectric: R + T and R_inside + T_inside), table_ggx_glass_Eavg and "
         "table_ggx_glass_inv_Eavg (dielectric-eavg: Eavg, Eavg_inside) (intern/cycles/scene/shader.tables)",
         {"albedo", "eavg", "gen-schlick", "gen-schlick-ior", "dielectric", "dielectric-eavg"}, "h", false,
         "32 x 32 (32 for eavg; 16 x 16 x 16 for gen-schlick, gen-schlick-ior and dielectric with z = cycles_z, "
         "16 x 16 for dielectric-eavg with z = cycles_z, the dielectric kinds with Cycles' transmission shadowing; "
         "gen-schlick kinds with --estimator cycles: Cycles' own estimator on ggx:shadowing=masking), "
         "x = roughness, y = mu, edge texels (i/(N - 1)), mu floored at 1e-4, double precision to 5e-7 (dielectric: 1e-6, dielectric-eavg: 4e-6), C header",
         cycles},
        {"unreal", "Unreal Engine", "PreIntegratedGF (EnvBRDF)", {"dfg"}, "png", false,
         "128 x 32, x = NoV, y = roughness, texel centres, R = A, G = B, 16-bit PNG", unreal},
    };
    return presets;
}

const LutPreset& lut_preset(const std::string& name) {
    std::string known;
    for (const LutPreset& p : lut_presets()) {
        if (p.name == name) return p;
        known += (known.empty() ? "" : ", ") + p.name;
    }
    throw Error("unknown preset '" + name + "'; known: " + known);
}

}  // namespace brdfbake
