// SPDX-License-Identifier: Apache-2.0
// phasor — the named render-time counters (core/render/integrator.h, RenderEvent): one table of keys
// and messages.
#include "core/render/integrator.h"

namespace phasor {

const RenderEventInfo &Describe(RenderEvent e) {
    static const RenderEventInfo table[] = {
        {"footprint_after_spread_free",
         "path vertices met an aperture after another aperture; it acted geometrically (only the first "
         "footprint-aware kernel on a path diffracts)"},
        {"specular_after_spread_free",
         "path vertices scattered specularly after an aperture; delta lights (plane waves, point, spot, "
         "directional, laser beams) are not reached through such a surface, so their light behind it is "
         "missing (theory §9 item 5)"},
        {"lobe_average_capped",
         "lobe averages needed more than 256 quadrature nodes per axis to prove their bound of 3e-4 of the "
         "lobe's peak (films of tens of µm under sources of several degrees, or a film met within a degree "
         "of grazing, where its efficiency turns fastest; theory §4.11), or more than 20 per axis at the "
         "edge of a source disc wider than 10 times the ray's angular spread; their error is unproven there "
         "(measured: ≤ 2.3e-4 relative for films up to 100 µm under 10° discs, docs/accuracy.md §3); a "
         "thinner layer or a smaller source stays within the bound"},
    };
    static_assert(std::size(table) == std::size_t(RenderEvent::Count), "one entry per RenderEvent");
    return table[std::size_t(e)];
}

std::vector<std::string> RenderCounters::Warnings() const {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < n.size(); ++i)
        if (n[i] > 0) out.push_back(std::to_string(n[i]) + " " + Describe(RenderEvent(i)).message);
    return out;
}

void RenderCounters::ToMetadata(std::map<std::string, std::string> &metadata) const {
    for (std::size_t i = 0; i < n.size(); ++i) {
        const std::string key = std::string("phasor:count:") + Describe(RenderEvent(i)).key;
        if (n[i] > 0) metadata[key] = std::to_string(n[i]);
        else metadata.erase(key);
    }
}

}  // namespace phasor
