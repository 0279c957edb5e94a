// Statistical image match for renderer tests: two renders of the same view with independent noise
// (different seeds) agree "within the noise of their sample count" when neither statistic of
// knit::compareImages rejects at significance alpha:
//   * chi-square: sum over blocks of z^2 ~ chi^2(testedBlocks) (local differences: missing
//     pieces, caps, seams). Conservative for heavy-tailed path-tracing noise (self-normalised
//     sums have E[z^2] <= 1), so it never rejects more often than alpha under the null.
//   * meanZ: the whole-image mean difference over its standard error ~ N(0, 1) (a global
//     brightness offset, the most sensitive test for e.g. a systematically darker mode).
// With k comparisons in a test, alpha per statistic bounds the family-wise false failure rate by
// 2 k alpha (Bonferroni).
#pragma once
#include <cmath>
#include <ostream>

#include <boost/math/special_functions/gamma.hpp>

#include "knit/image_io.hpp"

namespace knit {

struct ImageMatch {
    ImageComparison comparison;
    double pChiSquare = 1, pMean = 1;
    bool within(double alpha) const { return pChiSquare >= alpha && pMean >= alpha; }
};

inline ImageMatch matchImages(const Image& a, const Image& b, int block = 8) {
    ImageMatch m;
    m.comparison = compareImages(a, b, block, 4.0);
    const ImageComparison& c = m.comparison;
    m.pChiSquare = c.testedBlocks > 0 ? boost::math::gamma_q(c.testedBlocks / 2.0, c.chiSquare / 2.0) : 1.0;
    m.pMean = std::erfc(std::abs(c.meanZ) / std::sqrt(2.0));
    return m;
}

inline std::ostream& operator<<(std::ostream& out, const ImageMatch& m) {
    const ImageComparison& c = m.comparison;
    return out << "chi2 " << c.chiSquare << " over " << c.testedBlocks << " blocks (p " << m.pChiSquare << "), mean z "
               << c.meanZ << " (p " << m.pMean << "), max block z " << c.maxZ;
}

}  // namespace knit
