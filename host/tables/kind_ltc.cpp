// Linearly transformed cosines per texel (Heitz, Dupuy, Hill and Neubelt 2016, "Real-Time
// Polygonal-Light Shading with Linearly Transformed Cosines", [HDHN16]): the tables real-time
// renderers light polygonal area lights with. Per texel (mu, alpha): the matrix M whose
// transformed clamped cosine D best matches the normalised lobe p = f cos(theta_i) / E (fitted by
// host/fit/ltc_fit.h on the device), the magnitude E (the engine's albedo integration, F = 1, with
// its error), the fresnel channel (integral of f cos (1 - wo.h)^5, the Schlick split's second
// term as Heitz and Hill's fitLTC tabulates it, by the same integration as the magnitude, with
// its error) and the distance integral over the upper hemisphere of |p - D| with its own error
// channel distance_error. docs/architecture.md, "The fitting layer".
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numeric>
#include <sstream>

#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "brdfbake/progress.h"
#include "fit/ltc_fit.h"
#include "tables/lut_common.h"
#include "tables/sweep.h"

namespace brdfbake {
namespace tables {
namespace {

/// The alpha at which a texel below it of a model with a mirror limit is fitted (the mirror's LTC
/// is a delta, which no finite M reaches): the models' own floor BB_ALPHA_MIN (microfacet.h).
/// Measured (benchmarks/results/ltc_published.md, branch ltc2): with the floor at 1e-3, three.js's
/// texel a = 1 (alpha 2.5e-4, cos theta 0.999) was fitted at 1e-3 and lay 1.195 from its true lobe;
/// at 1e-4 it fits to 0.00066 (three.js 0.00058), and near-normal a = 0 texels to 0.00005-0.0017.
constexpr double kLtcAlphaFloor = 1e-4;

std::vector<std::string> ltc_programs(const LutRequest& r) {
    return {"albedo|" + r.model + "|none", "albedo|" + r.model + "|schlick", "ltc|" + r.model};
}

/// How a table stores each texel's M with its magnitude E and fresnel term B (the value channels
/// before distance and distance_error), and the M that the stored values denote (the distance
/// reported is that M's).
struct LtcPacking {
    std::string name;  // LutRequest::packing
    std::string quantity;
    std::vector<std::string> channels;
    std::function<std::vector<double>(const fit::LtcMatrix&, double e, double b)> values;
    std::function<fit::LtcMatrix(const fit::LtcMatrix&)> as_written;
};

/// three.js's ltc_1 = M^-1 / M^-1_11 as (M^-1_00, M^-1_20, M^-1_02, M^-1_22), float32: its shaders
/// build mInv = mat3(vec3(t1.x, 0, t1.y), vec3(0, 1, 0), vec3(t1.z, 0, t1.w)) (GLSL columns) in
/// RE_Direct_RectArea_Physical (src/renderers/shaders/ShaderChunk/lights_physical_pars_fragment.glsl.js)
/// from texture2D(ltc_1, LTC_Uv(...)); docs/ltc_presets.md. With D = m00 m22 - m02 m20,
/// M^-1 = [[m22, 0, -m02], [0, D/m11, 0], [-m20, 0, m00]] / D.
std::array<double, 4> three_ltc1(const fit::LtcMatrix& m) {
    const double d = m.m00 * m.m22 - m.m02 * m.m20;
    return {double(float(m.m11 * m.m22 / d)), double(float(-m.m11 * m.m20 / d)), double(float(-m.m11 * m.m02 / d)),
            double(float(m.m11 * m.m00 / d))};
}

/// The M (up to scale, which D ignores) of a stored ltc_1 t: the inverse of [[t0, 0, t2], [0, 1, 0], [t1, 0, t3]].
fit::LtcMatrix from_three_ltc1(const std::array<double, 4>& t) {
    const double d = t[0] * t[3] - t[2] * t[1];
    fit::LtcMatrix m;
    m.m00 = t[3] / d;
    m.m02 = -t[2] / d;
    m.m11 = 1.0;
    m.m20 = -t[1] / d;
    m.m22 = t[0] / d;
    return m;
}

/// The M that a stored ltc_1 (three.js's, EEVEE's ltc_mat_ggx) denotes: M rounded through float32 ltc_1.
fit::LtcMatrix as_stored_ltc1(const fit::LtcMatrix& m) { return from_three_ltc1(three_ltc1(m)); }

/// v rounded to the nearest IEEE 754 binary16 value (ties to even), clamped to its largest finite
/// magnitude 65504 as HDRP's LTC loader clamped its tables (LTCAreaLight.cs LoadLUT's clampValue;
/// pull request Unity-Technologies/ScriptableRenderPipeline#5839 "Fix a source of Inf").
double as_half(double v) {
    constexpr double kHalfMax = 65504.0;
    v = std::clamp(v, -kHalfMax, kHalfMax);
    int e = 0;
    std::frexp(v, &e);                                   // |v| = f 2^e, f in [0.5, 1)
    const double ulp = std::ldexp(1.0, std::max(e, -13) - 11);  // 11 significant bits; subnormals below 2^-14
    return std::nearbyint(v / ulp) * ulp + 0.0;  // + 0.0: no negative zero
}

/// Unity HDRP's s_LtcMatrixData_BRDF_GGX texel (R, G, B, A) = (M^-1_00, M^-1_20, M^-1_11, M^-1_02) / M^-1_22
/// as half floats: its generator's ExportToCSharp (Editor/Material/LTCAreaLight/LTCTableGenerator.cs
/// divides invM by invM.m22, Unity's Matrix mRC being row R, column C; LTC.cs) read by
/// SampleLtcMatrix (LTCAreaLight.hlsl) into invM._m00_m02_m11_m20 with invM._m22 = 1, "the transposed
/// M^(-1)". With D = m00 m22 - m02 m20 and M^-1_22 = m00 / D: (m22, -m20, D / m11, -m02) / m00.
std::array<double, 4> unity_hdrp_texel(const fit::LtcMatrix& m) {
    const double d = m.m00 * m.m22 - m.m02 * m.m20;
    return {as_half(m.m22 / m.m00), as_half(-m.m20 / m.m00), as_half(d / (m.m11 * m.m00)), as_half(-m.m02 / m.m00)};
}

/// The M (up to scale) of a stored texel u: the inverse of [[u0, 0, u3], [0, u2, 0], [u1, 0, 1]].
fit::LtcMatrix from_unity_hdrp_texel(const std::array<double, 4>& u) {
    const double d = u[0] - u[3] * u[1];
    fit::LtcMatrix m;
    m.m00 = 1.0 / d;
    m.m02 = -u[3] / d;
    m.m11 = 1.0 / u[2];
    m.m20 = -u[1] / d;
    m.m22 = u[0] / d;
    return m;
}

const std::vector<LtcPacking>& ltc_packings() {
    static const std::vector<LtcPacking> packings = {
        {"",
         "M = [[m00, 0, m02], [0, m11, 0], [m20, 0, m22]]",
         {"m00", "m02", "m11", "m20", "m22", "magnitude", "fresnel"},
         [](const fit::LtcMatrix& m, double e, double b) { return std::vector<double>{m.m00, m.m02, m.m11, m.m20, m.m22, e, b}; },
         {}},  // the entries themselves, float32: the fitter's default
        // three.js's RectAreaLightTexturesLib (examples/jsm/lights): LTC_FLOAT_1 -> ltc_1 as above,
        // LTC_FLOAT_2 -> ltc_2 = (E, B, 0, sphere term), read as specularColor * t2.x +
        // (1 - specularColor) * t2.y; the rect-light shader reads no ltc_2.w: 0 here.
        {"three",
         "three.js's ltc_1 = M^-1 / M^-1_11 as (M^-1_00, M^-1_20, M^-1_02, M^-1_22) and ltc_2 = (magnitude, "
         "fresnel, 0, 0)",
         {"ltc_1.R", "ltc_1.G", "ltc_1.B", "ltc_1.A", "ltc_2.R", "ltc_2.G", "ltc_2.B", "ltc_2.A"},
         [](const fit::LtcMatrix& m, double e, double b) {
             const std::array<double, 4> t = three_ltc1(m);
             return std::vector<double>{t[0], t[1], t[2], t[3], e, b, 0.0, 0.0};
         },
         as_stored_ltc1},
        // Blender EEVEE's eevee_lut.cc: ltc_mat_ggx[t][a][0..3] and ltc_mag_ggx[t][a][0..1] hold
        // three.js's ltc_1 and (ltc_2.R, ltc_2.G), the same numbers printed to 6 decimals; read by
        // ltc_matrix (eevee_ltc_lib.glsl) as three.js reads ltc_1 (docs/ltc_presets.md, "Blender EEVEE").
        {"eevee",
         "Blender EEVEE's ltc_mat_ggx = M^-1 / M^-1_11 as (M^-1_00, M^-1_20, M^-1_02, M^-1_22) (three.js's ltc_1) "
         "and ltc_mag_ggx = (magnitude, fresnel)",
         {"ltc_mat_ggx.0", "ltc_mat_ggx.1", "ltc_mat_ggx.2", "ltc_mat_ggx.3", "ltc_mag_ggx.0", "ltc_mag_ggx.1"},
         [](const fit::LtcMatrix& m, double e, double b) {
             const std::array<double, 4> t = three_ltc1(m);
             return std::vector<double>{t[0], t[1], t[2], t[3], e, b};
         },
         as_stored_ltc1},
        // Unity HDRP's Generated/LtcData.BRDF_GGX.cs: the half floats above; HDRP takes the
        // magnitude and Fresnel terms from its FGD table, so they are channels of the table only.
        {"unity-hdrp",
         "Unity HDRP's s_LtcMatrixData_BRDF_GGX = M^-1 / M^-1_22 as (M^-1_00, M^-1_20, M^-1_11, M^-1_02), half "
         "floats clamped to 65504; magnitude and fresnel",
         {"s_LtcMatrixData_BRDF_GGX.0", "s_LtcMatrixData_BRDF_GGX.1", "s_LtcMatrixData_BRDF_GGX.2",
          "s_LtcMatrixData_BRDF_GGX.3", "magnitude", "fresnel"},
         [](const fit::LtcMatrix& m, double e, double b) {
             const std::array<double, 4> u = unity_hdrp_texel(m);
             return std::vector<double>{u[0], u[1], u[2], u[3], e, b};
         },
         [](const fit::LtcMatrix& m) { return from_unity_hdrp_texel(unity_hdrp_texel(m)); }},
        // HDRP from its 2021 LTC generator to mid-2023: the whole M^-1 / M^-1_22 "columns first"
        // as doubles (double[64 * 64, 3 * 3], entry r + 3 c = M^-1_rc / M^-1_22), of which
        // LTCAreaLight.cs's LoadLUT uploads entries 0, 2, 4, 6, min(65504, (float)v), as half floats.
        {"unity-hdrp-2021",
         "Unity HDRP's s_LtcMatrixData_BRDF_GGX of 2021 to 2023 = M^-1 / M^-1_22 columns first (entry r + 3 c = "
         "M^-1_rc / M^-1_22), doubles; magnitude and fresnel",
         {"s_LtcMatrixData_BRDF_GGX.0", "s_LtcMatrixData_BRDF_GGX.1", "s_LtcMatrixData_BRDF_GGX.2",
          "s_LtcMatrixData_BRDF_GGX.3", "s_LtcMatrixData_BRDF_GGX.4", "s_LtcMatrixData_BRDF_GGX.5",
          "s_LtcMatrixData_BRDF_GGX.6", "s_LtcMatrixData_BRDF_GGX.7", "s_LtcMatrixData_BRDF_GGX.8", "magnitude",
          "fresnel"},
         [](const fit::LtcMatrix& m, double e, double b) {  // the half floats the GPU gets, as doubles
             const std::array<double, 4> u = unity_hdrp_texel(m);
             return std::vector<double>{u[0], 0.0, u[1], 0.0, u[2], 0.0, u[3], 0.0, 1.0, e, b};
         },
         [](const fit::LtcMatrix& m) { return from_unity_hdrp_texel(unity_hdrp_texel(m)); }},  // what the GPU holds
    };
    return packings;
}

const LtcPacking& ltc_packing(const std::string& name) {
    for (const LtcPacking& p : ltc_packings())
        if (p.name == name) return p;
    throw Error("the ltc table has no packing '" + name + "' (three, eevee, unity-hdrp, unity-hdrp-2021, or none for its own channels)");
}

void validate_ltc(const LutRequest& r, const ModelConfig& m, const FresnelConfig& f) {
    ltc_packing(r.packing);
    if (m.traits().delta)
        throw Error("the ltc table fits a lobe; '" + m.name + "' is a delta lobe, which no linearly transformed cosine fits");
    if (m.anisotropic)
        throw Error("the ltc table fits isotropic lobes (M symmetric in y); '" + m.canonical + "' is anisotropic");
    // A Lambert base kd/pi has an exact LTC of its own (M = I, magnitude kd), which the engines
    // light beside the lobe's; one LTC of the sum was never closer to it than that pair (8x8 GGX,
    // diffuse=0.3: worse beyond noise at 42 of 64 texels, up to 70x near normal at alpha 0.06, better at
    // none; docs/ltc_presets.md).
    if (m.traits().diffuse_key && m.params[BB_SMITH_SCATTERING] == BB_SCATTERING_SINGLE && m.params[BB_SMITH_DIFFUSE] > 0.0)
        throw Error("the ltc table fits one lobe; '" + m.canonical + "' adds a Lambert base kd/pi, whose LTC is exact "
                    "(M = I, magnitude kd): fit the model without diffuse= and light kd with the clamped cosine beside it");
    if (f.kind != BB_FRESNEL_NONE)
        throw Error("the ltc table holds the lobe with F = 1 (its fresnel channel is the Schlick split's term); drop --fresnel");
}

/// The fit's rows, rough to smooth, with the cells of each and their albedo E (the magnitude
/// channel, where the texel is fitted at its own alpha); `order[k]` is the table row of fit row k.
std::vector<std::vector<fit::LtcCell>> fit_rows(const MuAlphaGrid& g, const ModelConfig& m, const AlbedoResult& e,
                                                std::vector<size_t>& order) {
    const size_t w = g.table.x.parameter.size(), h = g.table.y.parameter.size();
    order.resize(h);
    std::iota(order.begin(), order.end(), 0);
    const std::vector<double>& alpha = g.table.y.parameter;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return alpha[a] > alpha[b]; });
    const std::vector<int> slots = roughness_slots(m);
    std::vector<std::vector<fit::LtcCell>> rows;
    for (size_t j : order) {
        rows.emplace_back();
        for (size_t i = 0; i < w; ++i) {
            const AlbedoCell& c = g.cells[j * w + i];
            ParamBlock p = c.params;
            bool floored = false;
            if (has_mirror_limit(m))
                for (int s : slots) {
                    floored = floored || p[s] < kLtcAlphaFloor;
                    p[s] = std::max(p[s], kLtcAlphaFloor);
                }
            rows.back().push_back({c.mu, p, floored ? 0.0 : e.values[j * w + i].value});
        }
    }
    return rows;
}

/// The table's channels: the packing's, then the fit's distance and its error.
std::vector<std::string> ltc_channels(const LutRequest& r) {
    std::vector<std::string> c = ltc_packing(r.packing).channels;
    c.insert(c.end(), {"distance", "distance_error"});
    return c;
}

Table compute_ltc(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig& f) {
    MuAlphaGrid g = mu_alpha_grid(r, m);
    Table& t = g.table;
    const LtcPacking& packing = ltc_packing(r.packing);
    t.quantity = "linearly transformed cosine fits (Heitz et al. 2016) of the lobe f cos(theta_i) / E, "
                 "viewer at (sin theta_o, 0, cos theta_o): " + packing.quantity;
    // E and the Schlick split's term B = integral of f cos (1 - wo.h)^5 (Schlick with f0 = 0), each
    // to the tolerance: the table's error is the larger of their errors.
    const AlbedoResult albedo = integrate(engine, r, m, f, g.cells);
    // A model without a Fresnel term (oren-nayar, the Phong lobes) has none to split: B = E, so
    // that the engines' f0 E + (1 - f0) B gives its lobe's E for every f0.
    const AlbedoResult fresnel =
        m.uses_fresnel ? integrate(engine, r, m, resolve_fresnel("schlick:f0=0"), g.cells) : albedo;
    std::vector<size_t> order;
    const std::vector<std::vector<fit::LtcCell>> rows = fit_rows(g, m, albedo, order);
    fit::LtcFitOptions options;
    options.precision = r.precision;
    options.as_written = packing.as_written;
    std::vector<std::vector<fit::LtcFit>> fits;
    {
        ProgressStage stage("LTC fit of " + m.canonical, rows.size(), "rows", "fitted");
        fits = fit::fit_ltc_rows(engine, m, rows, options, [&](size_t k) { stage.update(k + 1); });
    }
    const size_t w = t.x.parameter.size(), n = g.cells.size();
    t.channels = ltc_channels(r);
    t.values.assign(t.channels.size(), std::vector<double>(n));
    t.error.assign(n, 0.0);
    std::vector<double> distance, distance_error;
    for (size_t k = 0; k < rows.size(); ++k)
        for (size_t i = 0; i < w; ++i) {
            const size_t c = order[k] * w + i;
            const fit::LtcFit& ft = fits[k][i];
            std::vector<double> v = packing.values(ft.m, albedo.values[c].value, fresnel.values[c].value);
            v.insert(v.end(), {ft.distance, ft.distance_error});
            for (size_t ch = 0; ch < t.channels.size(); ++ch) t.values[ch][c] = v[ch];
            t.error[c] = std::max(albedo.values[c].error, fresnel.values[c].error);
            distance.push_back(ft.distance);
            distance_error.push_back(ft.distance_error);
        }
    describe(t, r, m, f.canonical, albedo.method, albedo.samples_per_cell, g.clamped);
    t.attributes["distance"] = "integral over the upper hemisphere of |f cos / E - D|: " + min_median_max_text(distance);
    t.attributes["distance_error"] =
        std::to_string(int(options.distance_sigmas)) + " standard errors of the mean over " +
        std::to_string(options.distance_grids) + " independent jittered grids of " + std::to_string(options.distance_side) +
        "^2 points (lobe- and LTC-sampled), for the M that the stored float32 values denote: " + min_median_max_text(distance_error);
    t.attributes["error_channel"] = "the larger of the magnitude's and the fresnel channel's integration errors "
                                    "(--samples, --method, --tolerance); the distance's: the distance_error channel";
    auto short_text = [](double v) {
        std::ostringstream o;
        o << v;
        return o.str();
    };
    t.attributes["ltc_fit"] = "Nelder-Mead in (theta, ln a, b, ln c), M = R_y(theta) [[a,0,b],[0,c,0],[0,0,1]], on " +
                              std::to_string(options.fit_side) + "x" + std::to_string(options.fit_side) +
                              " sampler points per texel (u1 graded towards the lobe's tail, power " +
                              std::to_string(options.fit_grade) + "), steps relative to the lobe's width, rows from rough "
                              "to smooth, each started from the row before; then polished on " +
                              std::to_string(options.refine_side) + "x" + std::to_string(options.refine_side) +
                              " points; a row whose narrowest lobe is under " + short_text(options.narrow_width) +
                              " wide in double, tolerances " + short_text(options.narrow_tolerance);
    if (!m.uses_fresnel)
        t.attributes["fresnel_channel"] = "the magnitude: " + m.name + " has no Fresnel term to split "
                                          "(f0 E + (1 - f0) B = E for every f0)";
    if (has_mirror_limit(m)) {
        std::ostringstream s;
        s << "texels below alpha = " << kLtcAlphaFloor << " are fitted at " << kLtcAlphaFloor;
        t.attributes["ltc_alpha_floor"] = s.str();
    }
    return std::move(g.table);
}

}  // namespace

