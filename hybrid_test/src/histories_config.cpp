#include "rpsd/hybrid_test/histories_config.h"

namespace rpsd::hybrid_test {

const char* kept_name(HistoriesConfig::Kept kept) {
  switch (kept) {
    case HistoriesConfig::Kept::kAll:
      return "all";
    case HistoriesConfig::Kept::kCriteriaOnly:
      return "criteria_only";
    case HistoriesConfig::Kept::kDecimated:
      return "decimated";
  }
  return "all";
}

}  // namespace rpsd::hybrid_test
