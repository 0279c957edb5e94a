// The deformation a scene gets when its caller leaves the choice open (knit/strain.hpp,
// decideDeform): one rule for the command line, Python and Blender.
#include "knit/strain.hpp"

namespace knit {

bool strainTableIsQuick(const Pattern& pattern, const StrainTableOptions& options) {
    const double samples = double(options.samples[0]) * options.samples[1] * options.samples[2];
    return double(pattern.points.size()) * samples <= kQuickStrainTableWork;
}

DeformDecision decideDeform(const Pattern& pattern, DeformChoice choice, std::shared_ptr<const StrainTable> given,
                            const std::function<StrainTable()>& make) {
    DeformDecision d;
    if (choice == DeformChoice::None) return d;  // geometric, as asked
    if (given) {
        d.deform = {DeformMode::Strain, std::move(given),
                    choice == DeformChoice::Strain ? DeformReason::Asked : DeformReason::TableGiven};
        return d;
    }
    const StrainTableOptions options;
    if (choice == DeformChoice::Auto && !strainTableIsQuick(pattern, options)) {
        d.cached = findCachedStrainTable(pattern, options);
        if (!d.cached.table) {
            d.deform.tableSeconds = estimateStrainTableSeconds(pattern, options);
            d.deform.reason = DeformReason::TooSlowToMake;
            return d;
        }
    } else {
        d.cached = cachedStrainTable(pattern, options, make);
    }
    d.deform = {DeformMode::Strain, d.cached.table, d.cached.made ? DeformReason::Made : DeformReason::Cached,
                d.cached.seconds};
    return d;
}

}  // namespace knit
