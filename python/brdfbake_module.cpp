// The Python module `brdfbake`: the core library's functions over numpy arrays. Every call goes
// to the same code the command line runs (resolve_model / resolve_fresnel for the specs,
// albedo_of_model, compute_lut, fresnel_on_device, run_check, evaluate_on_device, write_table);
// this file only converts arguments and results, releases the GIL while kernels run and turns
// Ctrl-C into a stop at the next kernel launch.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <algorithm>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <type_traits>

#include "brdfbake/albedo.h"
#include "brdfbake/api.h"
#include "brdfbake/analytic.h"
#include "brdfbake/cancel.h"
#include "brdfbake/check.h"
#include "brdfbake/engine.h"
#include "brdfbake/error.h"
#include "brdfbake/evaluate.h"
#include "brdfbake/memory_limit.h"
#include "brdfbake/fresnel_curve.h"
#include "brdfbake/fresnel_terms.h"
#include "brdfbake/lut.h"
#include "brdfbake/spec.h"
#include "brdfbake/table.h"
#include "brdfbake/table_kinds.h"
#include "brdfbake/version.h"
#include "models/key_reader.h"

namespace py = pybind11;
using namespace brdfbake;

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// One engine per device selector, created on first use and kept (kernel programs stay built).
Engine& engine_for(const std::optional<std::string>& device) {
    static std::map<std::string, std::unique_ptr<Engine>> engines;
    const std::string key = device.value_or("");
    auto& e = engines[key];
    if (!e) e = std::make_unique<Engine>(key, false);
    return *e;
}

/// Runs `work` on a worker thread with the GIL released; the calling thread checks for signals
/// every 50 ms. On Ctrl-C the computation is asked to stop at its next kernel launch, and
/// KeyboardInterrupt is raised once it has.
template <typename Work>
auto interruptible(Work&& work) -> decltype(work()) {
    clear_cancel();
    auto future = std::async(std::launch::async, std::forward<Work>(work));
    bool interrupted = false;
    {
        py::gil_scoped_release release;
        while (future.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) {
            py::gil_scoped_acquire acquire;
            if (PyErr_CheckSignals() != 0) {  // sets KeyboardInterrupt (or the handler's exception)
                interrupted = true;
                request_cancel();
                py::gil_scoped_release wait;
                future.wait();
                break;
            }
        }
    }
    if (interrupted) {
        clear_cancel();
        throw py::error_already_set();
    }
    return future.get();
}

Precision precision_of(const std::string& name) {
    if (name == "float") return Precision::Float;
    if (name == "double") return Precision::Double;
    throw Error("precision must be 'float' or 'double'; got '" + name + "'");
}

py::array_t<double> to_array(const std::vector<double>& v, const std::vector<py::ssize_t>& shape) {
    py::array_t<double> a(shape);
    std::copy(v.begin(), v.end(), a.mutable_data());
    return a;
}

std::vector<py::ssize_t> shape_of(const py::array& a) { return {a.shape(), a.shape() + a.ndim()}; }

// ------------------------------------------------------------------ albedo

struct AlbedoOut {
    py::array_t<double> albedo, error;
    std::string model, fresnel, method, device;
    std::uint64_t samples = 0;
    double seconds = 0.0;
};

