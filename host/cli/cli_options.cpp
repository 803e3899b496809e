// Options shared by the commands: how much work an integration does, by which method, or to
// which tolerance; the kernels' arithmetic; the output format.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "brdfbake/error.h"
#include "brdfbake/fresnel_terms.h"
#include "brdfbake/output.h"
#include "cli/cli.h"
#include "models/key_reader.h"
#include "plot/plot.h"

namespace brdfbake {

const CLI::Validator kPositive(
    [](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !(v > 0.0) || !std::isfinite(v))
            return "must be a positive number, got '" + text + "'";
        return "";
    },
    "POSITIVE");

const CLI::Validator kNonNegative(
    [](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !(v >= 0.0) || !std::isfinite(v))
            return "must be a number of 0 or more, got '" + text + "'";
        return "";
    },
    "NONNEGATIVE");

namespace {

/// `text` as a whole decimal (base 0: also 0x hex, as CLI11 reads it) integer, if it is one.
bool plain_integer(const std::string& text, long long& value, int base = 0) {
    if (text.empty() || std::isspace((unsigned char)text[0])) return false;
    char* end = nullptr;
    errno = 0;
    value = std::strtoll(text.c_str(), &end, base);
    return *end == '\0' && errno != ERANGE;
}

/// base^exponent (power) or base * 2^exponent (shift), exponent >= 0, if it fits in a long long.
bool integer_power(long long base, long long exponent, bool shift, long long& value) {
    if (shift ? base == 0 : std::llabs(base) <= 1) {  // no growth: 0 << n, 0^n, 1^n, (-1)^n
        value = shift ? 0 : base == 0 ? (exponent == 0 ? 1 : 0) : (base == -1 && exponent % 2 ? -1 : 1);
        return true;
    }
    if (exponent > 64) return false;
    const long long limit = std::numeric_limits<long long>::max();
    value = shift ? base : 1;
    for (long long i = 0; i < exponent; ++i) {
        const long long factor = shift ? 2 : base;
        if (factor != 0 && std::llabs(value) > limit / std::llabs(factor)) return false;
        value *= factor;
    }
    return true;
}

}  // namespace

std::string integer_text(const std::string& text, const std::string& what) {
    const std::string wanted = what + ": must be an integer (e.g. 1000000, 1e6, 2^20 or 1<<20), got '" + text + "'";
    long long value = 0;
    if (plain_integer(text, value)) return text;
    const size_t caret = text.find('^'), shift = text.find("<<");
    if (caret != std::string::npos || shift != std::string::npos) {
        const bool is_shift = shift != std::string::npos;
        const size_t at = is_shift ? shift : caret;
        long long base = 0, exponent = 0;
        if (!plain_integer(text.substr(0, at), base, 10) || !plain_integer(text.substr(at + (is_shift ? 2 : 1)), exponent, 10))
            throw Error(wanted);
        if (exponent < 0) throw Error(wanted);
        if (!integer_power(base, exponent, is_shift, value)) throw Error(what + ": '" + text + "' is too large for an integer");
        return std::to_string(value);
    }
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(v) || v != std::floor(v)) throw Error(wanted);
    if (std::fabs(v) >= 9.2e18) throw Error(what + ": '" + text + "' is too large for an integer");
    return std::to_string((long long)v);
}

void accept_integer_forms(CLI::App& app) {
    for (CLI::Option* option : app.get_options()) {
        const std::string type = option->get_type_name();
        if (type.rfind("INT", 0) != 0 && type.rfind("UINT", 0) != 0) continue;
        option->transform(CLI::Validator(
            [](std::string& text) -> std::string {
                try {
                    text = integer_text(text, "");
                } catch (const Error& e) {
                    return std::string(e.what()).substr(2);  // less the empty name's ": "
                }
                return "";
            },
            ""));
    }
    for (CLI::App* sub : app.get_subcommands({})) accept_integer_forms(*sub);
}

