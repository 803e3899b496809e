#include "brdfbake/error.h"
#include "brdfbake/lut.h"
#include "brdfbake/table_kinds.h"

namespace brdfbake {

namespace {

/// The axes of a kind, in --size order, for messages: "mu x alpha x eta".
std::string axes_of(const TableKind& kind) {
    if (kind.one_dimensional) return "alpha";
    const std::string z = kind.own_z_axis.empty() ? "eta" : kind.own_z_axis;
    return kind.eta_axis ? "mu x alpha x " + z : "mu x alpha";
}

}  // namespace

void set_lut_size(LutRequest& r, const std::vector<int>& dims) {
    if (dims.empty()) throw Error("--size: give N, WIDTHxHEIGHT or WIDTHxHEIGHTxDEPTH");
    // An unknown kind is reported by validate_lut; its size is read as 2D meanwhile.
    const TableKind* kind = find_table_kind(r.kind);
    const bool three = kind && kind->eta_axis, one = kind && kind->one_dimensional;
    // N (the same on every axis) or one size per axis; a 1D kind also takes Nx1. A 3D kind given
    // two sizes is refused rather than given a depth the user did not ask for.
    const size_t axes = three ? 3 : one ? 1 : 2;
    if (dims.size() != 1 && dims.size() != axes && !(one && dims.size() == 2)) {
        const std::string form = three ? "WIDTHxHEIGHTxDEPTH" : one ? "N or Nx1" : "WIDTHxHEIGHT";
        const bool vowel = std::string("aeiou").find(r.kind[0]) != std::string::npos;
        throw Error("--size: " + std::string(vowel ? "an " : "a ") + r.kind + " table has " + std::to_string(axes) + " ax" + (axes == 1 ? "is" : "es") +
                    " (" + (kind ? axes_of(*kind) : "mu x alpha") + "); give N (the same on every axis)" +
                    (one ? "" : " or " + form));
    }
    r.width = dims[0];
    r.height = dims.size() > 1 ? dims[1] : (one ? 1 : dims[0]);
    if (three) r.depth = dims.size() > 2 ? dims[2] : r.height;
    if (one && r.height != 1) throw Error("--size: an " + r.kind + " table is 1D; give N or Nx1");
}

}  // namespace brdfbake