AlbedoOut python_albedo(const std::string& model_spec, const Array& mu, const std::optional<Array>& phi_deg,
                 const std::string& fresnel_spec, double wavelength, double samples, std::optional<double> tolerance,
                 const std::string& method, double max_samples, const std::string& precision,
                 const std::optional<std::string>& device) {
    const auto t0 = std::chrono::steady_clock::now();
    const ModelConfig model = resolve_model(model_spec);
    const FresnelConfig fresnel = resolve_fresnel(fresnel_spec, wavelength);
    if (fresnel.kind != 0 && !model.uses_fresnel)
        throw Error("model '" + model.name + "' has no Fresnel term; drop --fresnel");
    const MethodChoice choice = choose_method(method, samples, tolerance.value_or(0.0), max_samples);
    const size_t n = size_t(mu.size());
    if (n == 0) throw Error("mu is empty");
    // phi broadcasts against mu: one value, or one per mu.
    std::vector<double> phis(n, 0.0);
    if (phi_deg) {
        if (phi_deg->size() == 1)
            std::fill(phis.begin(), phis.end(), phi_deg->data()[0]);
        else if (size_t(phi_deg->size()) == n)
            phis.assign(phi_deg->data(), phi_deg->data() + n);
        else
            throw Error("phi must be one value or one per mu");
    }
    AlbedoRequest req;
    req.model = model.id;
    req.fresnel = fresnel;
    req.samples = choice.samples;
    req.method = choice.method;
    req.precision = precision_of(precision);
    for (size_t i = 0; i < n; ++i) {
        const double m = mu.data()[i];
        if (!(m > 0.0 && m <= 1.0))
            throw Error("mu: " + format_number(m) + " is out of range; mu = cos(theta_o) must lie in (0, 1]");
        req.cells.push_back(AlbedoCell{m, azimuth_from_degrees(phis[i]), model.params});
    }
    Engine& engine = engine_for(device);
    const AlbedoResult r =
        interruptible([&] { return albedo_of_model(engine, model, fresnel, req, choice.tolerance); });
    const AlbedoValues v = albedo_values(r, model, fresnel, engine.device().name,
                                         std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    AlbedoOut out;
    out.albedo = to_array(v.albedo, shape_of(mu));
    out.error = to_array(v.error, shape_of(mu));
    out.model = v.model;
    out.fresnel = v.fresnel;
    out.method = v.method;
    out.samples = v.samples;
    out.device = v.device;
    out.seconds = v.seconds;
    return out;
}

// ------------------------------------------------------------------ tables

/// Values as (height, width, channels) for a 2D table, (depth, height, width, channels) with an
/// eta axis, (width, channels) for a 1D one: numpy's C order, x fastest, as the files store them.
std::vector<py::ssize_t> table_shape(const Table& t, bool with_channels) {
    std::vector<py::ssize_t> s;
    if (t.depth() > 1) s.push_back(t.depth());
    if (t.height() > 1 || t.depth() > 1) s.push_back(t.height());
    s.push_back(t.width());
    if (with_channels) s.push_back(py::ssize_t(t.channels.size()));
    return s;
}

py::array_t<double> table_values(const Table& t) {
    const size_t texels = t.error.size(), nc = t.channels.size();
    std::vector<double> v(texels * nc);
    for (size_t i = 0; i < texels; ++i)
        for (size_t c = 0; c < nc; ++c) v[i * nc + c] = t.values[c][i];
    return to_array(v, table_shape(t, true));
}

py::dict axis_dict(const Axis& a) {
    py::dict d;
    d["name"] = a.name;
    d["mapping"] = a.mapping;
    d["parameter_name"] = a.parameter_name.empty() ? a.name : a.parameter_name;
    d["texels"] = texels_name(a.texels);
    d["lo"] = a.lo;
    d["hi"] = a.hi;
    d["size"] = a.size;
    d["coordinate"] = to_array(a.coordinate, {py::ssize_t(a.coordinate.size())});
    d["parameter"] = to_array(a.parameter, {py::ssize_t(a.parameter.size())});
    return d;
}

py::list table_axes(const Table& t) {
    py::list axes;
    axes.append(axis_dict(t.x));
    if (t.height() > 1 || t.depth() > 1) axes.append(axis_dict(t.y));
    if (t.depth() > 1) axes.append(axis_dict(t.z));
    return axes;
}

std::vector<int> size_list(const py::object& size) {
    if (py::isinstance<py::int_>(size)) return {size.cast<int>()};
    try {
        return size.cast<std::vector<int>>();
    } catch (const py::cast_error&) {
        throw Error("size must be an int or a tuple of 1 to 3 ints");
    }
}

template <typename T>
using Opt = std::optional<T>;

/// The names of a registry's entries (entries or pointers to them), in its order.
template <typename Entries, typename Entry, typename Name>
std::vector<std::string> names_of(const Entries& entries, Name Entry::*name) {
    std::vector<std::string> names;
    for (const auto& e : entries) {
        if constexpr (std::is_pointer_v<std::decay_t<decltype(e)>>)
            names.push_back(e->*name);
        else
            names.push_back(e.*name);
    }
    return names;
}

/// As `brdfbake lut`: every argument given (not None) is the option of the same name, merged
/// with the preset by the core's apply_preset; `output` writes the table as -o does (with the
/// preset's --half unless half is given).
Table python_lut(Opt<std::string> kind, Opt<std::string> model, const py::object& size, Opt<std::string> preset,
          Opt<std::string> estimator, Opt<std::string> fresnel, Opt<double> wavelength, Opt<std::string> mu_map,
          Opt<std::string> alpha_map, Opt<std::vector<double>> alpha_range, Opt<std::vector<double>> mu_range,
          Opt<double> mu_floor, Opt<std::vector<double>> eta_range, Opt<std::string> eta_map,
          Opt<std::string> texels, Opt<std::vector<std::string>> axes, Opt<std::vector<std::string>> flip,
          Opt<double> samples, Opt<double> tolerance, Opt<std::string> method, Opt<double> max_samples,
          Opt<std::string> precision, Opt<bool> half, Opt<std::string> colour_space, Opt<bool> rgb_wavelengths,
          Opt<std::string> output, const Opt<std::string>& device, Opt<std::vector<double>> thickness_range,
          Opt<double> thickness_step) {
    if (rgb_wavelengths.value_or(false) && colour_space)
        throw Error("rgb_wavelengths takes R, G, B at 650, 550 and 450 nm, not a colour space; drop one of them");
    const Opt<std::string> colour = rgb_wavelengths.value_or(false) ? Opt<std::string>("wavelengths") : colour_space;
    const Opt<std::vector<int>> dims = size.is_none() ? std::nullopt : Opt<std::vector<int>>(size_list(size));
    // In LutSettings' order: each field the argument of its name.
    const LutSettings given{kind,     preset,    model,       estimator, fresnel,  wavelength,  dims,
                            mu_map,   alpha_map, eta_map,     texels,    alpha_range, eta_range, mu_range,
                            mu_floor, axes,      flip,        samples,   tolerance, max_samples, method,
                            precision, half,     colour,      thickness_range, thickness_step};
    const LutSetup setup = apply_preset(given);
    validate_lut(setup.request);  // every input checked before the device is touched
    if (output) check_table_format(lut_table_shape(setup.request), *output);  // before the compute
    Engine& engine = engine_for(device);
    Table table = interruptible([&] { return compute_lut(engine, setup.request); });
    if (output) write_table(table, *output, setup.half);
    return table;
}

// ------------------------------------------------------------------ fresnel, check, eval

py::dict fresnel(const std::string& spec, const Array& theta_deg, double wavelength, const std::string& precision,
                 const std::optional<std::string>& device) {
    const FresnelConfig f = resolve_fresnel(spec, wavelength);
    std::vector<double> cosines;
    for (py::ssize_t i = 0; i < theta_deg.size(); ++i) {
        const double t = theta_deg.data()[i];
        if (!(t >= 0.0 && t <= 90.0))
            throw Error("theta_deg: " + std::to_string(t) + " is out of range; angles of incidence lie in [0, 90] degrees");
        cosines.push_back(std::sin((90.0 - t) * (M_PI / 180.0)));  // exact 1 at 0 and 0 at 90 degrees
    }
    Engine& engine = engine_for(device);
    const FresnelCurves c = interruptible([&] { return fresnel_on_device(engine, f, precision_of(precision), cosines); });
    py::dict d;
    d["fresnel"] = f.canonical;
    d["F"] = to_array(c.f, shape_of(theta_deg));
    d["Rs"] = to_array(c.rs, shape_of(theta_deg));
    d["Rp"] = to_array(c.rp, shape_of(theta_deg));
    return d;
}

py::dict check(const std::string& model_spec, const std::string& fresnel_spec, double wavelength, int directions,
               double samples, const std::string& precision, double energy_tolerance, int resolution,
               double reciprocity_tolerance, const std::optional<std::string>& device) {
    const ModelConfig model = resolve_model(model_spec);
    const FresnelConfig fresnel = resolve_fresnel(fresnel_spec, wavelength);
    if (fresnel.kind != 0 && !model.uses_fresnel)
        throw Error("model '" + model.name + "' has no Fresnel term; drop --fresnel");
    if (!(samples >= 1.0)) throw Error("samples must be a positive number");
    CheckOptions o;
    o.directions = directions;
    o.samples = std::uint64_t(samples);
    o.precision = precision_of(precision);
    o.energy_tolerance = energy_tolerance;
    o.resolution = resolution;
    o.reciprocity_tolerance = reciprocity_tolerance;
    Engine& engine = engine_for(device);
    const CheckReport r = interruptible([&] { return run_check(engine, model, fresnel, o); });
    py::dict energy, reciprocity, values, d;
    energy["max_albedo"] = r.max_albedo;
    energy["error"] = r.max_albedo_error;
    energy["mu"] = r.max_albedo_mu;
    energy["phi_deg"] = r.max_albedo_phi * 180.0 / M_PI;
    energy["analytic"] = r.furnace_analytic;
    energy["violation"] = r.energy_violation;
    reciprocity["max_relative_error"] = r.max_rel;
    reciprocity["theta_i_deg"] = r.max_rel_theta_i * 180.0 / M_PI;
    reciprocity["theta_o_deg"] = r.max_rel_theta_o * 180.0 / M_PI;
    reciprocity["tolerance"] = r.reciprocity_tolerance;
    reciprocity["pairs"] = r.pairs;
    reciprocity["nonfinite"] = r.scan_nonfinite;
    reciprocity["violation"] = r.scan_nonfinite > 0 ? py::object(py::none()) : py::bool_(r.reciprocity_violation);
    values["nonfinite"] = r.nonfinite;
    values["min_value"] = r.min_value;
    values["violation"] = r.value_violation;
    d["model"] = r.model;
    d["fresnel"] = r.fresnel;
    d["energy"] = energy;
    d["reciprocity"] = reciprocity;
    d["values"] = values;
    d["passed"] = r.passed();
    return d;
}

// How far from length 1 a direction may be: float32 unit vectors are within about 1e-7.
constexpr double kUnitTolerance = 1e-5;
// Pairs evaluated per device call: the device's buffers stay small whatever the arrays' size.
constexpr size_t kEvalChunk = size_t(1) << 20;

void check_directions_shape(const Array& a, const char* name) {
    if (a.ndim() < 1 || a.shape(a.ndim() - 1) != 3)
        throw Error(std::string(name) + " must be an array of unit vectors with a last axis of 3");
}

/// Directions [from, to) of `a`: each finite and of length 1 within kUnitTolerance (then
/// normalised exactly); anything else is refused (ValueError) naming the index and the vector.
std::vector<Vec3> directions_of(const Array& a, const char* name, size_t from, size_t to) {
    std::vector<Vec3> out(to - from);
    for (size_t i = from; i < to; ++i) {
        const double* v = a.data() + 3 * i;
        const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]) ||
            !(std::fabs(length - 1.0) <= kUnitTolerance)) {
            char b[256];
            std::snprintf(b, sizeof b, "%s[%zu] = (%g, %g, %g) is not a unit vector (%s); eval takes finite directions "
                          "of length 1 (within %g), and does not normalise them", name, i, v[0], v[1], v[2],
                          std::isfinite(length) ? ("length " + std::to_string(length)).c_str() : "not finite",
                          kUnitTolerance);
            throw Error(b);
        }
        for (int k = 0; k < 3; ++k) out[i - from][k] = v[k] / length;
    }
    return out;
}

