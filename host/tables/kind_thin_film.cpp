// The thin-film table (issue 36, item 4): the Fresnel-weighted albedo E(mu_o, alpha, d) of a lobe
// whose Fresnel term is one film on a substrate (thin-film:eta=,base_eta= or base=metal:X), over
// the film's thickness d: the axis a glTF KHR_materials_iridescence thickness texture drives
// (thickness = mix(iridescenceThicknessMinimum, iridescenceThicknessMaximum, texture.g), defaults
// 100 and 400 nm; KhronosGroup/glTF extensions/2.0/Khronos/KHR_materials_iridescence/README.md).
// The glTF Sample Viewer evaluates F_iridescence(cos) per pixel (source/Renderer/shaders/
// iridescence.glsl, Belcour and Barla 2017's evalIridescence) and mixes it with Schlick's by
// iridescenceFactor; the albedo is linear in F, so a renderer that wants the lobe's albedo reads
// E_film from this table at the texel's thickness and mixes it the same way.
//
// Each z slice is the conductor kind's spectral table at that thickness (the colour R, G, B from
// three tabulated curves, tables/spectral_fresnel.h) or, with --wavelength, its one channel E.
#include <algorithm>
#include <cmath>

#include "brdfbake/brdf/models.h"
#include "brdfbake/error.h"
#include "brdfbake/fresnel_terms.h"
#include "models/key_reader.h"
#include "tables/lut_common.h"
#include "tables/spectral_fresnel.h"

