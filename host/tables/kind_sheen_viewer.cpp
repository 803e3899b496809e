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
// integrated by 32-point Gauss-Legendre rules on pieces split at every kink of the clamped
// visibility (sheen_albedo); the error channel is the difference from the 16-point rules on the
// same pieces. The viewer's runtime generator (ibl_filtering.frag, LUT()) sums the same integrand over Charlie-distributed
// half vectors but divides by a uniform-hemisphere pdf (its factor 4 * 2 pi / N), so what it
// renders into its runtime texture is not this integral; docs/models.md says so.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <thread>

#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "tables/lut_common.h"

namespace brdfbake {
namespace tables {
namespace {

constexpr double kPi = 3.14159265358979323846;
/// Gauss-Legendre points per smooth piece, in u and in phi: the value's rule and the error's.
constexpr int kFine = 32, kCoarse = 16;

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

/// The NdotL levels where the clamped visibility's derivatives jump: 0 (the horizon, where the
/// integrand meets 0 with a slope), each NdotL where V crosses 1 (found by a scan and bisection:
/// V_Ashikhmin crosses once, V_Sheen's fitted Lambda may cross more often), and for V_Sheen 0.5,
/// where lambda_sheen switches branches (its second derivative jumps there).
std::vector<double> kink_levels(bool charlie, double alpha, double mu) {
    std::vector<double> levels = {0.0};
    if (charlie) levels.push_back(0.5);
    auto above = [&](double nl) { return visibility(charlie, alpha, mu, nl) >= 1.0; };
    const int scan = 256;
    for (int k = 0; k < scan; ++k) {
        double a = (k + 1e-9) / scan, b = (k + 1.0) / scan;
        const bool at_a = above(a);
        if (at_a == above(b)) continue;
        for (int it = 0; it < 60; ++it) {
            const double m = 0.5 * (a + b);
            (above(m) == at_a ? a : b) = m;
        }
        levels.push_back(0.5 * (a + b));
    }
    return levels;
}

/// The two rules' estimates of one texel, and the integrand evaluations they took.
struct Estimate {
    double fine = 0.0, coarse = 0.0;
    std::uint64_t nodes = 0;
};

/// E(mu, alpha) by product Gauss-Legendre rules, split where the integrand's derivatives jump so
/// that every piece is smooth and the difference of the kFine and kCoarse rules bounds the error
/// (issue 37: the former 128^2 vs 64^2 rules over the whole square understated it at grazing mu).
/// Half vectors H = (s cos phi, s sin phi, c) by the Charlie inverse CDF u (s = u^exponent), where
/// f NdotL / pdf = 4 V NdotL VdotH / NdotH; with V = (sin_o, 0, mu), NdotL = 2 c (sin_o s cos phi
/// + mu c) - mu falls with phi in [0, pi], so a row (fixed theta_h) splits phi where NdotL meets
/// each kink level L (kink_levels). A row's NdotL spans [cos(2 theta_h + theta_o), cos(2 theta_h -
/// theta_o)] (the reflection of V about H in the plane of incidence): a level enters or leaves the
/// rows at theta_h = (theta_o +- acos L)/2 and (acos L - theta_o)/2, where the rows' integral has a
/// (3/2)-power kink; the outer integral splits there. It runs over y = sqrt(1 - u) (du = 2 y dy):
/// in u the rows have a branch point at u = 1 (c = sqrt(1 - u^(2 exponent))), next to the pieces
/// that grazing views end there, and the lobe of a small alpha (within sqrt(alpha) of theta_h =
/// pi/2) spans y in [0, ~1]. On each outer piece y = lo + width (3 t^2 - 2 t^3): the (3/2)-power
/// kinks at its ends, and the rows' start a + b u^(2 exponent) at u = 0, are smoother in t.
Estimate sheen_albedo(const Rule& fine, const Rule& coarse, bool charlie, double mu, double alpha) {
    const double exponent = alpha / (2.0 * alpha + 1.0), sin_o = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    const double theta_o = std::acos(mu);
    const std::vector<double> levels = kink_levels(charlie, alpha, mu);
    std::vector<double> cuts_y = {0.0, 1.0};
    for (double level : levels) {
        const double a = std::acos(level);
        for (double th : {0.5 * (theta_o + a), 0.5 * (theta_o - a), 0.5 * (a - theta_o)})
            if (th > 0.0 && th < 0.5 * kPi) cuts_y.push_back(std::sqrt(-std::expm1(std::log(std::sin(th)) / exponent)));
    }
    std::sort(cuts_y.begin(), cuts_y.end());
    Estimate e;
    auto row = [&](const Rule& rule, double s, double c) {  // the mean over phi / pi in [0, 1]
        if (c <= 0.0) return 0.0;
        const double a = sin_o * s, b = mu * c;
        std::vector<double> cuts = {0.0, kPi};
        for (double level : levels) {
            const double x = a > 0.0 ? ((level + mu) / (2.0 * c) - b) / a : 2.0;
            if (std::abs(x) < 1.0) cuts.push_back(std::acos(x));
        }
        std::sort(cuts.begin(), cuts.end());
        double sum = 0.0;
        for (size_t p = 0; p + 1 < cuts.size(); ++p) {
            const double lo = cuts[p], width = cuts[p + 1] - lo;
            if (width <= 0.0 || 2.0 * c * (a * std::cos(lo + 0.5 * width) + b) - mu <= 0.0) continue;
            e.nodes += rule.x.size();
            for (size_t j = 0; j < rule.x.size(); ++j) {
                const double vh = a * std::cos(lo + width * rule.x[j]) + b, nl = 2.0 * vh * c - mu;
                if (nl > 0.0) sum += rule.w[j] * width * visibility(charlie, alpha, mu, nl) * nl * 4.0 * vh / c;
            }
        }
        return sum / kPi;
    };
    auto piece = [&](const Rule& rule, double lo, double width) {  // over y in [lo, lo + width]
        double sum = 0.0;
        for (size_t i = 0; i < rule.x.size(); ++i) {
            const double t = rule.x[i], dy = 6.0 * t * (1.0 - t) * width;
            const double y = lo + width * t * t * (3.0 - 2.0 * t), log_u = std::log1p(-y * y);
            const double s = std::exp(exponent * log_u), c = std::sqrt(-std::expm1(2.0 * exponent * log_u));
            sum += rule.w[i] * dy * 2.0 * y * row(rule, s, c);
        }
        return sum;
    };
    for (size_t p = 0; p + 1 < cuts_y.size(); ++p) {
        const double lo = cuts_y[p], width = cuts_y[p + 1] - lo;
        if (width <= 0.0) continue;
        e.fine += piece(fine, lo, width);
        e.coarse += piece(coarse, lo, width);
    }
    return e;  // the pdf of (u, phi/pi) is uniform: the integral over the unit square is the mean
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
    const Rule fine = gauss_legendre(kFine), coarse = gauss_legendre(kCoarse);
    const size_t n = g.cells.size();
    t.channels = {"E"};
    t.values.assign(1, std::vector<double>(n));
    t.error.assign(n, 0.0);
    std::vector<char> saturated(n, 0);
    std::vector<std::uint64_t> nodes(n, 0);
    auto work = [&](size_t begin, size_t step) {
        for (size_t c = begin; c < n; c += step) {
            const double alpha = std::max(g.cells[c].params[BB_SHEEN_ALPHA], 1e-12);  // the viewer's r >= 1e-6
            const double mu = g.cells[c].mu;
            const Estimate est = sheen_albedo(fine, coarse, charlie, mu, alpha);
            const double e = est.fine;
            t.error[c] = std::abs(est.fine - est.coarse);
            nodes[c] = est.nodes;
            saturated[c] = e > 1.0;
            t.values[0][c] = std::min(e, 1.0);
        }
    };
    const size_t threads = std::max(1u, std::min(16u, std::thread::hardware_concurrency()));
    std::vector<std::thread> pool;
    for (size_t k = 1; k < threads; ++k) pool.emplace_back(work, k, threads);
    work(0, threads);
    for (auto& th : pool) th.join();
    describe(t, r, m, f.canonical,
             "quadrature (host, " + std::to_string(kFine) + "- and " + std::to_string(kCoarse) +
                 "-point Gauss-Legendre in the Charlie inverse CDF, split at the clamp's kinks)",
             n > 0 ? *std::max_element(nodes.begin(), nodes.end()) : 0, g.clamped);
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
    // Computed on the host: the plan counts the layout's samples (20480 a texel) as samples; at 2.2
    // engine albedo samples each they make the 15 s of CPU that the 128 x 128 lut_sheen_E takes
    // (V_Sheen's fitted Lambda is the costly case; lut_charlie takes 1 s), measured on this
    // project's 2-core machine.
    k.sample_cost = 2.2;
    k.validate = validate_viewer;
    return k;
}

}  // namespace tables
}  // namespace brdfbake