std::string unknown_option_message(CLI::App& app, const std::vector<std::string>& arguments) {
    CLI::App* command = nullptr;
    if (!arguments.empty()) {
        for (CLI::App* sub : app.get_subcommands({}))
            if (sub->get_name() == arguments[0]) command = sub;
    }
    std::vector<std::string> known;
    for (CLI::App* scope : {command, &app}) {
        if (!scope) continue;
        for (const CLI::Option* option : scope->get_options()) {
            for (const std::string& n : option->get_lnames()) known.push_back("--" + n);
            for (const std::string& n : option->get_snames()) known.push_back("-" + n);
        }
    }
    for (const std::string& word : arguments) {
        if (word == "--") break;
        if (word.size() < 2 || word[0] != '-' || std::isdigit((unsigned char)word[1]) || word[1] == '.') continue;
        const std::string name = word[1] == '-' ? word.substr(0, word.find('=')) : word.substr(0, 2);
        if (std::find(known.begin(), known.end(), name) != known.end()) continue;
        const std::string where = command ? "brdfbake " + command->get_name() : std::string("brdfbake");
        const std::string hint = did_you_mean(name, known);
        return "unknown option '" + name + "' of `" + where + "`" +
               (hint.empty() ? "; see " + where + " --help" : hint);
    }
    return "";
}

void add_method_options(CLI::App* cmd, MethodOptions& o, const std::string& per) {
    CLI::Option* s = cmd->add_option("--samples", o.samples,
                                     "samples per " + per + " (quadrature: n = sqrt(samples/4) nodes per axis of the finer rule, n^2 per azimuth piece; "
                                     "the rough dielectric's up to n = 32: a Gauss-Kronrod rule of at most 2n - 1 points, 15 to 61)")
                         ->capture_default_str();
    cmd->add_option("--method", o.method,
                    "integration method: importance (the model's sampler, randomised Hammersley), qmc and mc "
                    "(uniform hemisphere, randomised Hammersley or Philox), quadrature (Gauss-Legendre, in "
                    "half-vector space for microfacet lobes); auto: importance with --samples, the engine's "
                    "per-cell choice with --tolerance")
        ->check(CLI::IsMember({"auto", "importance", "qmc", "mc", "quadrature"}))
        ->capture_default_str();
    cmd->add_option("--tolerance", o.tolerance,
                    "absolute error to reach in every " + per + " instead of a fixed sample count: each is refined "
                    "until its error estimate is at most this")
        ->check(kPositive)  // 0 is "not given": a given 0 (or -0) is refused, not ignored
        ->excludes(s);
    cmd->add_option("--max-samples", o.max_samples, "with --tolerance: the most samples to spend on one " + per)
        ->capture_default_str();
}

MethodChoice resolve_method_choice(const MethodOptions& o) {
    return choose_method(o.method, double(o.samples), o.tolerance, double(o.max_samples));
}

void check_plot_output(const std::string& path, const std::string& option) {
    if (path.empty()) return;
    if (!is_plot_path(path)) throw Error(option + " must end in .png or .svg");
    check_output_path(path);
}

void check_text_output(const std::string& path) {
    if (!path.empty() && path != "-") check_output_path(path);
}

std::string fresnel_spec_help() { return "Fresnel spec: " + fresnel_spec_forms(); }

void add_colour_space_option(CLI::App* cmd, std::string& colour_space, const std::string& description) {
    cmd->add_option("--colour-space", colour_space, description)
        ->check(CLI::IsMember({"srgb", "acescg"}))
        ->capture_default_str();
}

void add_precision_option(CLI::App* cmd, std::string& precision, const std::string& description) {
    cmd->add_option("--precision", precision, description)
        ->check(CLI::IsMember({"float", "double"}))
        ->capture_default_str();
}

void add_format_option(CLI::App* cmd, std::string& format, const std::vector<std::string>& formats) {
    cmd->add_option("--format", format, "output format")->check(CLI::IsMember(formats))->capture_default_str();
}

}  // namespace brdfbake
