#include <footprint/version.h>

namespace footprint {

const char* version() {
    return FOOTPRINT_VERSION_STRING;
}

}  // namespace footprint
