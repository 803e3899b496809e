// Reciprocity of a walk estimate from both ends of one pair (tests/test_random_walk*.cpp).
#pragma once

#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "integrate/random_walk.h"
#include "support.h"

namespace testing {

/// f(a, b) and f(b, a) by the walks of `req` (its model, Fresnel term and walks) on 4 seeds, float
/// and double in turn: the two within kReciprocitySigmas standard errors of their difference, and
/// that noise under `max_noise` of the value (so that the comparison can see an asymmetry).
inline void check_both_ends(brdfbake::WalkEvalRequest req, const brdfbake::Vec3& a, const brdfbake::Vec3& b,
                            const brdfbake::ParamBlock& params, double max_noise, const std::string& what) {
    using namespace brdfbake;
    for (int seed = 0; seed < 4; ++seed) {
        req.seed = 0x62726466u + 977u * unsigned(seed);
        req.precision = seed % 2 ? Precision::Double : Precision::Float;
        req.pairs = {{a, b, params}, {b, a, params}};
        const WalkEvalResult r = walk_eval(engine(), req);
        const double noise = std::hypot(r.f[0].error, r.f[1].error) / 3;  // errors are 3 standard errors
        INFO(what << " seed " << seed << ": " << r.f[0].value << " +- " << r.f[0].error << " vs " << r.f[1].value
                  << " +- " << r.f[1].error);
        CHECK(std::fabs(r.f[0].value - r.f[1].value) <= kReciprocitySigmas * noise);
        CHECK(noise < max_noise * r.f[0].value);
    }
}

/// The walk's albedo (walk_albedo, 2^18 walks) of model m at mu (phi = 0) with the Fresnel term
/// `fresnel`: E (R for a dielectric), T, their first orders.
inline brdfbake::WalkAlbedo walk_albedo_at_mu(const brdfbake::ModelConfig& m, const std::string& fresnel, double mu) {
    using namespace brdfbake;
    AlbedoRequest areq;
    areq.model = m.id;
    areq.fresnel = resolve_fresnel(fresnel);
    areq.cells = cells_for({mu}, 0.0, m.params);
    areq.samples = 1 << 18;
    return walk_albedo(engine(), areq).values[0];
}

/// pi times the mean of the values of `f` (an integral of f |cos| over a hemisphere by
/// cosine-distributed directions), its standard error over the directions in *se.
inline double pi_mean(const std::vector<brdfbake::AlbedoValue>& f, double* se) {
    double s = 0, s2 = 0;
    for (const brdfbake::AlbedoValue& v : f) {
        s += M_PI * v.value;
        s2 += M_PI * M_PI * v.value * v.value;
    }
    const double n = double(f.size()), mean = s / n;
    *se = std::sqrt((s2 / n - mean * mean) / (n - 1));
    return mean;
}

}  // namespace testing