namespace brdfbake {
namespace tables {
namespace {

constexpr const char* kThicknessAxis = "thickness_nm";

int film_channels(const LutRequest& r) { return r.wavelength_nm == 0.0 ? 3 : 1; }
int film_integrations(const LutRequest& r) { return film_channels(r) * r.depth; }

std::vector<std::string> film_passes(const LutRequest& r) {
    std::vector<std::string> names;
    const std::vector<std::string> each = r.wavelength_nm == 0.0 ? colour_channel_names() : std::vector<std::string>{"E"};
    for (int k = 1; k <= r.depth; ++k)
        for (const auto& c : each)
            names.push_back(c + " at thickness slice " + std::to_string(k) + " of " + std::to_string(r.depth));
    return names;
}

Axis thickness_axis(const LutRequest& r) {
    Axis a = make_axis(kThicknessAxis, "thickness_nm = w, the film's thickness in nanometres", r.thickness_lo,
                       r.thickness_hi, r.depth, r.texels);
    a.parameter_name = "thickness_nm";
    a.parameter = a.coordinate;
    return a;
}

/// The term at the range's upper thickness (at 550 nm without --wavelength); another term as it
/// is, for validate_thin_film to refuse.
FresnelConfig film_fresnel(const LutRequest& r) {
    const double nm = r.wavelength_nm == 0.0 ? 550.0 : r.wavelength_nm;
    if (r.fresnel.rfind("thin-film:", 0) != 0) return resolve_fresnel(r.fresnel, fresnel_needs_wavelength(r.fresnel) ? nm : 0.0);
    return resolve_fresnel(thin_film_at(r.fresnel, r.thickness_hi), nm);
}

std::vector<std::string> film_program(const LutRequest& r) { return {"albedo|" + r.model + "|thin-film"}; }

/// One slice's channels and errors appended to the table's (slices stacked along y).
void append_slice(Table& t, const std::vector<std::vector<double>>& values, const std::vector<double>& error) {
    for (size_t c = 0; c < values.size(); ++c)
        t.values[c].insert(t.values[c].end(), values[c].begin(), values[c].end());
    t.error.insert(t.error.end(), error.begin(), error.end());
}

Table compute_thin_film(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig&) {
    MuAlphaGrid g = mu_alpha_grid(r, m);
    Table& t = g.table;
    t.z = thickness_axis(r);
    const bool colour = r.wavelength_nm == 0.0;
    t.channels = colour ? colour_channel_names() : std::vector<std::string>{"E"};
    t.values.assign(t.channels.size(), {});
    AlbedoResult last;
    std::string colour_text;
    std::array<double, 3> curve{}, spectrum{};
    for (double d : t.z.parameter) {
        const std::string spec = thin_film_at(r.fresnel, d);
        std::vector<std::vector<double>> values;
        std::vector<double> error;
        if (colour) {
            const SpectralCurves curves = spectral_curves(engine, spec, r.colour, r.precision);
            colour_text = curves.colour;
            last = integrate_colour(engine, r, m, curves, g.cells, values, error);
            for (size_t c = 0; c < 3; ++c) {
                curve[c] = std::max(curve[c], curves.curve_error[c]);
                spectrum[c] = std::max(spectrum[c], curves.spectral_error[c]);
            }
        } else {
            last = integrate(engine, r, m, resolve_fresnel(spec, r.wavelength_nm), g.cells);
            values.assign(1, {});
            for (const auto& v : last.values) {
                values[0].push_back(v.value);
                error.push_back(v.error);
            }
        }
        append_slice(t, values, error);
    }
    t.quantity = "Fresnel-weighted directional albedo E(mu_o, alpha, thickness) of a lobe under a thin film, " +
                 (colour ? "its colour in " + colour_text : "at " + format_number(r.wavelength_nm) + " nm");
    describe(t, r, m, r.fresnel + " at each texel's thickness" + (colour ? " in " + colour_text : ""), last.method,
             last.samples_per_cell, g.clamped);
    if (colour)
        for (size_t c = 0; c < 3; ++c)
            t.attributes["spectral_error_" + t.channels[c]] = "curve " + format_number(curve[c]) + ", spectrum " +
                                                              format_number(spectrum[c]) + " (largest over the slices; in the error channel)";
    return std::move(g.table);
}

void validate_thin_film(const LutRequest& r, const ModelConfig&, const FresnelConfig& f) {
    if (f.kind != BB_FRESNEL_THIN_FILM)
        throw Error("the thin-film table needs --fresnel thin-film:eta=FILM_ETA,base_eta=N[,base_k=K] or "
                    "thin-film:eta=FILM_ETA,base=metal:X (its thickness is the table's z axis)");
    if (r.colour != "srgb" && r.colour != "acescg")
        throw Error("the thin-film table's colour space is srgb or acescg (--rgb-wavelengths is the conductor table's)");
    if (!(r.thickness_lo >= 0.0 && r.thickness_hi >= r.thickness_lo && r.thickness_hi <= 100000.0))
        throw Error("--thickness-range must satisfy 0 <= lo <= hi <= 100000 (nm)");
    if (r.thickness_lo == r.thickness_hi && r.depth != 1)
        throw Error("--thickness-range " + format_number(r.thickness_lo) + "," + format_number(r.thickness_hi) +
                    " is one thickness: give a depth of 1 (--size WxHx1)");
    if (r.depth < 1 || r.depth > 256 || double(r.width) * r.height * r.depth > kMaxTexels)
        throw Error("thin-film table depth must be 1 to 256 and the table at most 4M texels");
}

}  // namespace

int thickness_slices(double lo_nm, double hi_nm, double step_nm) {
    const double span = hi_nm - lo_nm;
    if (!(span > 0.0)) return 1;
    return int(std::min(1e6, std::ceil(span / step_nm - 1e-9) + 1.0));
}

std::string thin_film_at(const std::string& fresnel_spec, double thickness_nm) {
    const Spec s = parse_spec(fresnel_spec);
    std::string keys;
    for (const auto& kv : s.keys)
        if (kv.first != "thickness") keys += kv.first + "=" + kv.second + ",";
    return s.name + ":" + keys + "thickness=" + format_number(thickness_nm);
}

TableKind thin_film_kind() {
    TableKind k(TableKindId::ThinFilm, "thin-film",
                "Fresnel-weighted albedo E(mu_o, alpha, thickness_nm) under a thin film (--fresnel thin-film:eta=,"
                "base_eta= or base=metal:X; z = --thickness-range, default 100-400 nm as KHR_materials_iridescence): "
                "channels R, G, B in linear sRGB (--colour-space acescg), or E at --wavelength",
                film_program, compute_thin_film);
    k.eta_axis = true;  // a z axis: sizes WxHxD
    k.own_z_axis = kThicknessAxis;
    k.bakes_lobe_fresnel = true;
    k.spectral_colour = true;
    k.example_fresnel = "thin-film:eta=1.3,base_eta=1.5";
    k.lobe_requirement = "a thin-film table needs a thin-film Fresnel (thin-film:)";
    k.value_channels = [](const LutRequest& r) {
        return film_channels(r) == 3 ? colour_channel_names() : std::vector<std::string>{"E"};
    };
    k.integrations = film_integrations;
    k.pass_names = film_passes;
    k.fresnel = film_fresnel;
    k.validate = validate_thin_film;
    return k;
}

}  // namespace tables
}  // namespace brdfbake
