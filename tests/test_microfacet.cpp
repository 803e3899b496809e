// Closed forms and normalisation identities of the shared microfacet math (host, double).
#include <catch2/catch.hpp>

#include <random>

#include "brdfbake/brdf/ggx.h"
#include "reference/reference.h"

namespace {

bb_vec3 v3(ref::Dir d) { return bb_v3(double(d.x), double(d.y), double(d.z)); }

// Integral of D(m) cos(theta_m) over the hemisphere, which must be 1 (projected area of the
// microsurface equals that of the macrosurface; Heitz 2014 eq. 4).
double projected_area(double ax, double ay) {
    return ref::integrate2(
        [&](double th, double ph) {
            return bb_ggx_d(v3(ref::dir(th, ph)), ax, ay) * std::cos(th) * std::sin(th);
        },
        0.0, M_PI / 2, 0.0, 2 * M_PI, 1e-11);
}

// The weak white furnace (Heitz 2014 eq. 6): integral of G1(wo) D(m) max(0, wo.m) / cos_o = 1.
double weak_furnace(double ax, double ay, double theta_o, double phi_o) {
    const ref::Dir wo = ref::dir(theta_o, phi_o);
    const double g1 = bb_ggx_g1(v3(wo), ax, ay);
    return ref::integrate_facing(
        [&](double th, double ph) {
            ref::Dir m = ref::dir(th, ph);
            return g1 * bb_ggx_d(v3(m), ax, ay) * double(ref::dot(wo, m)) / double(wo.z);
        },
        wo.z, phi_o);
}

}  // namespace

TEST_CASE("GGX D is normalised: integral of D cos(theta_m) = 1", "[microfacet][quick]") {
    for (double a : {0.05, 0.2, 0.5, 1.0}) {
        INFO("alpha = " << a);
        CHECK(projected_area(a, a) == Approx(1.0).margin(1e-7));
    }
    INFO("anisotropic 0.1 x 0.4");
    CHECK(projected_area(0.1, 0.4) == Approx(1.0).margin(1e-7));
}

TEST_CASE("GGX weak white furnace: integral of G1 D <wo,m> / cos_o = 1", "[microfacet][quick]") {
    for (double a : {0.1, 0.5, 1.0})
        for (double th : {0.0, 0.7, 1.3, 1.5}) {
            INFO("alpha = " << a << ", theta_o = " << th);
            CHECK(weak_furnace(a, a, th, 0.3) == Approx(1.0).margin(1e-6));
        }
    CHECK(weak_furnace(0.08, 0.5, 1.2, 0.9) == Approx(1.0).margin(1e-6));
}

TEST_CASE("GGX closed forms", "[microfacet][quick]") {
    // D at the normal is 1 / (pi alpha_x alpha_y).
    CHECK(bb_ggx_d(bb_v3(0, 0, 1), 0.1, 0.1) == Approx(1.0 / (M_PI * 0.01)).epsilon(1e-14));
    CHECK(bb_ggx_d(bb_v3(0, 0, 1), 0.2, 0.5) == Approx(1.0 / (M_PI * 0.1)).epsilon(1e-14));
    // Published value: Smith G1 for GGX, alpha = 0.1, theta = 0.98 pi/2 (issue 3).
    const double th = 0.98 * M_PI / 2;
    CHECK(bb_ggx_g1(bb_v3(std::sin(th), 0, std::cos(th)), 0.1, 0.1) == Approx(0.46130955).margin(5e-9));
    // G1 is exactly 1 at normal incidence and 0 at and below the horizon.
    CHECK(bb_ggx_g1(bb_v3(0, 0, 1), 0.7, 0.3) == 1.0);
    CHECK(bb_ggx_g1(bb_v3(1, 0, 0), 0.7, 0.3) == 0.0);
    CHECK(bb_ggx_g1(bb_v3(0.8, 0, -0.6), 0.7, 0.3) == 0.0);
    // Back-facing microfacets have D = 0.
    CHECK(bb_ggx_d(bb_v3(0.6, 0, -0.8), 0.5, 0.5) == 0.0);
}