py::array_t<double> eval(const std::string& model_spec, const Array& wo, const Array& wi,
                         const std::string& fresnel_spec, double wavelength, const std::string& precision,
                         const std::optional<std::string>& device) {
    const ModelConfig model = resolve_model(model_spec);
    const FresnelConfig fresnel = resolve_fresnel(fresnel_spec, wavelength);
    if (fresnel.kind != 0 && !model.uses_fresnel)
        throw Error("model '" + model.name + "' has no Fresnel term; drop --fresnel");
    if (wo.ndim() != wi.ndim() || !std::equal(wo.shape(), wo.shape() + wo.ndim(), wi.shape()))
        throw Error("wo and wi must have the same shape");
    check_directions_shape(wo, "wo");
    check_directions_shape(wi, "wi");
    const size_t n = size_t(wo.size() / 3);
    for (size_t from = 0; from < n; from += kEvalChunk) {  // every input checked before any work
        directions_of(wo, "wo", from, std::min(n, from + kEvalChunk));
        directions_of(wi, "wi", from, std::min(n, from + kEvalChunk));
    }
    // The result (a vector, then the array it becomes) and one chunk's directions and device
    // buffers (about 200 bytes a pair).
    check_memory(16.0 * double(n) + 200.0 * double(std::min(n, kEvalChunk)),
                 "eval of " + std::to_string(n) + " direction pairs");
    Engine& engine = engine_for(device);
    std::vector<double> f;
    f.reserve(n);
    for (size_t from = 0; from < n; from += kEvalChunk) {
        const size_t to = std::min(n, from + kEvalChunk);
        const std::vector<Vec3> o = directions_of(wo, "wo", from, to), i = directions_of(wi, "wi", from, to);
        const std::vector<double> part =
            interruptible([&] { return evaluate_on_device(engine, model, fresnel, precision_of(precision), o, i); });
        f.insert(f.end(), part.begin(), part.end());
    }
    std::vector<py::ssize_t> shape = shape_of(wo);
    shape.pop_back();
    return to_array(f, shape);
}

