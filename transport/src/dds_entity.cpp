#include "rpsd/transport/dds_entity.h"

namespace rpsd::transport {

dds_return_t dds_check(dds_return_t rc, const std::string& what) {
  if (rc < 0) throw DdsError(what + ": " + dds_strretcode(rc));
  return rc;
}

}  // namespace rpsd::transport
