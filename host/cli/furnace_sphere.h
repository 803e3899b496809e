// The white-furnace sphere (`brdfbake furnace`, `compensation --furnace`): a sphere lit by a
// uniform white environment of radiance 1 whose pixels show E(n.v), the light it sends back.
#pragma once

#include <string>
#include <vector>

#include "plot/plot.h"

namespace brdfbake {

/// The mu nodes at which a sphere's E is given: mu_k = ((k + 0.5) / n)^2 (denser at grazing).
std::vector<double> furnace_nodes(int n);

/// A sphere `pixels` across showing E(n.v) interpolated from `e` at furnace_nodes(e.size()), its
/// silhouette outlined, the environment (E = 1) in light blue, titled `title`.
PlotSpec furnace_sphere(const std::string& title, const std::vector<double>& e, int pixels);

/// A figure for sphere panels `pixels` across (square spheres) with the grey colour bar of E.
Figure furnace_figure(int pixels);

}  // namespace brdfbake