// ------------------------------------------------------------------ argument checks

/// A parameter of a bound function, as its signature line spells it: name, type, whether it has
/// a default.
struct Parameter {
    std::string name, type;
    bool optional = false;
};

/// The parameters of `function` from the signature pybind11 writes on the first line of its
/// docstring ("albedo(model: str, mu: numpy.ndarray[numpy.float64], phi: ... = None, ...) -> ..."),
/// so that the py::arg lists stay the one place that names them.
std::vector<Parameter> parameters_of(const py::object& function) {
    const std::string doc = py::str(function.attr("__doc__"));
    std::vector<Parameter> params;
    size_t at = doc.find('(') + 1;
    int depth = 0;
    std::string piece;
    auto flush = [&] {
        const size_t colon = piece.find(':');
        if (colon == std::string::npos) return;
        Parameter p;
        p.name = piece.substr(piece.find_first_not_of(' '), colon - piece.find_first_not_of(' '));
        const size_t eq = piece.find(" = ");
        p.type = piece.substr(colon + 2, eq == std::string::npos ? std::string::npos : eq - colon - 2);
        p.optional = eq != std::string::npos;
        params.push_back(p);
        piece.clear();
    };
    for (; at < doc.size(); ++at) {
        const char c = doc[at];
        if (depth == 0 && c == ')') break;
        if (c == '[' || c == '(') ++depth;
        if (c == ']' || c == ')') --depth;
        if (depth == 0 && c == ',') {
            flush();
            continue;
        }
        piece += c;
    }
    flush();
    return params;
}

