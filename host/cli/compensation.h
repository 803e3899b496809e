// `brdfbake compensation` (cmd_compensation.cpp: the conductor; compensation_dielectric.cpp: the
// rough dielectric): the options both read and the pieces both build their comparison from.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "brdfbake/albedo.h"
#include "brdfbake/evaluate.h"
#include "brdfbake/output.h"
#include "brdfbake/spec.h"
#include "plot/plot.h"

namespace brdfbake {

struct CompensationOptions {
    std::string scheme = "all";
    std::string model = "ggx";
    std::string alpha = "0.1,0.25,0.5,0.75,1";
    std::string mu = "0.1,0.3,0.5,0.7,1";
    double f0 = 0.5;
    double eta = 0.0;  // the rough dielectric's relative index (> 1), compared from outside and inside
    bool f0_given = false, eta_given = false;  // --f0 and --eta on the command line
    std::int64_t walks = std::int64_t(1) << 18;
    int lobe_directions = 256;       // directions wi of the lobe distance (0: none)
    std::int64_t lobe_walks = 1024;  // walks per direction
    std::string format = "table";
    std::string output;
    std::string plot;
    std::string furnace;  // the furnace picture: spheres of single, each scheme and the walk per alpha
    int furnace_nodes = 24;
    int furnace_pixels = 120;
};

/// E(mu) at kEGrid mu texel centres (k + 0.5)/kEGrid, linear between them (clamped at the ends):
/// E(mu_i) of Kulla and Conty's lobe.
constexpr int kEGrid = 64;
std::vector<double> e_grid_nodes();
double e_at(const std::vector<AlbedoValue>& grid, double mu);

/// The directions wi of a lobe's L1 distance at wo = (sqrt(1 - mu^2), 0, mu): n/2 cosine-weighted,
/// n/2 the visible-normal sample of `single` (a height-correlated ggx or beckmann lobe at alpha, F = 1;
/// sample_on_device), seeded by (alpha, mu, seed); `density` the mixture's p(wi) (the visible
/// normals' p = f wi.z G1(wo) / G2(wo, wi) with F = 1, Lambda from brdf/microfacet.h). A sample below
/// the horizon is dropped (it adds 0): the integral of g over wi is sum g(wi)/density / n.
struct LobeDirections {
    Vec3 wo{0.0, 0.0, 1.0};
    std::vector<Vec3> wi;
    std::vector<double> density;
    std::vector<double> f_single;  // `single` with F = 1 at (wo, wi)
};
LobeDirections lobe_directions(Engine& engine, const ModelConfig& single, double alpha, double mu, int n,
                               std::uint64_t seed = 0);

/// One number of a comparison row: ",%.17g" in CSV, else " %*.{digits}f", `width` wide.
std::string number_cell(bool csv, double v, int width, int digits);
/// A row's lobe columns: per scheme `names[k]` its L1 distance l1[k] (text: as wide as its name + 3),
/// then the distances' error and the walk's noise in them.
std::string lobe_cells(bool csv, const std::vector<std::string>& names, const std::vector<double>& l1, double error,
                       double noise);

/// A panel of y against mu = cos theta_o, one curve per alpha (a new curve where alpha changes
/// along `points`), x in [0, 1], with a line at y = 0 where `zero_line`.
struct MuPoint {
    double alpha, mu, y;
};
PlotSpec mu_panel(const std::string& title, const std::string& y_label, const std::vector<MuPoint>& points,
                  bool zero_line);

/// `compensation --eta E` (compensation_dielectric.cpp): refuses what the dielectric comparison does
/// not take (one line each), then compares each dielectric scheme with the walk from outside (eta)
/// and inside (1/eta) per alpha and mu; writes the text (or JSON, CSV), --plot and --furnace.
void check_dielectric_compensation(const CompensationOptions& o, bool f0_given);
void run_dielectric_compensation(Engine& engine, const CompensationOptions& o, const std::vector<double>& alphas,
                                 const std::vector<double>& mus, Format format);

}  // namespace brdfbake
