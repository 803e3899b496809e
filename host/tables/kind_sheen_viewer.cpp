// The glTF Sample Viewer's sheen LUTs (KhronosGroup/glTF-Sample-Viewer): lut_charlie.png, read
// in ibl.glsl as texture(u_CharlieLUT, vec2(NdotV, sheenRoughness)).b, the sheen term of its
// image-based lighting, and lut_sheen_E.png, read in material_info.glsl as
// texture(u_SheenELUT, vec2(NdotV, sheenRoughness)).r, the sheen directional albedo of
// KHR_materials_sheen's albedo scaling. Both are E(mu_o, r) = integral of f NdotL over the
// hemisphere of the viewer's sheen BRDF f = D_Charlie(r, NdotH) V with its visibility clamped
// to [0, 1] as its shaders clamp it: lut_charlie with V_Ashikhmin (ibl_filtering.frag, after
// Neubelt and Pettineo 2013), lut_sheen_E with V_Sheen, the Estevez-Kulla fitted Lambda of
// brdf.glsl ("Production Friendly Microfacet Sheen BRDF", SIGGRAPH 2017). alpha = r^2 in
// D_Charlie = (2 + 1/alpha) sin^(1/alpha)(theta_h) / (2 pi) (Estevez-Kulla eq. 2), r floored at
// 1e-6 as the viewer floors it. A texel stores min(E, 1): the viewer's LUTs are unsigned
// normalized textures; the table counts the texels the bound cut ("saturated" attribute).
//
// The integral is computed here on the host, deterministically: half-vector directions drawn by
// the inverse CDF of D_Charlie cos(theta_h) (sin(theta_h) = u^(alpha/(2 alpha + 1)), the viewer's
// own Charlie() mapping), so that f NdotL / pdf(L) = 4 V NdotL VdotH / NdotH is bounded, and
// integrated with a 128 x 128 Gauss-Legendre rule over (u, phi) (phi over [0, pi], the lobe is
// mirror symmetric); the error channel is its difference from the 64 x 64 rule. The viewer's
// runtime generator (ibl_filtering.frag, LUT()) sums the same integrand over Charlie-distributed
// half vectors but divides by a uniform-hemisphere pdf (its factor 4 * 2 pi / N), so what it
// renders into its runtime texture is not this integral; docs/models.md says so.
#include <algorithm>
#include <cmath>
#include <thread>

#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "tables/lut_common.h"

namespace brdfbake {
namespace tables {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The Estevez-Kulla fit of the sheen Lambda as the viewer's brdf.glsl writes it (lambdaSheen).
double lambda_fit(double x, double alpha) {
    const double t = (1.0 - alpha) * (1.0 - alpha);
    auto mix = [t](double a, double b) { return a + (b - a) * t; };
    return mix(21.5473, 25.3245) / (1.0 + mix(3.82987, 3.32435) * std::pow(x, mix(0.19823, 0.16801))) +
           mix(-1.97760, -1.27393) * x + mix(-4.32054, -4.85967);
}
double lambda_sheen(double cos_theta, double alpha) {
    return std::abs(cos_theta) < 0.5 ? std::exp(lambda_fit(cos_theta, alpha))
                                     : std::exp(2.0 * lambda_fit(0.5, alpha) - lambda_fit(1.0 - cos_theta, alpha));
}

/// The viewer's visibility, clamped to [0, 1] as V_Sheen and V_Ashikhmin clamp it.
double visibility(bool charlie, double alpha, double nv, double nl) {
    const double v = charlie ? 1.0 / ((1.0 + lambda_sheen(nv, alpha) + lambda_sheen(nl, alpha)) * (4.0 * nv * nl))
                             : 1.0 / (4.0 * (nl + nv - nl * nv));
    return std::min(std::max(v, 0.0), 1.0);
}

struct Rule {
    std::vector<double> x, w;  // nodes and weights on [0, 1]
};

/// The n-point Gauss-Legendre rule on [0, 1] (Newton on the Legendre recurrence).
Rule gauss_legendre(int n) {
    Rule r;
    for (int i = 0; i < n; ++i) {
        double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 0.0;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1.0, p1 = 0.0;
            for (int k = 1; k <= n; ++k) {
                const double p2 = p1;
                p1 = p0;
                p0 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p2) / k;
            }
            dp = n * (z * p0 - p1) / (z * z - 1.0);
            const double dz = p0 / dp;
            z -= dz;
            if (std::abs(dz) < 1e-16) break;
        }
        r.x.push_back(0.5 * (1.0 - z));
        r.w.push_back(1.0 / ((1.0 - z * z) * dp * dp));
    }
    return r;
}