[[noreturn]] void type_error(const std::string& message) { throw py::type_error(message); }

/// A number given as text: refused, as Python refuses 1 + "0.5" (numpy would read "0.5" as 0.5).
void check_number_argument(const std::string& function, const Parameter& p, const py::handle& value) {
    const bool numeric = p.type.find("str") == std::string::npos &&
                         (p.type.find("float") != std::string::npos || p.type.find("int") != std::string::npos);
    if (!numeric || value.is_none()) return;
    if (py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value))
        type_error(function + "(): " + p.name + " must be a number" +
                   (p.type.find("ndarray") != std::string::npos ? " or an array of numbers" : "") + ", not the string " +
                   std::string(py::repr(value)));
    if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value) || py::isinstance<py::array>(value)) {
        const py::object array = py::module_::import("numpy").attr("asarray")(value);
        const std::string kind = py::str(array.attr("dtype").attr("kind"));
        if (kind != "f" && kind != "i" && kind != "u" && kind != "b")
            type_error(function + "(): " + p.name + " must be numbers, not an array of " +
                       std::string(py::str(array.attr("dtype"))));
    }
}

/// Checks a call's arguments against `params` before pybind11 sees them: one line per mistake,
/// naming the Python argument (a mistyped keyword with the nearest name), instead of pybind11's
/// list of every signature.
void check_call(const std::string& function, const std::vector<Parameter>& params, const py::args& args,
                const py::kwargs& kwargs) {
    if (args.size() > params.size())
        type_error(function + "() takes at most " + std::to_string(params.size()) + " positional arguments (" +
                   std::to_string(args.size()) + " given)");
    std::vector<std::string> names;
    for (const Parameter& p : params) names.push_back(p.name);
    std::vector<bool> given(params.size(), false);
    for (size_t i = 0; i < args.size(); ++i) {
        given[i] = true;
        check_number_argument(function, params[i], py::object(args[i]));
    }
    for (const auto& item : kwargs) {
        const std::string key = py::str(item.first);
        const auto it = std::find(names.begin(), names.end(), key);
        if (it == names.end()) {
            const std::string hint = did_you_mean(key, names);
            std::string list;
            for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
            type_error(function + "() got an unexpected keyword argument '" + key + "'" +
                       (hint.empty() ? "; its arguments: " + list : hint));
        }
        const size_t i = size_t(it - names.begin());
        if (given[i]) type_error(function + "() got multiple values for argument '" + key + "'");
        given[i] = true;
        check_number_argument(function, params[i], item.second);
    }
    for (size_t i = 0; i < params.size(); ++i)
        if (!given[i] && !params[i].optional) type_error(function + "() missing required argument '" + params[i].name + "'");
}

