// Footprint assembly through tiles (texture/footprint_assembly_filter.h says why it is compiled
// here, apart from the in-memory instance).
#include "texture/footprint_assembly_filter.h"

namespace footprint::detail {

template void filter_footprint_assembly(const TiledTexels&, float, float, const FootprintEllipse&,
                                        const LookupOptions&, float*);

}  // namespace footprint::detail