TableKind ltc_kind() {
    TableKind k(TableKindId::Ltc, "ltc",
                "linearly transformed cosines (Heitz et al. 2016) per (mu, alpha): m00 m02 m11 m20 m22, magnitude E, "
                "fresnel, the fit's L1 distance and its error (2D)",
                ltc_programs, compute_ltc);
    k.plan_fresnel = "none (F = 1; the fresnel channel is the Schlick split's term)";
    k.validate = validate_ltc;
    // Measured: the 64x64 GGX table takes 9.3 s of CPU against the albedo table's 0.66 s at the
    // default 2^18 samples (benchmarks/results/ltc-table-amd-epyc-2c.md, branch ltcfix): about 14
    // albedo samples' cost per sample of its magnitude (the fit's and the distance's cost do not
    // scale with --samples). With the graded points and the 96^2 polish (branch ltc2) the fit costs
    // 4.1x the fit without them in the same minutes (34 s against 8.3 s of CPU, load 15-17): 57;
    // branch ltc3's 64^2 lazy polish takes 16.9 s of CPU where that took 31.9: 30; branch ltc4's host
    // nodes 0.68 of that in the same minutes: 21.
    k.sample_cost = 21.0;
    k.value_channels = ltc_channels;
    k.integrations = [](const LutRequest&) { return 2; };
    return k;
}

}  // namespace tables
}  // namespace brdfbake