/// Defines `name` on `m` as `typed` behind check_call; a type pybind11 still refuses gets one
/// line naming the arguments' types. The docstring is `typed`'s, with its signature.
void def_checked(py::module_& m, const char* name, const py::cpp_function& typed) {
    const std::vector<Parameter> params = parameters_of(typed);
    const std::string function = name;
    const std::string doc = py::str(typed.attr("__doc__"));
    const py::object call = typed;  // captured as an object: cpp_function's own constructor would wrap it
    m.def(
        name,
        [function, params, call](const py::args& args, const py::kwargs& kwargs) -> py::object {
            check_call(function, params, args, kwargs);
            try {
                return call(*args, **kwargs);
            } catch (py::error_already_set& e) {
                if (!e.matches(PyExc_TypeError) || std::string(e.what()).find("incompatible function arguments") ==
                                                       std::string::npos)
                    throw;
                std::string given;
                for (size_t i = 0; i < args.size(); ++i)
                    given += (given.empty() ? "" : ", ") + params[i].name + ": " +
                             std::string(py::str(py::type::of(py::object(args[i])).attr("__name__")));
                for (const auto& item : kwargs)
                    given += (given.empty() ? "" : ", ") + std::string(py::str(item.first)) + ": " +
                             std::string(py::str(py::type::of(item.second).attr("__name__")));
                type_error(function + "(): an argument has the wrong type (given " + given + "); see help(brdfbake." +
                           function + ")");
            }
        },
        doc.c_str());
}

}  // namespace

