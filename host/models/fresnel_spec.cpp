// The Fresnel registry: which Fresnel terms exist, their keys and ranges:
//   none, schlick:f0=F0, dielectric:eta=E, conductor:eta=E,k=K, conductor-approx:eta=E,k=K,
//   gen-schlick:f0=F0,f90=F90,exponent=P, f82-tint:f0=F0,tint=T, gen-schlick-ior:f0=F0,f90=F90,eta=E,
//   metal:Al|Au|Ag|Cu and nk:FILE.yml (tabulated n,k at --wavelength NM).
#include <cmath>
#include <cstdio>

#include "brdfbake/brdf/fresnel.h"
#include "brdfbake/error.h"
#include "brdfbake/spec.h"
#include "models/key_reader.h"
#include "models/nk_data.h"

namespace brdfbake {

namespace {

// eta is a ratio of indices: positive. The upper bounds keep every shared-math expression far
// from float overflow (see the edge-case policy in brdf/fresnel.h).
constexpr Range kEta{0.0, kMaxOpticalConstant, true};
constexpr Range kExtinction{0.0, kMaxOpticalConstant};

const char kKnown[] =
    "known: none, schlick:f0=F0, gen-schlick:f0=F0,f90=F90,exponent=P, f82-tint:f0=F0,tint=T, gen-schlick-ior:f0=F0,f90=F90,eta=E, dielectric:eta=E, "
    "conductor:eta=E,k=K, conductor-approx:eta=E,k=K, metal:Al|Au|Ag|Cu, nk:FILE.yml";

// The generalized Schlick exponent: 0 (F = f90 everywhere) to far beyond Cycles' largest table
// texel (exponent 5 (1 - z)/z at z = 1e-4: about 5e4).
constexpr Range kSchlickExponent{0.0, 1e6};

/// F82-tint [Kutz et al. 2021, "Novel aspects of the Adobe Standard Material"; the OpenPBR Surface
/// specification, metal]: Schlick's F(mu) with f0 less b mu (1 - mu)^6, b chosen so that F at
/// mu_bar = 1/7 (about 82 degrees) is tint times Schlick's value there:
///   b = (1 - tint) F_schlick(mu_bar) / (mu_bar (1 - mu_bar)^6).
/// As the term is not clamped (so that tables stay linear in f0 and b), a pair whose F dips below 0
/// is rejected (small f0 with a dark tint: F82-tint is a metal's Fresnel).
FresnelConfig f82_tint(double f0, double tint) {
    const double mu_bar = 1.0 / 7.0;
    const double b = (1.0 - tint) * bb_fresnel_schlick(mu_bar, f0) / (mu_bar * std::pow(1.0 - mu_bar, 6));
    FresnelConfig f;
    f.kind = BB_FRESNEL_GEN_SCHLICK;
    f.params[BB_GEN_SCHLICK_F0] = f0;
    f.params[BB_GEN_SCHLICK_F90] = 1.0;
    f.params[BB_GEN_SCHLICK_EXPONENT] = 5.0;
    f.params[BB_GEN_SCHLICK_B] = b;
    double lowest = 1.0, at = 0.0;
    for (int i = 0; i <= 4000; ++i) {
        const double mu = i / 4000.0, v = bb_fresnel_gen_schlick(mu, f0, 1.0, 5.0, b);
        if (v < lowest) lowest = v, at = mu;
    }
    if (lowest < 0.0)
        throw Error("Fresnel f82-tint:f0=" + format_number(f0) + ",tint=" + format_number(tint) + " goes below 0 (F = " +
                    format_number(lowest) + " at cos " + format_number(at) +
                    "); F82-tint describes metals: raise f0 or tint");
    f.canonical = "f82-tint:f0=" + format_number(f0) + ",tint=" + format_number(tint);
    return f;
}

/// A measured material at one wavelength: the exact conductor with the interpolated n, k.
FresnelConfig measured(const NkTable& table, const std::string& what, double wavelength_nm) {
    if (wavelength_nm == 0.0)
        throw Error("Fresnel '" + what + "' needs --wavelength NM (its tabulated n,k cover " +
                    format_number(table.min_nm()) + " to " + format_number(table.max_nm()) + " nm)");
    if (!std::isfinite(wavelength_nm) || !(wavelength_nm > 0.0))
        throw Error("--wavelength must be a positive number of nanometres, got " + format_number(wavelength_nm));
    const NkValue v = interpolate_nk(table, wavelength_nm);
    FresnelConfig f;
    f.kind = BB_FRESNEL_CONDUCTOR;
    f.params[BB_FRESNEL_ETA] = v.n;
    f.params[BB_FRESNEL_K] = v.k;
    char nm[32];
    std::snprintf(nm, sizeof nm, "%.10g", wavelength_nm);  // 550, not format_number's 5.5e+02
    f.canonical = what + " at " + nm + " nm = conductor:eta=" + format_number(v.n) +
                  ",k=" + format_number(v.k);
    return f;
}

}  // namespace

FresnelConfig resolve_fresnel(const std::string& text, double wavelength_nm) {
    // Measured data: the part after the colon is a symbol or a path, not key=value pairs.
    if (text.rfind("metal:", 0) == 0) {
        const std::string symbol = text.substr(6);
        if (symbol.empty()) throw Error("Fresnel 'metal' needs a metal, e.g. metal:Al (known: Al, Au, Ag, Cu)");
        return measured(load_nk_preset(symbol), "metal:" + symbol, wavelength_nm);
    }
    if (text.rfind("nk:", 0) == 0) {
        const std::string path = text.substr(3);
        if (path.empty()) throw Error("Fresnel 'nk' needs a file, e.g. nk:Al.yml (refractiveindex.info YAML)");
        return measured(load_nk_file(path), "nk:" + path, wavelength_nm);
    }
    if (text == "metal" || text == "nk")
        throw Error("Fresnel '" + text + "' needs " + (text == "metal" ? "a metal, e.g. metal:Al" : "a file, e.g. nk:FILE.yml"));

    const Spec spec = parse_spec(text);
    KeyReader keys(spec, "Fresnel");
    FresnelConfig f;
    if (spec.name == "none") {
        f.kind = BB_FRESNEL_NONE;
        f.canonical = "none";
    } else if (spec.name == "schlick") {
        f.kind = BB_FRESNEL_SCHLICK;
        const double f0 = keys.required_number("f0", {0.0, 1.0}, "reflectance at normal incidence");
        f.params[BB_SCHLICK_F0] = f0;
        f.canonical = "schlick:f0=" + format_number(f0);
    } else if (spec.name == "gen-schlick") {
        f.kind = BB_FRESNEL_GEN_SCHLICK;
        const double f0 = keys.required_number("f0", {0.0, 1.0}, "reflectance at normal incidence");
        const double f90 = keys.number("f90", 1.0, {0.0, 1.0});
        const double exponent = keys.number("exponent", 5.0, kSchlickExponent);
        f.params[BB_GEN_SCHLICK_F0] = f0;
        f.params[BB_GEN_SCHLICK_F90] = f90;
        f.params[BB_GEN_SCHLICK_EXPONENT] = exponent;
        f.canonical = "gen-schlick:f0=" + format_number(f0) + ",f90=" + format_number(f90) +
                      ",exponent=" + format_number(exponent);
    } else if (spec.name == "gen-schlick-ior") {
        f.kind = BB_FRESNEL_GEN_SCHLICK_IOR;
        const double f0 = keys.required_number("f0", {0.0, 1.0}, "reflectance at normal incidence");
        const double f90 = keys.number("f90", 1.0, {0.0, 1.0});
        const double eta = keys.required_number("eta", {1.0, kMaxOpticalConstant}, "index whose dielectric curve drives F, >= 1");
        f.params[BB_GEN_SCHLICK_F0] = f0;
        f.params[BB_GEN_SCHLICK_F90] = f90;
        f.params[BB_GEN_SCHLICK_IOR_ETA] = eta;
        f.params[BB_GEN_SCHLICK_IOR_ETA_M1] = eta - 1.0;
        f.canonical = "gen-schlick-ior:f0=" + format_number(f0) + ",f90=" + format_number(f90) + ",eta=" + format_number(eta);
    } else if (spec.name == "f82-tint") {
        const double f0 = keys.required_number("f0", {0.0, 1.0}, "reflectance at normal incidence");
        const double tint = keys.required_number("tint", {0.0, 1.0}, "F at 82 deg relative to Schlick's");
        keys.finish();
        return f82_tint(f0, tint);
    } else if (spec.name == "dielectric") {
        f.kind = BB_FRESNEL_DIELECTRIC;
        const double eta = keys.required_number("eta", kEta, "relative index of refraction, e.g. 1.5");
        f.params[BB_FRESNEL_ETA] = eta;
        f.params[BB_FRESNEL_ETA_M1] = eta - 1.0;  // exact here; a float kernel could not recover it
        f.canonical = "dielectric:eta=" + format_number(eta);
    } else if (spec.name == "conductor" || spec.name == "conductor-approx") {
        f.kind = spec.name == "conductor" ? BB_FRESNEL_CONDUCTOR : BB_FRESNEL_CONDUCTOR_APPROX;
        const double eta = keys.required_number("eta", kEta, "real part of the complex index eta + ik");
        const double k = keys.required_number("k", kExtinction, "extinction coefficient, imaginary part of the index");
        f.params[BB_FRESNEL_ETA] = eta;
        f.params[BB_FRESNEL_K] = k;
        f.canonical = spec.name + ":eta=" + format_number(eta) + ",k=" + format_number(k);
    } else {
        throw Error("unknown Fresnel term '" + spec.name + "'; " + kKnown);
    }
    keys.finish();
    return f;
}

}  // namespace brdfbake
