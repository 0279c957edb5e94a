// The deformation a scene gets when its caller leaves the choice open (knit/strain.hpp,
// decideDeform): one rule for the command line, Python and Blender.
#include "knit/error.hpp"
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
    if (choice == DeformChoice::Auto) {
        d.cached = findCachedStrainTable(pattern, options);
        if (!d.cached.table) {
            // The estimate relaxes the rest cell and one sample: it also finds a pattern that
            // cannot have a table (open yarns), which Auto leaves geometric instead of failing.
            try {
                d.deform.tableSeconds = estimateStrainTableSeconds(pattern, options);
            } catch (const Error& e) {
                d.deform.reason = DeformReason::CannotMake;
                d.whyNot = e.what();
                return d;
            }
            if (!strainTableIsQuick(pattern, options)) {
                d.deform.reason = DeformReason::TooSlowToMake;
                return d;
            }
        }
    }
    if (!d.cached.table) d.cached = cachedStrainTable(pattern, options, make);
    d.deform = {DeformMode::Strain, d.cached.table, d.cached.made ? DeformReason::Made : DeformReason::Cached,
                d.cached.seconds};
    return d;
}

}  // namespace knit
