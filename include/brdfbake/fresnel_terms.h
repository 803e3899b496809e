// The Fresnel registry (host/models/fresnel_spec.cpp) as help texts, docs and checks see it: the
// Fresnel terms a spec may name, their forms and meanings. resolve_fresnel (brdfbake/spec.h)
// resolves a spec against the same entries.
#pragma once

#include <string>
#include <vector>

namespace brdfbake {

/// A Fresnel term of the registry.
struct FresnelTerm {
    std::string name;         // spec name, e.g. "schlick"
    std::string form;         // the spec with its keys, e.g. "schlick:f0=F0", "metal:Ag|Al|Au|Cu"
    std::string description;  // what F is, in one line
    bool measured;            // F depends on --wavelength: tabulated n, k, or a thin film's interference
    int kind;                 // the kernels' BB_FRESNEL_* (brdf/fresnel.h) it resolves to
};

/// Every Fresnel term, in help order.
const std::vector<FresnelTerm>& fresnel_terms();
/// "none, schlick:f0=F0, ...": every term's form, for help texts and messages.
std::string fresnel_spec_forms();
/// The name of the first term resolving to the kernels' kind (BB_FRESNEL_*): "conductor" for
/// metal:Al too, "gen-schlick" for f82-tint; "unknown" for no term.
std::string fresnel_kind_name(int kind);
/// Whether a Fresnel spec names a term whose F depends on the wavelength: a measured one
/// (metal:X, nk:FILE) or a thin film.
bool fresnel_needs_wavelength(const std::string& spec);
/// The kernels' kind (BB_FRESNEL_*) of the term a spec names, read from the registry without
/// resolving the spec (no file is read); -1 for a name the registry does not know.
int fresnel_kind_of(const std::string& spec);
/// Whether the spec's argument is a file path (nk:FILE), which a scene resolves beside itself.
bool fresnel_reads_file(const std::string& spec);

}  // namespace brdfbake