PYBIND11_MODULE(brdfbake, m) {
    m.doc() =
        "brdfbake: integrate BRDFs in OpenCL kernels (PoCL by default) from Python. Model and Fresnel specs are "
        "the command line's (`ggx:alpha=0.5`, `schlick:f0=0.04`); angles are degrees, mu = cos(theta).";
    m.attr("__version__") = BRDFBAKE_VERSION;

    // Bad input is ValueError with the command line's message; a violation found (a tolerance
    // not met, exit status 1 on the command line) and device faults are RuntimeError.
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const Error& e) {
            // The library speaks the command line's flags; here they are arguments: "--mu-map" is mu_map.
            std::string message = e.what();
            for (size_t at = message.find("--"); at != std::string::npos; at = message.find("--", at)) {
                size_t end = at + 2;
                while (end < message.size() && (std::isalnum((unsigned char)message[end]) || message[end] == '-')) {
                    if (message[end] == '-') message[end] = '_';
                    ++end;
                }
                message.erase(at, 2);
            }
            if (e.exit_code() == kExitViolation)
                PyErr_SetString(PyExc_RuntimeError, message.c_str());
            else
                PyErr_SetString(PyExc_ValueError, message.c_str());
        } catch (const cl::Error& e) {
            PyErr_SetString(PyExc_RuntimeError,
                            (std::string("OpenCL call ") + e.what() + " failed: " + cl_error_name(e.err())).c_str());
        }
    });

    py::class_<AlbedoOut>(m, "Albedo", "directional albedo E(mu) with its error, arrays of mu's shape")
        .def_readonly("albedo", &AlbedoOut::albedo)
        .def_readonly("error", &AlbedoOut::error)
        .def_readonly("model", &AlbedoOut::model)
        .def_readonly("fresnel", &AlbedoOut::fresnel)
        .def_readonly("method", &AlbedoOut::method)
        .def_readonly("samples", &AlbedoOut::samples, "samples per direction (the most any direction took)")
        .def_readonly("device", &AlbedoOut::device)
        .def_readonly("seconds", &AlbedoOut::seconds)
        .def("__repr__", [](const AlbedoOut& a) {
            return "<brdfbake.Albedo " + a.model + ", " + std::to_string(a.albedo.size()) + " directions>";
        });

    py::class_<Table>(m, "Table", "a lookup table: values, per-texel error, axes and the brdfbake:* attributes")
        .def_readonly("kind", &Table::kind)
        .def_readonly("quantity", &Table::quantity)
        .def_readonly("channels", &Table::channels)
        .def_property_readonly("values", &table_values,
                               "(height, width, channels); (depth, height, width, channels) with an eta axis; "
                               "(width, channels) for a 1D table")
        .def_property_readonly(
            "error", [](const Table& t) { return to_array(t.error, table_shape(t, false)); },
            "estimated absolute error per texel (the largest over the channels), values' shape without channels")
        .def_property_readonly("axes", &table_axes, "x (width), then y (height), then z (depth): dicts of name, "
                                                    "mapping, lo, hi, size, coordinate, parameter")
        .def_readonly("attributes", &Table::attributes)
        .def("max_error", &Table::max_error)
        .def(
            "save", [](const Table& t, const std::string& path, bool half) { write_table(t, path, half); },
            py::arg("path"), py::arg("half") = false,
            "write by the extension of path, as `brdfbake lut -o`: .exr, .csv, .h, .png (16-bit), .npy")
        .def("__repr__", [](const Table& t) {
            return "<brdfbake.Table " + t.kind + " " + std::to_string(t.width()) + "x" + std::to_string(t.height()) +
                   "x" + std::to_string(t.depth()) + ">";
        });

    def_checked(m, "albedo", py::cpp_function(&python_albedo, py::name("albedo"), py::arg("model"), py::arg("mu"), py::arg("phi") = py::none(),
          py::arg("fresnel") = "none", py::arg("wavelength") = 0.0, py::arg("samples") = double(1 << 18),
          py::arg("tolerance") = py::none(), py::arg("method") = "auto", py::arg("max_samples") = double(1 << 26),
          py::arg("precision") = "float", py::arg("device") = py::none(),
          "directional albedo E(mu) = integral of f cos(theta_i) over the hemisphere, as `brdfbake albedo`; phi in "
          "degrees (one value or one per mu); tolerance refines every direction to that absolute error"));
    def_checked(m, "lut", py::cpp_function(&python_lut, py::name("lut"), py::arg("kind") = py::none(), py::arg("model") = py::none(), py::arg("size") = py::none(),
          py::arg("preset") = py::none(), py::arg("estimator") = py::none(), py::arg("fresnel") = py::none(),
          py::arg("wavelength") = py::none(),
          py::arg("mu_map") = py::none(), py::arg("alpha_map") = py::none(), py::arg("alpha_range") = py::none(),
          py::arg("mu_range") = py::none(), py::arg("mu_floor") = py::none(), py::arg("eta_range") = py::none(),
          py::arg("eta_map") = py::none(), py::arg("texels") = py::none(), py::arg("axes") = py::none(),
          py::arg("flip") = py::none(), py::arg("samples") = py::none(), py::arg("tolerance") = py::none(),
          py::arg("method") = py::none(), py::arg("max_samples") = py::none(), py::arg("precision") = py::none(),
          py::arg("half") = py::none(), py::arg("colour_space") = py::none(), py::arg("rgb_wavelengths") = py::none(),
          py::arg("output") = py::none(), py::arg("device") = py::none(), py::arg("thickness_range") = py::none(),
          py::arg("thickness_step") = py::none(),
          "a lookup table as `brdfbake lut KIND`: size is N, (W, H) or (W, H, D); preset names an engine's layout "
          "(the arguments given override it); output writes the table as -o does; every other argument is the "
          "option of the same name"));
    def_checked(m, "read_table", py::cpp_function(&read_table, py::name("read_table"), py::arg("path"),
          "a table brdfbake wrote (.exr, .csv, .npy with its .json), as a Table"));
    m.def("presets", [] { return names_of(lut_presets(), &LutPreset::name); },
          "the engines' table layouts (lut(preset=...))");
    def_checked(m, "fresnel", py::cpp_function(&fresnel, py::name("fresnel"), py::arg("spec"), py::arg("theta_deg"), py::arg("wavelength") = 0.0,
          py::arg("precision") = "float", py::arg("device") = py::none(),
          "F, Rs and Rp of a Fresnel spec at angles of incidence in degrees (dict of arrays)"));
    def_checked(m, "check", py::cpp_function(&check, py::name("check"), py::arg("model"), py::arg("fresnel") = "none", py::arg("wavelength") = 0.0,
          py::arg("directions") = 48, py::arg("samples") = double(1 << 16), py::arg("precision") = "float",
          py::arg("energy_tolerance") = 1e-4, py::arg("resolution") = 32, py::arg("reciprocity_tolerance") = 1e-6,
          py::arg("device") = py::none(),
          "white furnace, reciprocity and value scans with a verdict, as `brdfbake check` (a dict)"));
    def_checked(m, "eval", py::cpp_function(&eval, py::name("eval"), py::arg("model"), py::arg("wo"), py::arg("wi"), py::arg("fresnel") = "none",
          py::arg("wavelength") = 0.0, py::arg("precision") = "double", py::arg("device") = py::none(),
          "f(wo, wi) without the cosine, on the device, for arrays of unit vectors (..., 3) in the shading frame "
          "(normal +z)"));
    m.def("models", [] { return names_of(model_registry(), &ModelTraits::name); }, "the model names of the registry");
    m.def("fresnel_terms", [] { return names_of(fresnel_terms(), &FresnelTerm::name); },
          "the Fresnel term names of the registry (fresnel=NAME:...)");
    m.def("table_kinds", [] { return names_of(table_kinds(), &TableKind::name); }, "the table kinds of the registry");
}
