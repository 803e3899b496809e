// `brdfbake fit`: an analytic model's alpha (or alpha_x, alpha_y) and Fresnel parameters fitted per colour channel to a
// target BRDF, a measured MERL file or any model spec (host/fit/model_fit.h).
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include "brdfbake/error.h"
#include "brdfbake/evaluate.h"
#include "brdfbake/output.h"
#include "cli/cli.h"
#include "fit/model_fit.h"
#include "models/key_reader.h"
#include "models/merl_file.h"
#include "plot/plot.h"

namespace brdfbake {
namespace {

struct FitOptions {
    fit::ModelFitRequest request;
    std::string precision = "double";
    std::string format = "table";
    std::string output;
    std::string plot;
};

std::string render(const FitOptions& o, const fit::ModelFitResult& r) {
    const Format format = parse_format(o.format);
    const fit::ModelFitRequest& q = o.request;
    std::ostringstream out;
    if (format == Format::Json) {
        nlohmann::json j;
        j["command"] = "fit";
        j["target"] = q.target;
        j["metric"] = q.metric;
        j["fresnel"] = q.amplitude;
        j["pairs"] = r.pairs;
        j["all_pairs"] = r.all_pairs;
        j["unmeasured_bins"] = r.unmeasured_bins;
        j["channels"] = nlohmann::json::array();
        for (const fit::ChannelFit& c : r.channels) {
            nlohmann::json params = nlohmann::json::object();
            for (const fit::FittedParameter& p : c.params) params[p.name] = {{"value", p.value}, {"error", p.error}};
            j["channels"].push_back({{"channel", c.channel},
                                     {"model", c.model_spec},
                                     {"fresnel", c.fresnel_spec},
                                     {"params", params},
                                     {"distance", c.distance},
                                     {"distance_fit_pairs", c.distance_fit},
                                     {"unmeasured_share", c.unmeasured_share},
                                     {"evaluations", c.evaluations},
                                     {"budget", c.budget},
                                     {"converged", c.converged}});
        }
        out << j.dump(2) << "\n";
        return out.str();
    }
    if (format == Format::Csv) {
        out << "channel,parameter,value,error,distance,distance_fit_pairs,unmeasured_share,evaluations,model,fresnel\n";
        for (const fit::ChannelFit& c : r.channels)
            for (const fit::FittedParameter& p : c.params)
                out << c.channel << "," << p.name << "," << round_trip_text(p.value) << "," << round_trip_text(p.error)
                    << "," << round_trip_text(c.distance) << "," << round_trip_text(c.distance_fit) << ","
                    << round_trip_text(c.unmeasured_share) << "," << c.evaluations << ",\"" << c.model_spec << "\",\""
                    << c.fresnel_spec << "\"\n";
        return out.str();
    }
    out << "# fit of " << q.model << " with --fresnel " << q.amplitude << " to " << q.target << "\n";
    out << "# metric " << q.metric << ": sqrt of the pair-measure-weighted mean square of g(f_fit cos) - g(f_target cos)"
        << " over the measured bins; fitted on " << r.pairs << " pairs (stride " << q.stride << "), distance on all "
        << r.all_pairs << " pairs above the horizon";
    if (r.unmeasured_bins) out << "; the file has " << r.unmeasured_bins << " unmeasured bins";
    out << "\n# parameter +- its standard error (the sandwich estimate with the residuals read as noise, and the optimiser's stop)\n";
    out << "# channel  parameter        value        error     distance  (fit pairs)  unmeasured  evaluations\n";
    char line[256];
    for (const fit::ChannelFit& c : r.channels)
        for (size_t i = 0; i < c.params.size(); ++i) {
            const fit::FittedParameter& p = c.params[i];
            if (i == 0)
                std::snprintf(line, sizeof line, "  %-7s %-9s %12.6f %12.2e %12.4e %12.4e %10.2e %12d\n",
                              c.channel.empty() ? "-" : c.channel.c_str(), p.name.c_str(), p.value, p.error,
                              c.distance, c.distance_fit, c.unmeasured_share, c.evaluations);
            else
                std::snprintf(line, sizeof line, "  %-7s %-9s %12.6f %12.2e\n", "", p.name.c_str(), p.value, p.error);
            out << line;
        }
    for (const fit::ChannelFit& c : r.channels)
        if (!c.converged)
            out << "# " << (c.channel.empty() ? "the fit" : "channel " + c.channel) << " stopped at its budget of "
                << c.budget << " evaluations per start before the minimiser converged (raise --max-evaluations)\n";
    for (const fit::ChannelFit& c : r.channels)
        out << (c.channel.empty() ? "" : c.channel + ": ") << "--model " << c.model_spec << " --fresnel "
            << c.fresnel_spec << "\n";
    return out.str();
}

/// --plot: f cos(theta_o) of the target (dashed) and of the fit (solid) per channel in the plane
/// of incidence, theta_o signed (positive on the mirror side), at theta_i = 30, 60 and 80 deg.
void plot_fit(Engine& engine, const FitOptions& o, const fit::ModelFitResult& r) {
    constexpr double kDeg = 3.14159265358979323846 / 180;
    const FresnelConfig target_fresnel = resolve_fresnel(o.request.target_fresnel);
    const FresnelConfig none = resolve_fresnel("none");
    const Precision precision = o.precision == "double" ? Precision::Double : Precision::Float;
    Figure fig;
    fig.panel_width = 640;
    fig.panel_height = 520;
    for (double theta_i : {30.0, 60.0, 80.0}) {
        PlotSpec p;
        p.title = "\\theta_i = " + std::to_string(int(theta_i)) + "\\deg";
        p.x.label = "\\theta_{o} (degrees, + on the mirror side)";
        p.y.label = "f cos \\theta_{o}";
        p.legend = LegendPlace::TopLeft;  // the lobes peak on the mirror side (right)
        p.x.lo = -90;
        p.x.hi = 90;
        std::vector<Vec3> wo, wi;
        std::vector<double> x;
        for (int k = -89; k <= 89; ++k) {
            wo.push_back({std::sin(k * kDeg), 0.0, std::cos(k * kDeg)});
            wi.push_back({-std::sin(theta_i * kDeg), 0.0, std::cos(theta_i * kDeg)});
            x.push_back(k);
        }
        for (const fit::ChannelFit& c : r.channels) {
            const std::string colour = c.channel == "r" ? "r" : c.channel == "g" ? "g" : c.channel == "b" ? "b" : "k";
            const std::string target = c.channel.empty() ? o.request.target : merl_channel_spec(o.request.target, c.channel);
            const ModelConfig tm = resolve_model(target);
            std::vector<double> ft = evaluate_on_device(engine, tm, tm.uses_fresnel ? target_fresnel : none, precision, wo, wi);
            std::vector<double> ff = evaluate_on_device(engine, resolve_model(c.model_spec), resolve_fresnel(c.fresnel_spec),
                                                        precision, wo, wi);
            for (size_t k = 0; k < wo.size(); ++k) {
                ft[k] *= wo[k][2];
                ff[k] *= wo[k][2];
            }
            const std::string name = c.channel.empty() ? "" : " " + c.channel;
            p.curves.push_back({"target" + name, x, ft, colour + ";2"});
            p.curves.push_back({"fit" + name, x, ff, colour + "-2"});
        }
        fig.panels.push_back(p);
    }
    write_figure(o.plot, fig);
}

int run_fit(const FitOptions& o, const GlobalOptions& g) {
    if (o.request.target.empty()) throw Error("give --target SPEC, e.g. --target merl:file=gold.binary");
    fit::ModelFitRequest request = o.request;
    request.precision = o.precision == "double" ? Precision::Double : Precision::Float;
    parse_format(o.format);
    fit::check_model_fit_request(request);
    check_text_output(o.output);
    check_plot_output(o.plot, "--plot");
    Engine engine(g.device, g.verbose);
    const fit::ModelFitResult result = fit::fit_model(engine, request);
    if (!o.plot.empty()) plot_fit(engine, o, result);
    emit(o.output, render(o, result));
    for (const fit::ChannelFit& c : result.channels)  // every format: never a silent stop
        if (!c.converged)
            std::fprintf(stderr, "brdfbake: warning: the fit%s stopped at its budget of %d evaluations per start before "
                         "converging (--max-evaluations)\n", c.channel.empty() ? "" : (" of channel " + c.channel).c_str(),
                         c.budget);
    return kExitOk;
}

}  // namespace

void add_fit_command(CLI::App& app, const GlobalOptions& global, Action& action) {
    const auto [cmd, o] = add_command<FitOptions>(
        app, "fit", "fit an analytic model's alpha (or alpha_x, alpha_y) and Fresnel parameters per channel, with standard errors, to a measured (MERL) or any BRDF", global,
        action, run_fit);
    cmd->add_option("--target,--data", o->request.target, "the BRDF to fit: merl:file=PATH[,channel=r|g|b|y] or any model spec")
        ->required();
    cmd->add_option("--target-fresnel", o->request.target_fresnel, "the Fresnel term of an analytic --target")
        ->capture_default_str();
    cmd->add_option("--model", o->request.model, "the fitted model without alpha: ggx, beckmann (keys allowed)")
        ->capture_default_str();
    std::string amplitudes;
    for (const fit::FitAmplitude& a : fit::fit_amplitudes())
        amplitudes += std::string(amplitudes.empty() ? "" : "; ") + a.name + ": " + a.description;
    cmd->add_option("--fresnel", o->request.amplitude, "the fitted Fresnel term: " + amplitudes)->capture_default_str();
    std::string metrics;
    for (const fit::FitMetric& m : fit::fit_metrics()) metrics += std::string(metrics.empty() ? "" : "; ") + m.name + ": " + m.description;
    cmd->add_option("--metric", o->request.metric, "the fit's distance: " + metrics)->capture_default_str();
    cmd->add_option("--stride", o->request.stride,
                    "fit on every N-th bin along theta_h and theta_d and every 2N-th along phi_d (the distance is "
                    "reported on all bins)")
        ->capture_default_str();
    cmd->add_flag("--anisotropic", o->request.anisotropic,
                  "fit alpha_x and alpha_y (automatic when the --target model is anisotropic; not for MERL files)");
    cmd->add_flag("--diffuse", o->request.diffuse,
                  "fit a Lambert weight kd beside the lobe (the model's diffuse=KD: f = f_spec + kd/pi; ggx, beckmann)");
    cmd->add_option("--max-evaluations", o->request.max_evaluations,
                    "objective evaluations per start (default 0: 200 + 100 n^2 for n free parameters); a fit the budget "
                    "stops says so")
        ->capture_default_str();
    add_precision_option(cmd, o->precision);
    add_format_option(cmd, o->format, {"table", "json", "csv"});
    cmd->add_option("-o,--output", o->output, "write the result here (default: standard output)");
    cmd->add_option("--plot", o->plot, "draw f cos(theta_o) of the target and the fit at theta_i = 30, 60, 80 deg (.png or .svg)");
}

}  // namespace brdfbake
