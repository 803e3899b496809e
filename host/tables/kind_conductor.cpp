// The Fresnel-weighted albedo of a conductor: one channel E at a given Fresnel term, or for a term
// that depends on the wavelength (metal:X, nk:FILE, thin-film) without --wavelength its colour R,
// G, B integrated over the spectrum (tables/spectral_fresnel.h), or with --rgb-wavelengths R, G, B
// at 650, 550 and 450 nm.
#include <algorithm>

#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "brdfbake/fresnel_terms.h"
#include "models/key_reader.h"
#include "tables/lut_common.h"
#include "tables/spectral_fresnel.h"

namespace brdfbake {
namespace tables {
namespace {

constexpr double kRgbNm[3] = {650.0, 550.0, 450.0};

/// A term that depends on the wavelength, without --wavelength: three colour channels.
bool rgb(const LutRequest& r) { return r.wavelength_nm == 0.0 && fresnel_needs_wavelength(r.fresnel); }

int channels(const LutRequest& r) { return rgb(r) ? 3 : 1; }
std::vector<std::string> channel_names(const LutRequest& r) {
    return rgb(r) ? colour_channel_names() : std::vector<std::string>{"E"};
}

FresnelConfig conductor_fresnel(const LutRequest& r) {
    return resolve_fresnel(r.fresnel, rgb(r) ? kRgbNm[0] : r.wavelength_nm);
}

std::vector<std::string> conductor_passes(const LutRequest& r) {
    if (!rgb(r)) return {};
    if (spectral_colour(r)) return colour_channel_names();
    return {"R at 650 nm", "G at 550 nm", "B at 450 nm"};
}

/// The spectral colour: R, G, B of the term's curves (spectral_fresnel.h).
Table spectral_conductor(Engine& engine, const LutRequest& r, const ModelConfig& m) {
    MuAlphaGrid g = mu_alpha_grid(r, m);
    Table& t = g.table;
    const SpectralCurves curves = spectral_curves(engine, r.fresnel, r.colour, r.precision);
    t.quantity = "Fresnel-weighted directional albedo E(mu_o, alpha) of a conductor, its colour in " + curves.colour;
    t.channels = colour_channel_names();
    const AlbedoResult last = integrate_colour(engine, r, m, curves, g.cells, t.values, t.error);
    describe(t, r, m, r.fresnel + " in " + curves.colour, last.method, last.samples_per_cell, g.clamped);
    for (size_t c = 0; c < 3; ++c)
        t.attributes["spectral_error_" + t.channels[c]] =
            "curve " + format_number(curves.curve_error[c]) + ", spectrum " + format_number(curves.spectral_error[c]) +
            " (in the error channel)";
    return std::move(g.table);
}

std::vector<std::string> conductor_program(const LutRequest& r) {
    return {"albedo|" + r.model + "|" + r.fresnel.substr(0, r.fresnel.find(':'))};
}

Table compute_conductor(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig& f) {
    if (!rgb(r))
        return directional_albedo_table(engine, r, m, f,
                                        "Fresnel-weighted directional albedo E(mu_o, alpha) of a conductor");
    if (spectral_colour(r)) return spectral_conductor(engine, r, m);
    MuAlphaGrid g = mu_alpha_grid(r, m);
    Table& t = g.table;
    t.quantity = "Fresnel-weighted directional albedo E(mu_o, alpha) of a measured conductor at 650, 550 and 450 nm";
    t.channels = colour_channel_names();
    t.error.assign(g.cells.size(), 0.0);
    std::string fresnel_text;
    AlbedoResult last;
    for (int c = 0; c < 3; ++c) {
        const FresnelConfig fc = resolve_fresnel(r.fresnel, kRgbNm[c]);
        last = integrate(engine, r, m, fc, g.cells);
        std::vector<double> v;
        for (size_t k = 0; k < g.cells.size(); ++k) {
            v.push_back(last.values[k].value);
            t.error[k] = std::max(t.error[k], last.values[k].error);
        }
        t.values.push_back(v);
        fresnel_text += std::string(c ? "; " : "") + colour_channel_names()[size_t(c)] + ": " + fc.canonical;
    }
    describe(t, r, m, fresnel_text, last.method, last.samples_per_cell, g.clamped);
    return t;
}

void validate_conductor(const LutRequest& r, const ModelConfig&, const FresnelConfig& f) {
    if (!(f.kind == BB_FRESNEL_CONDUCTOR || f.kind == BB_FRESNEL_CONDUCTOR_APPROX || fresnel_needs_wavelength(r.fresnel)))
        throw Error("the conductor table needs a conductor Fresnel term: --fresnel conductor:eta=E,k=K, metal:Al or nk:FILE");
    if (r.colour != "srgb" && r.colour != "acescg" && r.colour != "wavelengths")
        throw Error("unknown colour space '" + r.colour + "'; known: srgb, acescg (or --rgb-wavelengths)");
}

}  // namespace

TableKind conductor_kind() {
    TableKind k(TableKindId::Conductor, "conductor",
                "Fresnel-weighted albedo E(mu_o, alpha) of a conductor: --fresnel conductor:eta=,k= (channel E) or "
                "metal:X / nk:FILE / thin-film (channels R, G, B: the colour in linear sRGB or --colour-space acescg, or "
                "with --rgb-wavelengths at 650, 550, 450 nm; E at --wavelength)",
                conductor_program, compute_conductor);
    k.bakes_lobe_fresnel = true;
    k.spectral_colour = true;
    k.needs_conductor_fresnel = true;
    k.example_fresnel = "metal:Au";
    k.lobe_requirement = "a conductor table needs a conductor Fresnel (conductor:, metal:, nk:)";
    k.value_channels = channel_names;
    k.integrations = channels;  // one per colour channel
    k.fresnel = conductor_fresnel;
    k.validate = validate_conductor;
    k.pass_names = conductor_passes;
    return k;
}

}  // namespace tables
}  // namespace brdfbake
