#include "brdfbake/error.h"
#include "brdfbake/lut.h"
#include "brdfbake/table_kinds.h"

namespace brdfbake {

void set_lut_size(LutRequest& r, const std::vector<int>& dims) {
    if (dims.empty()) throw Error("--size: give N, WIDTHxHEIGHT or WIDTHxHEIGHTxDEPTH");
    // An unknown kind is reported by validate_lut; its size is read as 2D meanwhile.
    const TableKind* kind = find_table_kind(r.kind);
    const bool three = kind && kind->eta_axis, one = kind && kind->one_dimensional;
    if (dims.size() > (three ? 3u : 2u)) throw Error("--size: too many dimensions for a " + r.kind + " table");
    r.width = dims[0];
    r.height = dims.size() > 1 ? dims[1] : (one ? 1 : dims[0]);
    if (three) r.depth = dims.size() > 2 ? dims[2] : r.height;
    if (one && r.height != 1) throw Error("--size: an " + r.kind + " table is 1D; give N or Nx1");
}

}  // namespace brdfbake