/// E(mu, alpha) with the rule's nodes in u (the Charlie inverse CDF) and phi in [0, pi].
double sheen_albedo(const Rule& rule, bool charlie, double mu, double alpha) {
    const double exponent = alpha / (2.0 * alpha + 1.0), sin_o = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    double sum = 0.0;
    for (size_t i = 0; i < rule.x.size(); ++i) {
        const double s = std::pow(rule.x[i], exponent), c = std::sqrt(std::max(0.0, 1.0 - s * s));
        if (c <= 0.0) continue;
        double inner = 0.0;
        for (size_t j = 0; j < rule.x.size(); ++j) {
            const double phi = kPi * rule.x[j];
            const double vh = sin_o * s * std::cos(phi) + mu * c;  // V = (sin_o, 0, mu), H = (s cos, s sin, c)
            const double nl = 2.0 * vh * c - mu;
            if (vh <= 0.0 || nl <= 0.0) continue;
            inner += rule.w[j] * visibility(charlie, alpha, mu, nl) * nl * 4.0 * vh / c;
        }
        sum += rule.w[i] * inner;
    }
    return sum;  // the pdf of (u, phi/pi) is uniform: the sum over the unit square is the mean
}

void validate_viewer(const LutRequest& r, const ModelConfig& m, const FresnelConfig&) {
    if (m.id != BB_MODEL_SHEEN)
        throw Error("the sheen-viewer table is of the sheen model: --model sheen:visibility=charlie (lut_sheen_E) or "
                    "sheen:visibility=ashikhmin (lut_charlie), not '" + m.name + "'");
    if (r.alpha_hi > 1.0) throw Error("--alpha-range of a sheen-viewer table must lie within [0, 1]");
}

Table compute_viewer(Engine&, const LutRequest& r, const ModelConfig& m, const FresnelConfig& f) {
    const bool charlie = m.params[BB_SHEEN_VISIBILITY] == BB_SHEEN_V_CHARLIE;
    MuAlphaGrid g = mu_alpha_grid(r, m);
    Table& t = g.table;
    t.quantity = std::string("the glTF Sample Viewer's ") + (charlie ? "lut_sheen_E" : "lut_charlie") +
                 ": min(1, sheen directional albedo E(mu_o, sheenRoughness)) of D_Charlie with the viewer's " +
                 (charlie ? "V_Sheen (Estevez-Kulla fitted Lambda)" : "V_Ashikhmin") + " clamped to [0, 1]";
    const Rule fine = gauss_legendre(128), coarse = gauss_legendre(64);
    const size_t n = g.cells.size();
    t.channels = {"E"};
    t.values.assign(1, std::vector<double>(n));
    t.error.assign(n, 0.0);
    std::vector<char> saturated(n, 0);
    auto work = [&](size_t begin, size_t step) {
        for (size_t c = begin; c < n; c += step) {
            const double alpha = std::max(g.cells[c].params[BB_SHEEN_ALPHA], 1e-12);  // the viewer's r >= 1e-6
            const double mu = g.cells[c].mu;
            const double e = sheen_albedo(fine, charlie, mu, alpha);
            t.error[c] = std::abs(e - sheen_albedo(coarse, charlie, mu, alpha));
            saturated[c] = e > 1.0;
            t.values[0][c] = std::min(e, 1.0);
        }
    };
    const size_t threads = std::max(1u, std::min(16u, std::thread::hardware_concurrency()));
    std::vector<std::thread> pool;
    for (size_t k = 1; k < threads; ++k) pool.emplace_back(work, k, threads);
    work(0, threads);
    for (auto& th : pool) th.join();
    describe(t, r, m, f.canonical, "quadrature (host, 128 x 128 Gauss-Legendre in the Charlie inverse CDF)",
             128 * 128 + 64 * 64, g.clamped);
    t.attributes["visibility"] = charlie ? "charlie" : "ashikhmin";
    t.attributes["saturated"] = std::to_string(std::count(saturated.begin(), saturated.end(), 1)) +
                                " texels with E > 1 stored as 1";
    return std::move(g.table);
}

}  // namespace

TableKind sheen_viewer_kind() {
    TableKind k(TableKindId::SheenViewer, "sheen-viewer",
                "the glTF Sample Viewer's sheen LUTs (lut_charlie, lut_sheen_E): min(1, E(mu_o, sheenRoughness)) "
                "of its Charlie sheen with clamped visibility (2D)",
                [](const LutRequest&) { return std::vector<std::string>{}; }, compute_viewer);
    k.plan_fresnel = "none (the sheen lobe has no Fresnel term)";
    k.required_model = "sheen";
    k.lobe_requirement = "the sheen-viewer table needs a sheen lobe (model sheen, KHR_materials_sheen)";
    // Computed on the host: the plan counts its quadrature nodes (the layout's samples, 20480 a
    // texel) as samples; a node costs about 1.5 engine albedo samples (10.5 s of CPU for the
    // 128 x 128 table, measured on this project's 2-core machine).
    k.sample_cost = 1.5;
    k.validate = validate_viewer;
    return k;
}

}  // namespace tables
}  // namespace brdfbake
