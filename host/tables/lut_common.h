// What the table kinds share: the axes, the albedo integration of a list of cells (to a
// tolerance or with a fixed sample count), the attributes that say how a table was made, and
// each kind's registry entry (one .cpp per kind or family under host/tables).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "brdfbake/albedo.h"
#include "brdfbake/lut.h"
#include "brdfbake/table.h"
#include "brdfbake/table_kinds.h"

namespace brdfbake {
namespace tables {

constexpr int kMaxTexels = 1 << 22;

/// Whether the model's alpha -> 0 limit is a mirror (the Smith microfacet lobes), so that a
/// texel at alpha = 0 is computed as that limit rather than at the alpha floor.
bool has_mirror_limit(const ModelConfig& m);

// The axes, with the request's texel convention (r.texels), range and mapping; every kind builds
// its axes with these so that the grid options (--texels, ranges, floors) reach it.
/// The spread of a channel over a table for its header: "min A, median B, max C" (4 digits), or
/// "none" for no values.
std::string min_median_max_text(std::vector<double> v);
/// The mu axis's name under the request's --mu-map: mu, sqrt_mu or sqrt_one_minus_mu.
std::string table_mu_axis_name(const LutRequest& r);
/// The mu axis (x) of a 2D table; mu below r.mu_floor is computed at it (said in the mapping).
Axis mu_axis(const LutRequest& r, int size);
/// The roughness axis; `clamped` tells whether a texel's alpha was raised to BB_ALPHA_MIN. A texel
/// at alpha = 0 of a model with a mirror limit keeps alpha = 0: `integrate` computes it as the limit.
Axis alpha_axis(const LutRequest& r, int size, bool& clamped);
/// The eta axis (z) with the request's mapping (r.eta_map) over [r.eta_lo, r.eta_hi] in eta. With
/// the cycles map, r.eta_hi = infinity is Cycles' whole z range [z(eta_lo), 1]: a texel above z =
/// kCyclesZHi is computed there (eta = infinity has no interface to integrate), as Cycles does.
Axis eta_axis(const LutRequest& r, int size);
/// The eta axis's name under the request's --eta-map: eta, f0 or cycles_z.
std::string eta_axis_name(const LutRequest& r);

/// Blender Cycles' z coordinate of its 3D tables (intern/cycles/app/cycles_precompute.cpp): texel
/// i of N at z = i/(N - 1) on [0, 1], computed at z clamped to [kCyclesZLo, kCyclesZHi]; the glass
/// and gen-schlick-ior tables read it as eta = (1 + z^2)/(1 - z^2), i.e. z = sqrt((eta - 1)/(eta + 1))
/// (ior_from_F0(z^4)), the gen-schlick table as exponent = 5 (1 - z)/z.
constexpr double kCyclesZLo = 1e-4, kCyclesZHi = 0.99;

/// A (mu, alpha) table with its axes set and one albedo cell per texel, alpha-major.
struct MuAlphaGrid {
    Table table;
    std::vector<AlbedoCell> cells;
    bool clamped = false;
};
MuAlphaGrid mu_alpha_grid(const LutRequest& r, const ModelConfig& swept_model);

/// The model's parameters with the swept alpha set through its roughness axis (none where `slots`,
/// roughness_slots(m) or empty for a model without roughness, is empty).
ParamBlock with_alpha(const ModelConfig& m, ParamBlock p, const std::vector<int>& slots, double alpha);

/// The smallest alpha a table computes the model at: BB_ALPHA_MIN, or a mapped axis' alpha_lo.
double alpha_floor(const ModelConfig& m);

/// The albedo of every cell, with the request's method and samples, or to its tolerance times
/// `share` (the split-sum table adds two integrals' errors: each gets half). A cell at alpha = 0
/// of a model with a mirror limit is that limit, F(mu) at Fresnel term f, in closed form.
AlbedoResult integrate(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig& f,
                       std::vector<AlbedoCell> cells, double share = 1.0);

/// The one-channel table E(mu_o, alpha) of the albedo at Fresnel term f (the albedo kind, and
/// the conductor kind at one wavelength), described by `quantity`.
Table directional_albedo_table(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig& f,
                               const std::string& quantity);

/// The attributes of a computed table: model, Fresnel, the method and samples per texel of its
/// integration, precision, the tolerance where the request has one, and the alpha floor note
/// where `clamped`.
void describe(Table& t, const LutRequest& r, const ModelConfig& m, const std::string& fresnel,
              const std::string& method, std::uint64_t samples_per_cell, bool clamped);

/// The rough dielectric integration's request for a table's cells (the dielectric and
/// dielectric-eavg kinds): the model's shadowing, the request's method, samples and precision.
DielectricRequest dielectric_request(const LutRequest& r, const ModelConfig& m);
/// The checks the rough dielectric kinds share: GGX, a shadowing with a transmitted form (not
/// masking), no --fresnel (they hold the exact dielectric's), importance sampling or quadrature.
void validate_rough_dielectric(const LutRequest& r, const ModelConfig& m, const FresnelConfig& f);

/// A kind that is `base` in all but its id, name, description and computation (eavg of albedo,
/// dfg-ms of dfg).
TableKind variant_of(TableKind base, TableKindId id, const std::string& name, const std::string& description,
                     TableKind::Compute compute);

// The entries of the registry, one per kind (host/tables/registry.cpp lists them).
TableKind albedo_kind();
TableKind eavg_kind();
TableKind dfg_kind();
TableKind dfg_ms_kind();
TableKind dielectric_kind();
TableKind conductor_kind();
TableKind sheen_albedo_kind();
TableKind sheen_viewer_kind();
TableKind dielectric_eavg_kind();
TableKind gen_schlick_kind();
TableKind gen_schlick_ior_kind();
TableKind dfg_f82_kind();
TableKind ltc_kind();
TableKind sheen_ltc_kind();
TableKind thin_film_kind();

/// A thin-film Fresnel spec with its thickness set to `thickness_nm` (replacing any thickness key):
/// one z slice of the thin-film table (kind_thin_film.cpp).
std::string thin_film_at(const std::string& fresnel_spec, double thickness_nm);

/// The thicknesses of a film over [lo_nm, hi_nm] at most `step_nm` apart, evenly spaced with both
/// ends: ceil((hi - lo) / step) + 1 (1 for an empty span; at most 1e6). The one rule of the scene
/// setting thickness_step, `lut thin-film --thickness-step` and the iridescence map's.
int thickness_slices(double lo_nm, double hi_nm, double step_nm);

}  // namespace tables
}  // namespace brdfbake