TEST_CASE("GGX shared functions match the textbook forms", "[microfacet][quick]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int i = 0; i < 2000; ++i) {
        const double ax = 0.01 + u(rng), ay = 0.01 + u(rng);
        const ref::Dir wo = ref::dir_mu(1e-4 + (1 - 1e-4) * u(rng), 2 * M_PI * u(rng));
        const ref::Dir wi = ref::dir_mu(1e-4 + (1 - 1e-4) * u(rng), 2 * M_PI * u(rng));
        const ref::Dir m = ref::normalize({wo.x + wi.x, wo.y + wi.y, wo.z + wi.z});
        INFO("ax " << ax << " ay " << ay << " wo.z " << double(wo.z) << " wi.z " << double(wi.z));
        CHECK(bb_ggx_d(v3(m), ax, ay) == Approx(double(ref::ggx_d(m, ax, ay))).epsilon(1e-12));
        CHECK(bb_ggx_g1(v3(wo), ax, ay) == Approx(double(ref::ggx_g1(wo, ax, ay))).epsilon(1e-12));
        bb_params p = {{ax, ay, 1.0}};
        CHECK(bb_ggx_eval(p, BB_FRESNEL_NONE, p, v3(wo), v3(wi)) ==
              Approx(double(ref::ggx_f(wo, wi, ax, ay, true))).epsilon(1e-11));
        p.v[BB_GGX_SHADOWING] = 0.0;
        CHECK(bb_ggx_eval(p, BB_FRESNEL_NONE, p, v3(wo), v3(wi)) ==
              Approx(double(ref::ggx_f(wo, wi, ax, ay, false))).epsilon(1e-11));
    }
}

TEST_CASE("GGX visible-normal samples have the density the weight assumes", "[microfacet][quick]") {
    // The mean of the VNDF sample weight G2/G1(wo) must equal the albedo integrated in
    // half-vector space; with F = 1 and separable G2 this is the mean of G1(wi) over visible
    // normals. Here we check a weaker, exact identity: the mean of 1 over VNDF samples whose
    // microfacet lies in a cap equals the VNDF mass of that cap computed by quadrature.
    const double a = 0.4;
    const ref::Dir wo = ref::dir(1.1, 0.0);
    const double cap = 0.5;  // theta_m < cap
    const double g1 = double(ref::ggx_g1(wo, a, a));
    const double mass = ref::integrate_facing(
        [&](double th, double ph) {
            ref::Dir m = ref::dir(th, ph);
            return g1 * double(ref::ggx_d(m, a, a)) * double(ref::dot(wo, m)) / double(wo.z);
        },
        wo.z, 0.0, cap);
    const int n = 512;
    int inside = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            bb_vec3 m = bb_ggx_sample_vndf(v3(wo), a, a, (i + 0.5) / n, (j + 0.5) / n);
            inside += std::acos(std::fmin(1.0, m.z)) < cap;
        }
    CHECK(double(inside) / (n * n) == Approx(mass).margin(2e-3));
}

