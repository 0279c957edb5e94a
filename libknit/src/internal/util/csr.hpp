// util/csr.hpp — compressed-row (offsets) arrays: element e owns items [offsets[e], offsets[e+1]).
// Used for Polylines, yarns, cell -> triangle lists and vertex -> face lists (internal).
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

namespace knit::util {

// True when `offsets` spans `items` items in `rows` rows: rows + 1 entries, starting at 0 and
// ending at `items` (their order is not checked: for callers that name the first decreasing row).
template <class Offset>
bool offsetEnds(const std::vector<Offset>& offsets, size_t rows, size_t items) {
    return offsets.size() == rows + 1 && offsets.front() == 0 && size_t(offsets.back()) == items;
}

// True when `offsets` describes `rows` rows over `items` items: rows + 1 entries, starting at 0,
// never decreasing, ending at `items`.
template <class Offset>
bool validOffsets(const std::vector<Offset>& offsets, size_t rows, size_t items) {
    return offsetEnds(offsets, rows, items) && std::is_sorted(offsets.begin(), offsets.end());
}

// Counts to offsets, in place (an exclusive prefix sum): on entry offsets[r + 1] holds row r's
// item count and offsets[0] is 0; on return offsets[r] is row r's first item and offsets.back()
// the total. The usual way to build a CSR array: count, countsToOffsets, then fill each row.
template <class Offset>
void countsToOffsets(std::vector<Offset>& offsets) {
    for (size_t r = 1; r < offsets.size(); ++r) offsets[r] += offsets[r - 1];
}

}  // namespace knit::util
