// What the table kinds share: the axes, the albedo integration of a list of cells (to a
// tolerance or with a fixed sample count), the attributes that say how a table was made, and
// each kind's registry entry (one .cpp per kind or family under host/tables).
#pragma once

#include <string>
#include <vector>

#include "brdfbake/albedo.h"
#include "brdfbake/lut.h"
#include "brdfbake/table.h"
#include "brdfbake/table_kinds.h"

namespace brdfbake {
namespace tables {

constexpr int kMaxTexels = 1 << 22;

/// A measured metal (metal:X, nk:FILE), whose Fresnel term depends on the wavelength.
bool is_measured_metal(const std::string& fresnel);

/// The mu axis (x) of a 2D table, with the request's mapping.
Axis mu_axis(const LutRequest& r, int size);
/// The roughness axis; `clamped` tells whether a texel's alpha was raised to BB_ALPHA_MIN.
Axis alpha_axis(const LutRequest& r, int size, bool& clamped);

/// A (mu, alpha) table with its axes set and one albedo cell per texel, alpha-major.
struct MuAlphaGrid {
    Table table;
    std::vector<AlbedoCell> cells;
    bool clamped = false;
};
MuAlphaGrid mu_alpha_grid(const LutRequest& r, const ModelConfig& swept_model);

/// The model's parameters with the swept alpha set.
ParamBlock with_alpha(ParamBlock p, const std::vector<int>& slots, double alpha);

/// The albedo of every cell, with the request's method and samples, or to its tolerance times
/// `share` (the split-sum table adds two integrals' errors: each gets half).
AlbedoResult integrate(Engine& engine, const LutRequest& r, const ModelConfig& m, const FresnelConfig& f,
                       std::vector<AlbedoCell> cells, double share = 1.0);

/// The attributes of an albedo-based table: model, Fresnel, method, samples, precision, tolerance,
/// and the alpha floor note.
void describe(Table& t, const LutRequest& r, const ModelConfig& m, const std::string& fresnel,
              const AlbedoResult& res, bool clamped);

/// The request's Fresnel term at its wavelength (most kinds' TableKind::fresnel).
FresnelConfig request_fresnel(const LutRequest& r);

// The entries of the registry, one per kind (host/tables/registry.cpp lists them).
const TableKind& albedo_kind();
const TableKind& eavg_kind();
const TableKind& dfg_kind();
const TableKind& dfg_ms_kind();
const TableKind& dielectric_kind();
const TableKind& conductor_kind();

}  // namespace tables
}  // namespace brdfbake