TEST_CASE("GGX closed-form disk weight (the vector kernel's) is the textbook G2/G1 weight", "[microfacet][quick]") {
    // bb_ggx_disk_weight against F(wo.m) G2(wo, wi) / G1(wo) evaluated in long double from the
    // reference Lambda (benchmarks/reference/reference.h), on the visible normal m of the same disk point:
    // anisotropic, grazing, both shadowing forms, with and without a Fresnel term.
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    bb_params cond{};
    cond.v[BB_FRESNEL_ETA] = 0.2;
    cond.v[BB_FRESNEL_K] = 3.0;
    int compared = 0, compared_iso = 0;
    for (const double ax : {1e-3, 0.05, 0.5, 1.0})
        for (const double ay : {ax, 0.7})
            for (const double mu : {1e-4, 0.05, 0.5, 1.0})
                for (const double phi : {0.0, 0.6})
                    for (const int correlated : {0, 1})
                        for (const int fkind : {BB_FRESNEL_NONE, BB_FRESNEL_CONDUCTOR}) {
                            bb_params p{};
                            p.v[BB_GGX_ALPHA_X] = ax;
                            p.v[BB_GGX_ALPHA_Y] = ay;
                            p.v[BB_GGX_SHADOWING] = correlated;
                            const ref::Dir wo_ref = ref::dir_mu(mu, phi);
                            const bb_vec3 wo = v3(wo_ref);
                            const int iso = ax == ay;  // the kernels' -D BB_ISOTROPIC
                            const bb_ggx_disk_cell cell = bb_ggx_disk_cell_make(p, wo, 0);
                            const bb_ggx_disk_cell cell_iso = bb_ggx_disk_cell_make(p, wo, 1);
                            for (int k = 0; k < 64; ++k) {
                                const double u1 = u(rng), u2 = u(rng);
                                const bb_vec2 d = bb_disk_polar(u1, u2);
                                const double h = std::sqrt(1.0 - d.x * d.x);
                                const bb_vec3 m = bb_ggx_sample_vndf_disk(wo, ax, ay, d);
                                const ref::Dir mr{m.x, m.y, m.z};
                                const ref::Dir wi = ref::reflect(wo_ref, ref::normalize(mr));
                                const double w = bb_ggx_disk_weight(cell, fkind, cond, d, h, 0);
                                if (std::fabs(double(wi.z)) < 1e-9) continue;  // the horizon: either side
                                const ref::ld lo = ref::ggx_lambda(wo_ref, ax, ay), li = ref::ggx_lambda(wi, ax, ay);
                                const ref::ld g2 = correlated ? 1 / (1 + lo + li) : ref::ggx_g1(wo_ref, ax, ay) * ref::ggx_g1(wi, ax, ay);
                                const double f = bb_fresnel_eval(fkind, cond, double(ref::dot(wo_ref, ref::normalize(mr))));
                                const double expect = wi.z > 0 ? double(g2 / ref::ggx_g1(wo_ref, ax, ay)) * f : 0.0;
                                INFO("ax " << ax << " ay " << ay << " mu " << mu << " phi " << phi << " corr " << correlated
                                           << " F " << fkind << " d " << d.x << "," << d.y);
                                CHECK(std::isfinite(w));
                                CHECK(w == Approx(expect).epsilon(1e-11).margin(1e-13));
                                // and the shared sampler's own weight, the scalar kernel's
                                const bb_sample s = bb_ggx_sample(p, fkind, cond, wo, u1, u2);
                                CHECK(w == Approx(s.weight).epsilon(1e-11).margin(1e-13));
                                if (iso) {
                                    // the isotropic form: wo rotated into the x-z plane, same point
                                    // of the disk, so wi rotated too; the weight is the same.
                                    const double wi_iso = bb_ggx_disk_weight(cell_iso, fkind, cond, d, h, 1);
                                    CHECK(std::isfinite(wi_iso));
                                    if (phi == 0.0) CHECK(wi_iso == Approx(expect).epsilon(1e-11).margin(1e-13));
                                    ++compared_iso;
                                }
                                ++compared;
                            }
                        }
    CHECK(compared > 10000);
    CHECK(compared_iso > 4000);
}

TEST_CASE("Smith lobe: a sample above the horizon has wo.wh > 0 (the shared validity rule)", "[microfacet][quick]") {
    // smith.h drops Beckmann's former extra test cos_oh > 0 from the sample weight: wi.z > 0
    // with G1(wo) > 0 implies wo.wh > 0 in floating point. Checked on both distributions,
    // grazing and anisotropic, where rounding is worst.
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    long live = 0, violations = 0;
    for (const int dist : {BB_SMITH_GGX, BB_SMITH_BECKMANN})
        for (const double ax : {1e-4, 0.01, 0.3, 1.0, 3.0})
            for (const double ay : {ax, 0.05})
                for (const double mu : {1e-6, 1e-3, 0.2, 0.9, 1.0})
                    for (int k = 0; k < 200; ++k) {
                        const double phi = 2 * M_PI * u(rng);
                        const bb_vec3 wo = bb_dir_from_mu_phi(mu, phi);
                        const double u1 = u(rng), u2 = u(rng);
                        const bb_vec3 wh = bb_smith_sample_vndf(dist, wo, ax, ay, u1, u2);
                        const bb_vec3 wi = bb_reflect(wo, wh);
                        if (!(wi.z > 0.0 && bb_smith_g1(dist, wo, ax, ay) > 0.0)) continue;
                        ++live;
                        violations += !(bb_dot(wo, wh) > 0.0);
                    }
    CHECK(live > 10000);
    CHECK(violations == 0);
}
