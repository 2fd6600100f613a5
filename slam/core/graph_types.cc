#include "slam/core/graph_types.h"

#include "slam/core/graph_types_json.h"

namespace duskmap {

const char* LinkTypeName(LinkType type) { return JsonEnumName(type); }

}  // namespace duskmap
