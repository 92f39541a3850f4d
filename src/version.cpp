#include "strictmin/version.h"

namespace strictmin {

std::string_view version() { return STRICTMIN_VERSION; }

}  // namespace strictmin
